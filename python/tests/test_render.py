"""Rendering from Python: array layout, units, determinism, options."""

import numpy as np
import pytest

import steradian
from conftest import CORNELL

# A camera in a uniform environment of radiance L sees L in every pixel, whatever the
# filter and the samples: an exact check of units and of the (H, W, 3) layout.
SKY = """<scene version="3.0.0">
    <integrator type="path"/>
    <emitter type="constant"><rgb name="radiance" value="0.25, 1.5, 3"/></emitter>
    <sensor type="perspective">
        <film type="hdrfilm">
            <integer name="width" value="7"/><integer name="height" value="5"/>
        </film>
    </sensor>
</scene>"""


@pytest.fixture(scope="module")
def cornell():
    return steradian.load_file(CORNELL, res=48)


def test_uniform_sky_gives_its_radiance_in_every_pixel():
    image = steradian.load_string(SKY).render(spp=3)
    assert image.dtype == np.float32
    assert image.shape == (5, 7, 3)  # (H, W, 3)
    np.testing.assert_allclose(image, np.broadcast_to([0.25, 1.5, 3.0], (5, 7, 3)), rtol=1e-6)


def test_readme_example_shape_and_values(cornell):
    image = cornell.render(spp=2)
    assert image.shape == (48, 48, 3) and image.dtype == np.float32
    assert image.flags.c_contiguous and image.flags.writeable
    assert np.isfinite(image).all() and (image >= 0).all()
    # the light (radiance 18.4, 14.0, 6.8 W/(m²·sr) in the scene) is in view
    assert image.max() > 5.0
    assert 0.01 < image.mean() < 1.0


def test_same_seed_same_image_other_seed_other_image(cornell):
    a = cornell.render(spp=2, seed=5)
    b = cornell.render(spp=2, seed=5)
    c = cornell.render(spp=2, seed=6)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_default_seed_is_zero_and_none_keeps_the_scene_seed(cornell):
    assert np.array_equal(cornell.render(spp=2), cornell.render(spp=2, seed=0))
    # the scene's sampler has no seed: Mitsuba's default, 0
    assert np.array_equal(cornell.render(spp=2, seed=None), cornell.render(spp=2, seed=0))


def test_thread_count_does_not_change_the_image(cornell):
    assert np.array_equal(cornell.render(spp=3, threads=1), cornell.render(spp=3, threads=2))


def test_defaults_override_scene_defaults():
    scene = steradian.load_file(str(CORNELL), res=20, spp=3)
    assert scene.film_size() == (20, 20)
    # spp=None takes the scene's sample count, here the overridden <default name="spp">
    assert scene.measure(spp=None).spp == 3
    assert scene.render().shape == (20, 20, 3)


def test_sensor_by_index_and_id(cornell):
    assert cornell.sensor_ids == ["", "top-down"]
    by_id = cornell.render(spp=1, sensor="top-down")
    by_index = cornell.render(spp=1, sensor=1)
    assert np.array_equal(by_id, by_index)
    assert not np.array_equal(by_id, cornell.render(spp=1, sensor=0))


def test_irradiance_and_illuminance_maps(cornell):
    e = cornell.render(spp=2, sensor="top-down", quantity="irradiance")
    lux = cornell.render(spp=2, sensor="top-down", quantity="illuminance")
    assert e.shape == lux.shape == (48, 48, 3)
    assert e.max() > 0
    # lux = 683 lm/W × luminance (Rec. 709 / sRGB Y weights) of the irradiance, in all channels
    y = 683.0 * (0.212671 * e[..., 0] + 0.715160 * e[..., 1] + 0.072169 * e[..., 2])
    np.testing.assert_allclose(lux[..., 0], y, rtol=1e-5, atol=1e-6)
    assert np.array_equal(lux[..., 0], lux[..., 2])


def test_progress_callback_reaches_the_total(cornell):
    calls = []
    cornell.render(spp=8, progress=lambda done, total: calls.append((done, total)))
    assert calls, "the callback was never called"
    total = 48 * 48 * 8
    assert all(t == total for _, t in calls)
    dones = [d for d, _ in calls]
    assert dones == sorted(dones) and dones[-1] == total


def test_exception_in_progress_callback_stops_and_propagates(cornell):
    class Stop(Exception):
        pass

    def progress(done, total):
        raise Stop(done)

    with pytest.raises(Stop):
        steradian.load_file(CORNELL, res=64).render(spp=4096, progress=progress)


def test_gil_is_released_while_rendering():
    import threading
    import time

    scene = steradian.load_file(CORNELL, res=64)
    ticks = []
    worker = threading.Thread(target=lambda: scene.render(spp=64, threads=1))
    start = time.perf_counter()
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.002)
    elapsed = time.perf_counter() - start
    worker.join()
    assert elapsed > 0.3, f"render too short ({elapsed:.2f} s) to tell"
    # with the GIL held by the render, this thread could not tick until it ended
    gaps = np.diff([start] + ticks)
    assert len(ticks) > 20 and gaps.max() < max(0.25, elapsed / 4), (len(ticks), gaps.max(), elapsed)


