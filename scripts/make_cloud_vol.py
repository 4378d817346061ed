#!/usr/bin/env python3
"""Writes a small procedural cloud as a Mitsuba .vol grid (version 3, float32, 1 channel):
a sum of smooth Gaussian puffs, densities in [0, 1], x fastest.

    python3 scripts/make_cloud_vol.py OUT.vol [--res 24]
"""
import argparse, struct
import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("out")
ap.add_argument("--res", type=int, default=24)
a = ap.parse_args()
n = a.res
rng = np.random.default_rng(7)
c = (np.arange(n) + 0.5) / n
z, y, x = np.meshgrid(c, c, c, indexing="ij")
d = np.zeros((n, n, n))
for _ in range(14):
    p = rng.uniform(0.25, 0.75, 3)
    r = rng.uniform(0.08, 0.2)
    d += np.exp(-((x - p[0])**2 + (y - p[1])**2 + (z - p[2])**2) / (2 * r * r))
d = np.clip(d / d.max() * 1.6 - 0.4, 0, 1).astype("<f4")
with open(a.out, "wb") as f:
    f.write(b"VOL" + bytes([3]))
    f.write(struct.pack("<iiiii", 1, n, n, n, 1))
    f.write(struct.pack("<6f", 0, 0, 0, 1, 1, 1))
    f.write(d.tobytes())  # z, y, x order with x fastest
