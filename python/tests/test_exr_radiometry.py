"""EXR input/output and the radiometry functions."""

import math

import numpy as np
import pytest

import steradian
from steradian import radiometry


def test_exr_round_trip_is_exact(tmp_path):
    rng = np.random.default_rng(4)
    image = (rng.standard_normal((9, 13, 3)) * 10.0 ** rng.integers(-6, 6, (9, 13, 3))).astype(np.float32)
    image[0, 0] = [0.0, np.float32(1e-40), 65504.0 * 16]  # zero, a subnormal, beyond half range
    path = tmp_path / "rt.exr"
    steradian.write_exr(path, image)
    back = steradian.read_exr(str(path))
    assert back.dtype == np.float32 and back.shape == (9, 13, 3)
    assert back.tobytes() == image.tobytes()


def test_write_exr_converts_array_likes(tmp_path):
    f64 = np.linspace(0, 1, 2 * 3 * 3).reshape(2, 3, 3)
    strided = np.zeros((4, 6, 3), np.float32)[::2, ::2]  # not contiguous
    strided[...] = 2.5
    for i, image in enumerate([f64, strided, f64.tolist()]):
        steradian.write_exr(tmp_path / f"{i}.exr", image)
        assert np.array_equal(steradian.read_exr(tmp_path / f"{i}.exr"), np.asarray(image, np.float32))


def test_solid_angles_against_independent_forms():
    # cone of half-angle θ vs the sphere that it circumscribes
    r, d = 1.0, 3.0
    assert radiometry.sphere_solid_angle(r, d) == pytest.approx(radiometry.cone_solid_angle(math.asin(r / d)), rel=1e-12)
    assert radiometry.sphere_solid_angle(1.0, 0.5) == pytest.approx(4 * math.pi)
    assert radiometry.cone_solid_angle(math.pi / 2) == pytest.approx(2 * math.pi)
    assert radiometry.cone_projected_solid_angle(math.pi / 2) == pytest.approx(math.pi)
    # a 2a × 2b rectangle on its axis: closed form = two triangles = quadrilateral
    a, b, h = 0.5, 1.0, 2.0
    p = [0.0, 0.0, h]
    corners = [[-a, -b, 0.0], [a, -b, 0.0], [a, b, 0.0], [-a, b, 0.0]]
    on_axis = radiometry.rectangle_solid_angle_on_axis(a, b, h)
    assert radiometry.quad_solid_angle(p, *corners) == pytest.approx(on_axis, rel=1e-12)
    two = radiometry.triangle_solid_angle(p, *corners[:3]) + radiometry.triangle_solid_angle(
        np.array(p), np.array(corners[0]), np.array(corners[2]), np.array(corners[3])
    )
    assert two == pytest.approx(on_axis, rel=1e-12)
    # a disk seen on axis: quadrature vs closed form; off axis it subtends less
    disk = radiometry.disk_solid_angle((0.0, 0.0, 1.5), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.8)
    assert disk == pytest.approx(radiometry.disk_solid_angle_on_axis(0.8, 1.5), rel=1e-9)
    assert radiometry.disk_solid_angle((1.0, 0.0, 1.5), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.8) < disk


def test_irradiance_formulas():
    # inverse square and cosine: I = 100 W/sr, r = 2 m, θ = 60°
    n = (0.0, math.sin(math.radians(60)), math.cos(math.radians(60)))
    assert radiometry.point_irradiance(100.0, (0, 0, 2), (0, 0, 0), n) == pytest.approx(12.5)
    assert radiometry.point_irradiance_at(100.0, 2.0, math.radians(60)) == pytest.approx(12.5)
    assert radiometry.point_irradiance(1.0, (0, 0, -1), (0, 0, 0), (0, 0, 1)) == 0.0
    assert radiometry.point_light_flux(1.0) == pytest.approx(4 * math.pi)
    # a disk of radiance L subtending θ: H = L·π sin²θ = L × projected solid angle
    L, r, h = 2.0, 0.5, 1.2
    assert radiometry.disk_on_axis_irradiance(L, r, h) == pytest.approx(
        L * radiometry.cone_projected_solid_angle(math.atan(r / h)), rel=1e-12
    )
    # four corner rectangles make a centred one: H = L ∫ cos θ cos θ′ / r² dA = L ∫ d²/r⁴ dA,
    # by midpoint quadrature
    a, b, d = 0.7, 0.4, 1.1
    x = np.linspace(-a, a, 801)[:-1] + a / 800
    y = np.linspace(-b, b, 801)[:-1] + b / 800
    X, Y = np.meshgrid(x, y)
    quad = (d * d / (X**2 + Y**2 + d * d) ** 2).sum() * (2 * a / 800) * (2 * b / 800)
    assert 4 * radiometry.rect_parallel_corner_irradiance(1.0, a, b, d) == pytest.approx(quad, rel=1e-4)
    assert radiometry.lambertian_exitance(1.0) == pytest.approx(math.pi)


def test_brdf_normalisations():
    assert radiometry.lambert_brdf(1.0) == pytest.approx(1 / math.pi)
    for n in (0.0, 1.0, 10.0):
        assert radiometry.phong_lobe_integral(n) == pytest.approx(2 * math.pi / (n + 1))
        # (n+2)/(2π) × ∫cosⁿ⁺¹ = 1
        assert radiometry.modified_phong_normalization(n) * radiometry.phong_lobe_integral(n + 1) == pytest.approx(1.0)
    assert radiometry.modified_phong_albedo_normal_incidence(0.3, 0.5, 20.0) == pytest.approx(0.8)


def test_every_function_is_documented_with_units():
    names = [n for n in dir(radiometry) if not n.startswith("_")]
    assert len(names) == 21
    for name in names:
        doc = getattr(radiometry, name).__doc__
        assert doc and any(u in doc for u in ("sr", "W/m²", "W", "1/sr", "dimensionless")), name
    with pytest.raises(ValueError, match="length 3"):
        radiometry.point_irradiance(1.0, (0, 0), (0, 0, 0), (0, 0, 1))
    with pytest.raises(TypeError):
        radiometry.cone_solid_angle("wide")
