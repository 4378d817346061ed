#!/usr/bin/env python3
"""Prints Mitsuba 3's `ellipsoidsmesh` shell templates (`ico_sphere`, `box`, `uv_sphere`) as
steradian's `SHELL_*` tables (crates/steradian/src/shape/ellipsoid_shells.rs): each template's
vertices, already scaled by Mitsuba's rule, and its triangles with Mitsuba's vertex order,
read back from a unit ellipsoid that Mitsuba's own plugin builds. The vertex order fixes a
shell's texture coordinates (a triangle's barycentrics) and ∂p/∂u, ∂p/∂v, so textures and
normal maps on the shells need it to render as in Mitsuba.

    pip install mitsuba numpy && python3 scripts/ellipsoid_shells.py > /tmp/shells.rs
"""
import os
import tempfile

import mitsuba as mi

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)

# one ellipsoid at the origin, unit scales (log 0), identity rotation (real part first)
FIELDS = "x y z nx ny nz scale_0 scale_1 scale_2 rot_0 rot_1 rot_2 rot_3".split()
ply = os.path.join(tempfile.mkdtemp(), "unit.ply")
with open(ply, "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 1\n")
    f.write("".join(f"property float {p}\n" for p in FIELDS))
    f.write("end_header\n0 0 0 0 0 1 0 0 0 1 0 0 0\n")

print(f"// Mitsuba {mi.__version__} scalar_rgb, scripts/ellipsoid_shells.py")
for shell, name in [("ico_sphere", "ICO_SPHERE"), ("box", "BOX"), ("uv_sphere", "UV_SPHERE")]:
    s = mi.load_dict({"type": "ellipsoidsmesh", "filename": ply, "extent": 1.0, "shell": shell})
    vertices = [s.vertex_position(i) for i in range(s.vertex_count())]
    faces = [s.face_indices(i) for i in range(s.face_count())]
    print(f"pub(super) const {name}_VERTICES: [[f32; 3]; {len(vertices)}] = [")
    for v in vertices:
        print("    [" + ", ".join(f"{float(c):.9e}" for c in v) + "],")
    print("];")
    print(f"pub(super) const {name}_FACES: [[u32; 3]; {len(faces)}] = [")
    for i in range(0, len(faces), 6):
        print("    " + " ".join("[" + ", ".join(str(int(c)) for c in f) + "]," for f in faces[i:i + 6]))
    print("];")
