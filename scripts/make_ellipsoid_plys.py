"""Writes the two ellipsoid files of crates/steradian-mitsuba/tests/reference/ellipsoids.xml
into tests/reference/ellipsoids/:

- cloud.ply: binary little endian, 14 ellipsoids in the plain layout (x y z nx ny nz, an extra
  color_0..2 group, scale_0..2 as logarithms, rot_0..3 with rot_0 the real part);
- splats.ply: ASCII, 10 ellipsoids in the Gaussian-splatting layout (f_dc_*, f_rest_*, opacity
  logits from 4 down to -6: the last ones below the 0.01 opacity of adaptive clamping).

Deterministic (fixed seed): run it again to get the same bytes. Needs numpy.
"""
import os
import numpy as np
os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'crates', 'steradian-mitsuba', 'tests', 'reference', 'ellipsoids'))
rng = np.random.default_rng(7)

def quat():
    q = rng.normal(size=4); return q / np.linalg.norm(q)

# cloud.ply: binary, plain layout with an extra 3-component group (color_*) in the middle
rows = []
for i in range(14):
    c = [rng.uniform(-0.9, 0.9), rng.uniform(0.15, 0.75), rng.uniform(-0.5, 0.5)]
    s = np.log([rng.uniform(0.03, 0.09), rng.uniform(0.02, 0.06), rng.uniform(0.01, 0.04)])
    rows.append([*c, 0, 0, 1, *rng.uniform(0, 1, 3), *s, *quat()])
names = ["x","y","z","nx","ny","nz","color_0","color_1","color_2","scale_0","scale_1","scale_2","rot_0","rot_1","rot_2","rot_3"]
hdr = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(rows)
hdr += "".join("property float %s\n" % n for n in names) + "end_header\n"
open("cloud.ply", "wb").write(hdr.encode() + np.array(rows, dtype="<f4").tobytes())

# splats.ply: ASCII, the Gaussian-splatting layout (f_dc_*, f_rest_*, opacity)
rows = []
for i in range(10):
    c = [rng.uniform(-0.8, 0.8), rng.uniform(0.1, 0.6), rng.uniform(-0.4, 0.4)]
    s = np.log([rng.uniform(0.04, 0.1), rng.uniform(0.03, 0.08), rng.uniform(0.02, 0.05)])
    # opacity logits: from nearly opaque to below the 0.01 threshold (no shell)
    op = [4.0, 2.0, 1.0, 0.5, 0.0, -1.0, -2.0, -3.0, -4.0, -6.0][i]
    rows.append([*c, 0, 0, 0, *rng.normal(size=3), *rng.normal(size=6) * 0.1, op, *s, *quat()])
names = ["x","y","z","nx","ny","nz","f_dc_0","f_dc_1","f_dc_2"] + ["f_rest_%d" % k for k in range(6)] + ["opacity","scale_0","scale_1","scale_2","rot_0","rot_1","rot_2","rot_3"]
hdr = "ply\nformat ascii 1.0\ncomment Gaussian-splatting layout\nelement vertex %d\n" % len(rows)
hdr += "".join("property float %s\n" % n for n in names) + "end_header\n"
body = "".join(" ".join("%.6g" % v for v in r) + "\n" for r in rows)
open("splats.ply", "w").write(hdr + body)
