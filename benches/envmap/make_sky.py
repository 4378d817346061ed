#!/usr/bin/env python3
"""Writes sky.exr for the `glossy_spheres` benchmark (run from this folder with the mitsuba 3
pip package): a 256×128 lat-long sky in Mitsuba's convention (pixel (x, y) looks towards
θ = y·π/127, φ = 2π(x + ½)/256, d = (sin φ sin θ, cos θ, −cos φ sin θ)), a blue-to-white
gradient with a few brighter clouds, dark ground, and a sun of 2° radius whose radiance
(20000) is ~10⁴ times the sky's: most of the light comes from 0.01 % of the sphere.
"""
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")

W, H = 256, 128
sun = np.array([0.55, np.sin(np.radians(28.0)), 0.45])
sun /= np.linalg.norm(sun)
y, x = np.mgrid[0:H, 0:W]
theta = y * np.pi / (H - 1)
phi = 2 * np.pi * (x + 0.5) / W
d = np.stack([np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)], -1)
up = np.clip(d[..., 1], 0, 1)[..., None] ** 0.5
img = (1 - up) * np.array([1.0, 0.95, 0.85]) + up * np.array([0.2, 0.4, 0.95])
clouds = 0.6 * np.clip(np.sin(5 * phi) * np.sin(9 * theta), 0, 1) ** 4
img = img + clouds[..., None] * (d[..., 1:2] > 0)
img = np.where(d[..., 1:2] < 0, np.array([0.2, 0.17, 0.14]), img)
img = np.where((d @ sun > np.cos(np.radians(2.0)))[..., None], np.array([20000.0, 18500.0, 16000.0]), img)
mi.Bitmap(img.astype(np.float32)).write("sky.exr")
