#!/usr/bin/env python3
"""Writes the small procedural images used by ../textures.xml (run with Mitsuba's Python
package, `pip install mitsuba==3.9.1 numpy`, in this folder).

  wall.png      64×64 sRGB colour pattern (diagonal bands, warm/cool) for the back wall
  leaf.jpg      64×64 sRGB green leaf colours with veins (JPEG, quality 95)
  leaf_mask.png 64×64 grey opacity: a leaf outline, 0 outside, 255 inside
  bumps.png     32×32 grey height field (raw): smooth bumps
  normals.png   32×32 tangent-space normal map (raw): ripples along u
  light.exr     4×4 linear float RGB radiance (W/(m²·sr)) for the area light, 6 to 16
"""
import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")


def write_u8(name, a):
    a = np.clip(np.round(a * 255.0), 0, 255).astype(np.uint8)
    fmt = mi.Bitmap.PixelFormat.Y if a.ndim == 2 else mi.Bitmap.PixelFormat.RGB
    mi.Bitmap(a, fmt).write(name)


n = 64
y, x = np.mgrid[0:n, 0:n] / (n - 1.0)
band = 0.5 + 0.5 * np.sin(2 * np.pi * 3 * (x + 0.6 * y))
wall = np.stack([0.85 * band + 0.1, 0.5 * band + 0.25 * (1 - band) + 0.1, 0.8 * (1 - band) + 0.1], -1)
write_u8("wall.png", wall)

u, v = x, y
# leaf: an ellipse-like outline pointed at both ends, along v
half_width = 0.42 * np.sin(np.pi * np.clip(v, 0, 1)) ** 0.8
inside = (np.abs(u - 0.5) < half_width) & (v > 0.03) & (v < 0.97)
write_u8("leaf_mask.png", inside.astype(float))
vein = np.exp(-((u - 0.5) / 0.02) ** 2) + 0.6 * np.exp(-((np.abs(u - 0.5) - 0.6 * (v - 0.2) % 0.2) / 0.02) ** 2)
leaf = np.stack([0.15 + 0.5 * vein, 0.45 + 0.4 * vein + 0.1 * v, 0.1 + 0.2 * vein], -1)
mi.Bitmap(np.clip(np.round(leaf * 255), 0, 255).astype(np.uint8), mi.Bitmap.PixelFormat.RGB).write("leaf.jpg", quality=95)

m = 32
y, x = np.mgrid[0:m, 0:m] / float(m)
h = 0.5 + 0.25 * np.sin(2 * np.pi * 4 * x) * np.sin(2 * np.pi * 3 * y)
write_u8("bumps.png", h)
slope = 0.6 * np.cos(2 * np.pi * 5 * x)
nrm = np.stack([-slope, np.zeros_like(slope), np.ones_like(slope)], -1)
nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
write_u8("normals.png", 0.5 * nrm + 0.5)

k = 4
y, x = np.mgrid[0:k, 0:k]
light = np.where(((x + y) % 2 == 0)[..., None], [16.0, 15.0, 13.0], [6.0, 7.0, 8.0]) * (1.0 - 0.05 * x[..., None])
mi.Bitmap(light.astype(np.float32)).write("light.exr")