def test_moment_and_aov_layers_come_after_rgb_as_in_mitsuba():
    # in a uniform sky of radiance L every sample is L: the path tracer's mean XYZ layer is
    # the XYZ of L, its second moment the square, and an aov depth layer is 0 (no surface)
    moment = SKY.replace(
        '<integrator type="path"/>',
        '<integrator type="moment"><integrator type="path" name="pp"/></integrator>',
    )
    scene = steradian.load_string(moment)
    names = scene.channel_names()
    assert names == ["R", "G", "B", "pp.X", "pp.Y", "pp.Z", "m2_pp.X", "m2_pp.Y", "m2_pp.Z"]
    image = scene.render(spp=4)
    assert image.shape == (5, 7, 9)
    y = 0.212671 * 0.25 + 0.715160 * 1.5 + 0.072169 * 3
    assert np.allclose(image[..., 4], y, rtol=1e-5)
    assert np.allclose(image[..., 7], y * y, rtol=1e-5)
    aov = SKY.replace(
        '<integrator type="path"/>',
        '<integrator type="aov"><string name="aovs" value="dd:depth"/><integrator type="path"/></integrator>',
    )
    scene = steradian.load_string(aov)
    assert scene.channel_names() == ["R", "G", "B", "_arg_0.R", "_arg_0.G", "_arg_0.B", "_arg_0.A", "dd.T"]
    image = scene.render(spp=2)
    assert image.shape == (5, 7, 8)
    assert np.allclose(image[..., :3], [0.25, 1.5, 3], rtol=1e-6)
    assert np.all(image[..., 6] == 1.0) and np.all(image[..., 7] == 0.0)


def test_an_rgba_film_adds_alpha_last_and_develops_from_sums():
    # a sphere filling part of the frame, no environment: alpha is 1 on it, 0 off it
    xml = """<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective"><float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="10"/>
            <string name="pixel_format" value="rgba"/><rfilter type="box"/></film></sensor>
    <emitter type="point"><point name="position" x="0" y="2" z="3"/><rgb name="intensity" value="5"/></emitter>
    <shape type="sphere"><float name="radius" value="0.9"/></shape>
</scene>"""
    scene = steradian.load_string(xml)
    assert scene.channel_names() == ["R", "G", "B", "A"]
    image = scene.render(spp=8, seed=1)
    assert image.shape == (10, 12, 4)
    alpha = image[..., 3]
    assert alpha[5, 6] == 1.0 and alpha[0, 0] == 0.0
    assert np.all(image[..., :3][alpha == 0.0] == 0.0)
    rgb = steradian.load_string(xml.replace('"rgba"', '"rgb"')).render(spp=8, seed=1)
    assert np.array_equal(rgb, image[..., :3])
    sums = scene.render_range(0, 8, 8, 1)
    assert np.array_equal(scene.develop(sums), image)


# A diffuse plane (rho = 0.5) under a uniform sky (L = 1) seen from above: every pixel is
# 0.5, noisy through the sky's sampling, so a target error stops well before the cap.
PLANE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
    <shape type="rectangle"><transform name="to_world"><scale value="100"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"/>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/></film>
    </sensor>
</scene>"""


def test_render_result_is_the_image_with_its_errors_and_what_it_spent(cornell):
    r = cornell.render_result(spp=3, seed=2)
    assert np.array_equal(r.image, cornell.render(spp=3, seed=2))
    assert r.stderr.shape == r.image.shape and (r.stderr >= 0).all() and r.stderr.max() > 0
    assert (r.spp, r.samples, r.interrupted, r.target_reached) == (3, 3 * 48 * 48, False, False)
    # every camera sample traces its camera ray and its branches' paths
    assert r.rays > r.samples and r.branches is not None and r.elapsed > 0
    assert r.error_reached > 0 and "spp" in repr(r)


def test_render_result_reports_the_target_error_reached():
    e = 0.05
    r = steradian.load_string(PLANE).render_result(target_error=e, seed=1)
    assert r.target_reached and not r.interrupted and r.error_reached <= e
    assert 64 <= r.spp < 1 << 16
    # the rule it met: 95 % of the pixels within e at 1.96 standard errors, and the truth
    # (0.5) within e of at least 85 % of them
    within = np.abs(r.image[..., 1] - 0.5) <= e * 0.5
    assert (1.96 * r.stderr[..., 1] <= e * r.image[..., 1] * 1.0001).mean() >= 0.95
    assert within.mean() >= 0.85
