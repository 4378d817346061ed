#!/usr/bin/env python3
"""Writes the environment maps of the `envmap` reference scene (run from this folder with the
mitsuba 3 pip package):

- sky.exr: 128×64 lat-long sky in Mitsuba's convention (pixel (x, y) looks towards
  θ = y·π/63, φ = 2π(x + ½)/128, d = (sin φ sin θ, cos θ, −cos φ sin θ)): a blue-to-white
  gradient above the horizon, brown ground below, and a sun disk of 4° radius with
  radiance ~2000 at elevation 35°, azimuth towards +X and slightly +Z: one bright region, so
  the lit side of every object shows the map's orientation.
- sky_small.hdr: a 16×8 version of the same sky written by Mitsuba as Radiance RGBE (its
  run-length encoding), for the loader test.
- uniform.exr: 8×4 pixels of radiance (0.6, 0.8, 1.0), for the closed-form tests.
"""
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")

SUN = np.array([0.78, np.sin(np.radians(35.0)), 0.25])
SUN = SUN / np.linalg.norm(SUN)


def sky(w, h, sun_radius_deg=4.0):
    img = np.zeros((h, w, 3), dtype=np.float32)
    cos_sun = np.cos(np.radians(sun_radius_deg))
    for y in range(h):
        theta = y * np.pi / (h - 1)
        for x in range(w):
            phi = 2 * np.pi * (x + 0.5) / w
            d = np.array([np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)])
            if d[1] >= 0:
                t = d[1] ** 0.5
                c = (1 - t) * np.array([1.0, 0.95, 0.85]) + t * np.array([0.25, 0.45, 0.95])
                c = c * 1.2
            else:
                c = np.array([0.25, 0.2, 0.15])
            if d @ SUN > cos_sun:
                c = np.array([2000.0, 1800.0, 1500.0])
            img[y, x] = c
    return img


mi.Bitmap(sky(128, 64)).write("sky.exr")
mi.Bitmap(sky(16, 8, sun_radius_deg=15.0)).write("sky_small.hdr")
mi.Bitmap(np.tile(np.array([0.6, 0.8, 1.0], dtype=np.float32), (4, 8, 1))).write("uniform.exr")
# what Mitsuba reads from the RGBE file, for steradian's reader to match
mi.Bitmap("sky_small.hdr").write("sky_small-mitsuba.exr")
