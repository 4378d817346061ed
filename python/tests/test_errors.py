"""Errors surface as Python exceptions carrying the loader's file:line:col message."""

import numpy as np
import pytest

import steradian
from conftest import CORNELL


def write(tmp_path, text, name="bad.xml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_unknown_plugin_names_file_line_and_column(tmp_path):
    path = write(tmp_path, '<scene version="3.0.0">\n    <bsdf type="nosuch"/>\n</scene>\n')
    with pytest.raises(steradian.SceneError) as info:
        steradian.load_file(path)
    e = info.value
    assert isinstance(e, ValueError)
    assert str(e).startswith(f"{path}:2:5: error: ")
    assert "nosuch" in str(e)
    assert (e.file, e.line, e.column) == (str(path), 2, 5)
    assert "nosuch" in e.message and not e.message.startswith(str(path))


def test_unused_property_is_an_error(tmp_path):
    path = write(
        tmp_path,
        '<scene version="3.0.0">\n'
        '  <shape type="sphere">\n'
        '    <float name="radius" value="1"/>\n'
        '    <float name="radiuss" value="2"/>\n'
        "  </shape>\n"
        "</scene>\n",
    )
    with pytest.raises(steradian.SceneError, match="radiuss") as info:
        steradian.load_file(path)
    assert info.value.line == 4


def test_malformed_xml_from_a_string():
    with pytest.raises(steradian.SceneError) as info:
        steradian.load_string('<scene version="3.0.0">\n<shape type="sphere">\n</scene>')
    assert str(info.value).startswith("<string>:")
    assert info.value.file == "<string>" and info.value.line is not None


def test_missing_file_has_no_position(tmp_path):
    missing = tmp_path / "nope.xml"
    with pytest.raises(steradian.SceneError, match="nope.xml") as info:
        steradian.load_file(missing)
    assert str(info.value).startswith("error: ")
    assert info.value.line is None and info.value.column is None


def test_unused_default_override_is_an_error():
    with pytest.raises(steradian.SceneError, match="no_such_parameter"):
        steradian.load_file(CORNELL, no_such_parameter=3)


def test_missing_mesh_names_the_mesh(tmp_path):
    path = write(tmp_path, '<scene version="3.0.0">\n  <shape type="obj">\n    <string name="filename" value="gone.obj"/>\n  </shape>\n</scene>\n')
    with pytest.raises(steradian.SceneError, match="gone.obj"):
        steradian.load_file(path)


def test_bad_render_arguments():
    scene = steradian.load_file(CORNELL, res=8)
    with pytest.raises(ValueError, match="no sensor with id 'nope'.*top-down"):
        scene.render(spp=1, sensor="nope")
    with pytest.raises(ValueError, match="out of range"):
        scene.render(spp=1, sensor=2)
    with pytest.raises(ValueError, match="out of range"):
        scene.render(spp=1, sensor=-1)
    with pytest.raises(ValueError, match="spp"):
        scene.render(spp=0)
    with pytest.raises(ValueError, match="threads"):
        scene.render(spp=1, threads=0)
    with pytest.raises(ValueError, match="quantity"):
        scene.render(spp=1, quantity="luminance")
    with pytest.raises(TypeError):
        scene.render(spp="four")
    with pytest.raises(OverflowError):
        scene.render(spp=-1)


def test_a_scene_without_integrator_or_sensor():
    with pytest.raises(steradian.SceneError, match="no <integrator>"):
        steradian.load_string('<scene version="3.0.0"><shape type="sphere"/></scene>')
    scene = steradian.load_string('<scene version="3.0.0"><integrator type="path"/><shape type="sphere"/></scene>')
    assert scene.sensor_ids == []
    with pytest.raises(ValueError, match="no sensor"):
        scene.render(spp=1)
    with pytest.raises(ValueError, match="no sensor"):
        scene.measure(spp=1)


def test_exr_errors(tmp_path):
    with pytest.raises(OSError, match="missing.exr"):
        steradian.read_exr(tmp_path / "missing.exr")
    junk = tmp_path / "junk.exr"
    junk.write_bytes(b"not an exr")
    with pytest.raises(OSError, match="junk.exr"):
        steradian.read_exr(junk)
    with pytest.raises(ValueError, match=r"\(H, W, 3\)"):
        steradian.write_exr(tmp_path / "x.exr", np.zeros((4, 4)))
    with pytest.raises(OSError):
        steradian.write_exr(tmp_path / "no" / "such" / "dir.exr", np.zeros((2, 2, 3)))


def test_loader_warnings_are_user_warnings(tmp_path):
    path = write(
        tmp_path,
        '<scene version="3.0.0">\n'
        '  <integrator type="path"/>\n'
        '  <sensor type="perspective"/>\n'
        '  <shape type="sphere">\n'
        '    <bsdf type="diffuse"><rgb name="reflectance" value="1.2"/></bsdf>\n'
        "  </shape>\n"
        "</scene>\n",
        name="bright.xml",
    )
    with pytest.warns(UserWarning, match=r"bright\.xml:5:26: warning: .*above 1"):
        steradian.load_file(path)
    with pytest.raises(steradian.SceneError, match="non-negative"):
        steradian.load_string(path.read_text().replace("1.2", "-0.2"))
