#!/usr/bin/env python3
"""Writes hair.txt for benches/hair/scene.xml: 50 000 B-spline strands of 24 control points
(1.05 M segments) growing from a sphere, radius 0.004 tapering towards the tips.

    python3 benches/hair/make_hair.py && steradian render benches/hair/scene.xml --spp 16
"""
import math
import os
import random

random.seed(1)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "hair.txt")
with open(out, "w") as f:
    for i in range(50000):
        th = math.acos(random.uniform(0.2, 1.0))
        ph = random.uniform(0, 2 * math.pi)
        nx, ny, nz = math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph)
        x, y, z = nx, ny, nz
        for k in range(24):
            f.write(f"{x:.5f} {y:.5f} {z:.5f} {0.004 * (1 - k / 30):.5f}\n")
            x += 0.06 * nx + 0.01 * math.sin(k * 0.7 + i)
            y += 0.06 * ny - 0.012 * k * 0.1
            z += 0.06 * nz + 0.01 * math.cos(k * 0.5 + i)
        f.write("\n")
