#!/usr/bin/env bash
# Builds the `steradian` binary with profile-guided optimisation (PGO) and prints its path,
# target/pgo/release/steradian.
#
#     bash scripts/build-pgo.sh
#
# 1. builds an instrumented binary (target/pgo-gen), which counts how often each branch and
#    call runs;
# 2. runs it on a training workload: the reference scenes that the speed benchmark does not
#    use (plastics, textures, furnace, pointlight), scenes/phong.xml, scenes/merl.xml and
#    benches/pgo/training.xml (glass, GGX conductors, spherical and spot lights);
# 3. merges the counts with the toolchain's own llvm-profdata (rustup component
#    `llvm-tools`, installed here if missing: the profile format follows rustc's LLVM) and
#    rebuilds with them (target/pgo).
#
# The merged profile stays in target/pgo-profiles/merged.profdata; the Python package can use
# it too: RUSTFLAGS="-C target-cpu=native -C profile-use=$PWD/target/pgo-profiles/merged.profdata" pip install .
#
# The benchmark scenes (cornell, materials, veach) are deliberately not in the training set.
# The optimisation changes code layout, inlining and branch order, never floating-point
# operations: the images are bit for bit those of `cargo build --release`. Measured gain:
# benches/README.md ("Profile-guided build"). Honours RUSTFLAGS (default: target-cpu=native, as
# .cargo/config.toml, which RUSTFLAGS replaces).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

host=$(rustc -vV | sed -n 's/^host: //p')
profdata="$(rustc --print sysroot)/lib/rustlib/$host/bin/llvm-profdata"
if [ ! -x "$profdata" ]; then
    rustup component add llvm-tools >&2
fi
if [ ! -x "$profdata" ]; then
    echo "build-pgo: llvm-profdata not found at $profdata (rustup component add llvm-tools)" >&2
    exit 1
fi

flags=${RUSTFLAGS:--C target-cpu=native}
profiles="$root/target/pgo-profiles"
rm -rf "$profiles"
mkdir -p "$profiles"

echo "build-pgo: 1/3 instrumented build" >&2
RUSTFLAGS="$flags -C profile-generate=$profiles" \
    cargo build --release --locked -p steradian-cli --target-dir target/pgo-gen >&2

echo "build-pgo: 2/3 training" >&2
bin="$root/target/pgo-gen/release/steradian"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
ref=crates/steradian-mitsuba/tests/reference
for scene in $ref/plastics.xml $ref/textures.xml $ref/furnace.xml $ref/pointlight.xml \
             scenes/phong.xml scenes/merl.xml benches/pgo/training.xml; do
    "$bin" render "$scene" --spp 8 -o "$out/train.exr" --quiet >&2
done

echo "build-pgo: 3/3 optimised build" >&2
"$profdata" merge -o "$profiles/merged.profdata" "$profiles"
RUSTFLAGS="$flags -C profile-use=$profiles/merged.profdata" \
    cargo build --release --locked -p steradian-cli --target-dir target/pgo >&2

echo "$root/target/pgo/release/steradian"
