"""The type stubs (`_steradian.pyi`, `radiometry.pyi`) against the built module."""

import ast
import inspect
import subprocess
import sys
from pathlib import Path

import steradian
import steradian._steradian as ext
import steradian.radiometry

PACKAGE = Path(steradian.__file__).parent


def mypy(*args, cwd):
    return subprocess.run([sys.executable, "-m", "mypy", *args], capture_output=True, text=True, cwd=cwd, timeout=600)


def test_stub_files_are_installed():
    for name in ("_steradian.pyi", "radiometry.pyi", "py.typed"):
        assert (PACKAGE / name).is_file(), name


def test_stubtest_finds_the_stubs_match_the_module(tmp_path):
    # names, parameter names, kinds and defaults, final classes, __all__
    out = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "steradian"], capture_output=True, text=True, cwd=tmp_path, timeout=600
    )
    assert out.returncode == 0, out.stdout + out.stderr


def test_every_stub_function_signature_matches_inspect():
    """Independent of stubtest: parse the .pyi and compare parameter lists with the runtime's
    __text_signature__."""
    for stub, module in (("_steradian.pyi", ext), ("radiometry.pyi", steradian.radiometry)):
        tree = ast.parse((PACKAGE / stub).read_text())
        stub_names = set()
        for node in tree.body:
            if isinstance(node, ast.FunctionDef):
                stub_names.add(node.name)
                params = [a.arg for a in node.args.posonlyargs + node.args.args + node.args.kwonlyargs]
                runtime = [
                    p.name
                    for p in inspect.signature(getattr(module, node.name)).parameters.values()
                    if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL)
                ]
                assert params == runtime, (stub, node.name, params, runtime)
            elif isinstance(node, ast.ClassDef):
                stub_names.add(node.name)
                cls = getattr(module, node.name)
                for item in node.body:
                    if isinstance(item, ast.FunctionDef):
                        assert hasattr(cls, item.name), (node.name, item.name)
        public = {n for n in module.__all__}
        assert public <= stub_names | {"radiometry"}, public - stub_names


TYPED_USE = """
from typing import Optional

import numpy as np
import numpy.typing as npt
import steradian
from steradian.radiometry import cone_solid_angle

scene: steradian.Scene = steradian.load_file("scenes/cornell-box.xml", spp=4)
image: npt.NDArray[np.float32] = scene.render(spp=4, seed=1, sensor="top-down", quantity="irradiance")
m: steradian.Measurement = scene.measure(progress=lambda done, total: None)
value: npt.NDArray[np.float64] = m.value
steradian.write_exr("x.exr", image)
omega: float = cone_solid_angle(0.5) + steradian.radiometry.sphere_solid_angle(1.0, 2.0)
size: "tuple[int, int]" = scene.film_size(0)
try:
    steradian.load_string("<scene/>")
except steradian.SceneError as e:
    line: Optional[int] = e.line
"""


def test_mypy_strict_accepts_typed_use(tmp_path):
    (tmp_path / "use.py").write_text(TYPED_USE)
    out = mypy("--strict", "use.py", cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr


MISUSE = [
    ("steradian.load_file('s.xml').render(spp='4')", '"render" of "Scene" has incompatible type'),
    ("x: str = steradian.read_exr('a.exr')", "Incompatible types in assignment"),
    ("steradian.load_file('s.xml').render(quantity='luminance')", '"quantity"'),
    ("steradian.radiometry.cone_solid_angle('wide')", '"cone_solid_angle" has incompatible type'),
    ("steradian.load_file('s.xml').no_such_method()", '"Scene" has no attribute "no_such_method"'),
    ("steradian.load_file('s.xml').measure().value.upper()", "has no attribute \"upper\""),
]


def test_mypy_rejects_misuse(tmp_path):
    """The stubs are what mypy reads (not Any): each wrong use is a type error on its line."""
    (tmp_path / "bad.py").write_text("import steradian\n" + "\n".join(line for line, _ in MISUSE) + "\n")
    out = mypy("--strict", "bad.py", cwd=tmp_path)
    assert out.returncode == 1, out.stdout + out.stderr
    for number, (line, complaint) in enumerate(MISUSE, start=2):
        errors = [e for e in out.stdout.splitlines() if e.startswith(f"bad.py:{number}: error")]
        assert any(complaint in e for e in errors), (line, complaint, out.stdout)
