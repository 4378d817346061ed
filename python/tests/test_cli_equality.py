"""The array from Python equals the `steradian render` command's EXR, bit for bit, and the
`steradian measure` command's reading exactly."""

import json
import subprocess

import numpy as np
import pytest

import steradian
from conftest import CORNELL, DISK_METER


def run(cli, *args):
    out = subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    return out.stdout


@pytest.mark.parametrize(
    "spp, seed, sensor, quantity, res",
    [
        (4, 0, None, "radiance", 256),  # the README's example: the built-in scene as it is
        (3, 17, "top-down", "radiance", 64),
        (2, 5, "top-down", "irradiance", 64),
    ],
)
def test_render_equals_cli_exr(cli, tmp_path, spp, seed, sensor, quantity, res):
    exr = tmp_path / "cli.exr"
    args = ["render", CORNELL, "-o", exr, "--spp", spp, "--seed", seed, "--quiet", "-D", f"res={res}"]
    if sensor:
        args += ["--sensor", sensor]
    args += ["--quantity", quantity]
    run(cli, *args)
    from_cli = steradian.read_exr(exr)
    from_python = steradian.load_file(CORNELL, res=res).render(spp=spp, seed=seed, sensor=sensor, quantity=quantity)
    assert from_python.shape == from_cli.shape == (res, res, 3)
    assert from_python.dtype == from_cli.dtype == np.float32
    assert np.array_equal(from_python, from_cli), f"max difference {np.abs(from_python - from_cli).max()}"
    # and bitwise (array_equal would call -0.0 and 0.0 equal)
    assert from_python.tobytes() == from_cli.tobytes()


def test_adaptive_render_equals_cli_exr(cli, tmp_path):
    """An adaptive render (its pilot, densities and weighted samples) is the same in both."""
    exr = tmp_path / "cli.exr"
    out = run(cli, "render", CORNELL, "-o", exr, "--spp", 8, "--seed", 3, "--quiet", "-D", "res=32",
              "--allocation", "adaptive")
    assert "allocation: a pilot of 4 spp" in out and ": adaptive," in out, out
    scene = steradian.load_file(CORNELL, res=32)
    from_python = scene.render(spp=8, seed=3, allocation="adaptive")
    assert from_python.tobytes() == steradian.read_exr(exr).tobytes()
    uniform = scene.render(spp=8, seed=3, allocation="uniform")
    assert not np.array_equal(uniform, from_python)
    with pytest.raises(ValueError, match="allocation must be"):
        scene.render(spp=8, allocation="smart")


def test_measure_equals_cli_measure(cli):
    reading = json.loads(run(cli, "measure", DISK_METER, "--spp", 5000, "--seed", 3, "--json"))
    m = steradian.load_file(DISK_METER).measure(spp=5000, seed=3)
    # the command prints shortest round-trip decimals: the same doubles
    assert list(m.value) == reading["value"]
    assert list(m.stderr) == reading["stderr"]
    assert m.unit == reading["unit"] and m.spp == reading["spp"] == 5000
