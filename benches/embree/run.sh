#!/usr/bin/env bash
# Ray casting, steradian's BVH vs Embree 3, on the same mesh and the same rays in one run.
#
#   benches/embree/run.sh [--rounds N] [--threads 1,2] [--meshes sphere1m,bunny] [--work DIR]
#
# 1. installs Debian's libembree-dev (Embree 3.13.5) if missing and builds bench.cpp;
# 2. fetches the Stanford bunny (the PLY inside the pymeshfix 0.18.1 wheel) with pip;
# 3. makes the 1M-triangle cube-sphere and the bunny ray sets with `bench --export` (primary,
#    diffuse, bounce, shadow; 4M rays each) and Embree's per-ray results (--dump-hits);
# 4. builds `cargo run --release --example raycast` (for the host CPU, as .cargo/config.toml sets;
#    the node and triangle kernels still pick AVX2 or scalar code at run time);
# 5. alternates, N rounds: Embree traces the sets (rtcIntersect1/rtcOccluded1) on 1 and 2
#    threads, then steradian traces the same files and compares every ray with Embree's result;
# 6. prints the table (summary.py): the best round of each, Mrays/s, ratio, and the same
#    divided by the measured CPU utilisation (robust when the machine is shared).
# Data and logs go to --work (default /tmp/steradian-embree). Needs ~1.2 GB there.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
work=/tmp/steradian-embree
rounds=3
threads=1,2
meshes=sphere1m,bunny
while [ $# -gt 0 ]; do
    case "$1" in
        --rounds) rounds="$2"; shift 2 ;;
        --threads) threads="$2"; shift 2 ;;
        --meshes) meshes="$2"; shift 2 ;;
        --work) work="$2"; shift 2 ;;
        -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
        *) echo "run.sh: unknown argument '$1'" >&2; exit 1 ;;
    esac
done
mkdir -p "$work/data"
cd "$work"

if [ ! -e /usr/include/embree3/rtcore.h ]; then
    echo "== installing libembree-dev"
    apt-get update -qq && apt-get install -y -qq libembree-dev
fi
if [ ! -x bench ] || [ "$here/bench.cpp" -nt bench ]; then
    echo "== building the Embree benchmark"
    g++ -O3 -march=native -std=c++17 -Wall -Wextra -o bench "$here/bench.cpp" -lembree3 -pthread
fi
if [ ! -s data/StanfordBunny.ply ]; then
    echo "== fetching the Stanford bunny"
    tmp=$(mktemp -d)
    "${PIP:-pip3}" download --no-deps --only-binary=:all: --dest "$tmp" "pymeshfix==0.18.1" >/dev/null
    python3 - "$tmp" <<'PY'
import glob, sys, zipfile
whl = glob.glob(sys.argv[1] + "/pymeshfix-*.whl")[0]
with zipfile.ZipFile(whl) as z:
    open("data/StanfordBunny.ply", "wb").write(z.read("pymeshfix/examples/StanfordBunny.ply"))
PY
    rm -rf "$tmp"
fi

# the mesh source of each name, as bench.cpp takes it
source_args() {
    case "$1" in
        sphere1m) echo "--gen sphere --tris 1000000 --diffuse-side random --name sphere1m" ;;
        bunny) echo "--mesh data/StanfordBunny.ply --name bunny" ;;
        *) echo "run.sh: unknown mesh '$1'" >&2; exit 1 ;;
    esac
}

for m in ${meshes//,/ }; do
    if [ ! -s "data/$m.shadow.rays" ] || [ ! -s "data/$m.embree.shadow.hits" ]; then
        echo "== exporting $m"
        # shellcheck disable=SC2046
        ./bench $(source_args "$m") --export "data/$m" --modes 1 --threads 1 --dump-hits "data/$m.embree" > "export-$m.log"
    fi
done

echo "== building steradian's raycast example"
(cd "$repo" && cargo build --release --locked --example raycast)
raycast="$repo/target/release/examples/raycast"

log="$work/run-$(date -u +%Y%m%dT%H%M%S).log"
{
    echo "# $(date -u) $(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg)"
    grep -m1 'model name' /proc/cpuinfo
} | tee "$log"
for r in $(seq 1 "$rounds"); do
    for m in ${meshes//,/ }; do
        echo "== round $r/$rounds: $m (load $(cut -d' ' -f1-3 /proc/loadavg))"
        # shellcheck disable=SC2046
        ./bench $(source_args "$m") --rays-in "data/$m" --modes 1 --threads "$threads" | sed "s/^/round=$r /" | tee -a "$log"
        "$raycast" --data "data/$m" --name "$m" --reference "data/$m.embree" --threads "$threads" | sed "s/^/round=$r /" | tee -a "$log"
    done
done
echo "# end load: $(cut -d' ' -f1-3 /proc/loadavg)" | tee -a "$log"
python3 "$here/summary.py" "$log"
echo "log: $log"
