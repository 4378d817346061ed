"""Meters from Python, against closed forms, with error bars from the estimator."""

import numpy as np
import pytest

import steradian
from steradian import radiometry
from conftest import CORNELL, DISK_METER


def test_disk_irradiance_within_five_standard_errors():
    m = steradian.load_file(DISK_METER).measure(spp=40000, seed=1)
    assert m.quantity == "irradiance" and m.unit == "W/m²"
    assert m.value.shape == m.stderr.shape == (3,) and m.value.dtype == np.float64
    # emitter radiance (1, 2, 4) W/(m²·sr), radius 0.8 m, 1.5 m above the 1 mm meter disk
    expected = np.array([radiometry.disk_on_axis_irradiance(L, 0.8, 1.5) for L in (1.0, 2.0, 4.0)])
    assert (m.stderr > 0).all()
    # the error bar is a few tenths of a percent at this spp, not a loose bound
    assert (m.stderr < 0.01 * expected).all()
    z = (m.value - expected) / m.stderr
    assert np.abs(z).max() < 5, z


def test_standard_error_shrinks_as_one_over_sqrt_n():
    scene = steradian.load_file(DISK_METER)
    small = scene.measure(spp=2000, seed=2).stderr
    large = scene.measure(spp=32000, seed=2).stderr
    ratio = small / large  # expected √16 = 4
    assert np.all((ratio > 3.0) & (ratio < 5.3)), ratio


def test_camera_reading_is_the_image_mean():
    scene = steradian.load_file(CORNELL, res=32)
    image = scene.render(spp=4, seed=9)
    m = scene.measure(spp=4, seed=9)
    assert m.quantity == "radiance" and m.unit == "W/(m²·sr)"
    np.testing.assert_allclose(m.value, image.astype(np.float64).mean(axis=(0, 1)), rtol=1e-6)
    assert (m.stderr > 0).all() and (m.stderr < 0.1 * m.value).all()
    assert "W/(m²·sr)" in repr(m)


def test_measurement_reports_the_branch_count():
    # a 32 x 32 film at 4 spp is too small for the pilot: the path tracer's default, 4
    m = steradian.load_file(CORNELL, res=32).measure(spp=4, seed=9)
    assert m.branches == 4
    # an irradiance meter's samples start on a surface, so no pilot runs: the default too
    b = steradian.load_file(DISK_METER).measure(spp=100).branches
    assert isinstance(b, int) and b == 4, b


def test_meter_sensor_by_id():
    scene = steradian.load_file(DISK_METER)
    assert scene.sensor_ids == ["meter"]
    a = scene.measure(spp=100, sensor="meter")
    b = scene.measure(spp=100, sensor=0)
    assert np.array_equal(a.value, b.value) and a.sensor == b.sensor == 0


def test_meters_cannot_make_irradiance_maps():
    with pytest.raises(ValueError, match="camera"):
        steradian.load_file(DISK_METER).render(spp=1, quantity="irradiance")


def test_work_plane_grid_as_arrays_in_lux():
    """A 3 x 2 work plane 2 m below a 1000 cd point source reads I h / d^3 lx at each centre."""
    w = 1000.0 / 683.0
    xml = f"""<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  <emitter type="point"><point name="position" x="0" y="0" z="2"/>
    <rgb name="intensity" value="{w}, {w}, {w}"/></emitter>
  <sensor type="workplane"><transform name="to_world"><scale x="1.5" y="1"/></transform>
    <integer name="nx" value="3"/><integer name="ny" value="2"/></sensor>
</scene>"""
    g = steradian.load_string(xml).measure_grid(spp=4)
    assert g["unit"] == "lx" and g["values"].shape == g["stderr"].shape == (2, 3)
    assert g["values"].dtype == np.float64
    x = np.array([-1.0, 0.0, 1.0])[None, :]
    y = np.array([0.5, -0.5])[:, None]
    d2 = x * x + y * y + 4.0
    np.testing.assert_allclose(g["values"], 1000.0 * 2.0 / d2**1.5, rtol=1e-4)
    avg, se = g["stats"]["avg"]
    assert avg == pytest.approx(g["values"].mean()) and se >= 0
    assert g["stats"]["u0"][0] == pytest.approx(g["values"].min() / avg)
    with pytest.raises(ValueError, match="workplane"):
        steradian.load_file(DISK_METER).measure_grid(spp=1)


def test_target_error_stops_the_meter_within_it():
    """The disk meter at a 1 % target: stops early, within 1 % of the closed form."""
    m = steradian.load_file(DISK_METER).measure(target_error=0.01, seed=3)
    assert m.target_reached and 64 <= m.spp < 1 << 20
    expected = np.array([radiometry.disk_on_axis_irradiance(L, 0.8, 1.5) for L in (1.0, 2.0, 4.0)])
    assert (1.96 * m.stderr <= 0.01 * m.value * 1.0001).all()
    assert (np.abs(m.value - expected) <= 0.01 * expected).all(), (m.value, expected)
    with pytest.raises(ValueError, match="target-error"):
        steradian.load_file(DISK_METER).measure(target_error=2.0)


def test_volpath_meter_reads_beer_lambert_through_a_slab():
    """A point source seen through an absorbing slab (a null-bounded box) under `volpath`:
    the irradiance meter reads I cos θ / r² · exp(−σ_t t / cos θ) within five standard errors
    plus the shadow ray's offsets at the slab's faces."""
    xml = """<scene version="3.0.0">
  <integrator type="volpath"/>
  <emitter type="point"><point name="position" x="0" y="0" z="1.5"/><rgb name="intensity" value="4"/></emitter>
  <shape type="cube">
    <transform name="to_world"><scale x="20" y="20" z="0.25"/><translate z="0.75"/></transform>
    <bsdf type="null"/>
    <medium type="homogeneous" name="interior">
      <rgb name="albedo" value="0"/><rgb name="sigma_t" value="0.5, 1, 2"/>
    </medium>
  </shape>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/></transform>
    <sensor type="irradiancemeter">
      <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film>
    </sensor>
  </shape>
</scene>"""
    m = steradian.load_string(xml).measure(spp=64, seed=1)
    expected = np.array(
        [radiometry.point_irradiance_through_slab(4.0, 1.5, 0.0, s, 0.5) for s in (0.5, 1.0, 2.0)]
    )
    assert np.allclose(expected[0], 4.0 / 2.25 * radiometry.beer_lambert(0.5, 0.5))
    assert np.all(np.abs(m.value - expected) <= 5 * m.stderr + 5e-4 * expected), (m.value, expected)


def test_sobol_batches_keep_the_reading_and_its_error_bar():
    """Samples as Sobol batches (`batch=`): the disk meter still reads the closed form within
    five of its (smaller) standard errors; `spp` counts the batches."""
    expected = np.array([radiometry.disk_on_axis_irradiance(L, 0.8, 1.5) for L in (1.0, 2.0, 4.0)])
    plain = steradian.load_file(DISK_METER).measure(spp=4096, seed=4)
    batched = steradian.load_file(DISK_METER).measure(spp=64, seed=4, batch=64)
    assert batched.spp == 64
    assert (batched.stderr > 0).all() and (batched.stderr < plain.stderr).all()
    z = (batched.value - expected) / batched.stderr
    assert np.abs(z).max() < 5, z
    with pytest.raises(ValueError, match="batch"):
        steradian.load_file(DISK_METER).measure(spp=4, batch=0)
