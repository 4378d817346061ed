"""Shared fixtures of the Python test suite (run by scripts/test.sh against `pip install .`)."""

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENES = REPO / "scenes"
CORNELL = SCENES / "cornell-box.xml"
DISK_METER = SCENES / "validation" / "disk_on_axis_irradiance.xml"


@pytest.fixture(scope="session")
def cli() -> Path:
    """The `steradian` command: $STERADIAN_CLI (scripts/test.sh sets it to the binary that
    `cargo test` built), else target/release/steradian. Missing is a failure, never a skip: the
    Python-vs-CLI tests are part of the acceptance criteria."""
    env = os.environ.get("STERADIAN_CLI")
    path = Path(env) if env else REPO / "target" / "release" / "steradian"
    if not path.is_file():
        pytest.fail(
            f"the steradian binary is missing at {path}: run `cargo build --release -p steradian-cli` "
            "or set STERADIAN_CLI (scripts/test.sh does both)"
        )
    return path
