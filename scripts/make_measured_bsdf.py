#!/usr/bin/env python3
"""Writes small synthetic RGB `.bsdf` files in the layout of RGL's measured materials
(Dupuy and Jakob 2018), for steradian's `measured` tests: an isotropic and an anisotropic
one with a four-fold symmetry (φᵢ over [−π, −π/2]), and the same two with a VNDF that
vanishes at the normal ("smooth": their solid-angle density stays finite at the mirror
direction, where the others' grows as θ_h^(−3/2), so that a χ² test's quadrature is exact).

    python3 scripts/make_measured_bsdf.py crates/steradian/src/bsdf/testdata

The tables are smooth positive functions of the grid coordinates (not a physical material):
enough structure that every warp and interpolation of the model matters. Written with
Mitsuba's own `tensor_io.write`, so Mitsuba reads them as it reads RGL's files.
"""
import math
import sys

import numpy as np


def tables(phi_i, theta_i, n=9, ndf_n=(7, 11), smooth=False):
    f = np.float32
    g = np.linspace(0.0, 1.0, n)
    y, x = np.meshgrid(g, g, indexing="ij")  # x: the θ coordinate, y: the φ coordinate
    gy, gx = np.meshgrid(np.linspace(0, 1, ndf_n[0]), np.linspace(0, 1, ndf_n[1]), indexing="ij")
    ndf = np.exp(-(1.6 * gx) ** 2) * (1.0 + 0.3 * np.cos(2 * math.pi * gy)) + 0.05
    sigma = 0.6 + 0.4 * (1.0 - gx ** 2) + 0.1 * np.sin(2 * math.pi * gy)
    P, T = len(phi_i), len(theta_i)
    vndf = np.zeros((P, T, n, n))
    lum = np.zeros((P, T, n, n))
    rgb = np.zeros((P, T, 3, n, n))
    for p in range(P):
        for t in range(T):
            vndf[p, t] = np.exp(-((1.0 + 0.4 * t) * x) ** 2) * (1 + 0.25 * np.sin(2 * math.pi * y + p)) + 0.02
            if smooth:
                vndf[p, t] *= x
            lum[p, t] = 0.3 + x * (1 - x) * (1 + 0.5 * y) + 0.1 * t + 0.05 * p
            for c in range(3):
                rgb[p, t, c] = 0.5 * (0.2 + 0.6 * x * (c + 1) / 3 + 0.1 * y + 0.05 * p) * (1 + 0.1 * t)
    return dict(
        theta_i=np.asarray(theta_i, f), phi_i=np.asarray(phi_i, f),
        ndf=ndf.astype(f), sigma=sigma.astype(f), vndf=vndf.astype(f),
        luminance=lum.astype(f), rgb=rgb.astype(f),
        description=np.frombuffer(b"steradian synthetic test material", np.uint8),
        jacobian=np.array([1], np.uint8))


def main():
    out = sys.argv[1]
    import mitsuba as mi
    theta = [0.0, 0.35, 0.7, 1.1, 1.5]
    mi.tensor_io.write(f"{out}/measured_iso_rgb.bsdf", **tables([0.0], theta))
    phi = list(np.linspace(-math.pi, -math.pi / 2, 3))
    mi.tensor_io.write(f"{out}/measured_aniso_rgb.bsdf", **tables(phi, theta))
    mi.tensor_io.write(f"{out}/measured_smooth_iso_rgb.bsdf", **tables([0.0], theta, smooth=True))
    mi.tensor_io.write(f"{out}/measured_smooth_aniso_rgb.bsdf", **tables(phi, theta, smooth=True))


if __name__ == "__main__":
    main()
