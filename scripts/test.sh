#!/usr/bin/env bash
# Runs every check of the project: formatting, clippy and rustdoc (warnings are errors), the Rust
# workspace's tests, then the Python package's pytest suite against a fresh `pip install .` in a
# virtual environment (.venv-test/, made when missing).
# Needs only a Rust toolchain (rustup) and Python >= 3.9 with venv; PyPI for maturin, numpy,
# pytest, mypy and ray. This is the README's test command and what .ci/run runs.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v cargo >/dev/null 2>&1; then
    # Rust comes from rustup on every machine of this project; make it visible if PATH lacks it.
    export PATH="$HOME/.cargo/bin:$PATH"
fi
PYTHON="${PYTHON:-python3}"
VENV=.venv-test

# rustup's default profile has rustfmt and clippy; a minimal one does not
if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
    rustup component add rustfmt clippy
fi

echo "== cargo fmt --all --check"
cargo fmt --all --check
echo "== cargo clippy --workspace --all-targets --locked -- -D warnings"
cargo clippy --workspace --all-targets --locked -- -D warnings
echo "== cargo doc --workspace --no-deps --locked (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked

echo "== cargo test --workspace --locked"
cargo test --workspace --locked

# The Python-vs-CLI comparison runs the `steradian` binary that `cargo test` has just built for
# the CLI's own tests (test profile): no second, release build of the renderer (~4 min on 2
# cores). The image is the same bit for bit in any profile (no fast-math; checked against the
# release binary too).
export STERADIAN_CLI="$PWD/target/debug/steradian"
if [ ! -x "$STERADIAN_CLI" ]; then
    echo "error: cargo test did not leave $STERADIAN_CLI" >&2
    exit 1
fi

echo "== Python package: $VENV, pip install ."
if [ ! -x "$VENV/bin/python" ]; then
    if ! "$PYTHON" -m venv "$VENV"; then
        # Debian's own Python ships venv separately (python3-venv)
        rm -rf "$VENV"
        if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
            apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv
            "$PYTHON" -m venv "$VENV"
        else
            echo "error: '$PYTHON -m venv' failed: install Python's venv module (Debian: python3-venv)" >&2
            exit 1
        fi
    fi
fi
export PATH="$PWD/$VENV/bin:$PATH"   # maturin's command must be on PATH for the build
# ray: the distributed renders' tests run on a local Ray (python/tests/test_distributed.py)
python -m pip install --quiet --disable-pip-version-check "maturin>=1.5,<2" numpy pytest mypy "ray>=2.9"
start=$SECONDS
# the build tools are in the venv already: no isolated build environment to download
python -m pip install --disable-pip-version-check --no-build-isolation --force-reinstall --no-deps .
echo "pip install . took $((SECONDS - start)) s"

echo "== pytest python/tests"
# run from python/tests' parent with the installed package, never the source tree's copy
python -m pytest python/tests -p no:cacheprovider -ra
