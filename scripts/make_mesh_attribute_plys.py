"""Writes the PLY meshes of tests/reference/mesh-attribute.xml (binary little endian):

- sphere.ply: a UV sphere (radius 1) with float vertex colours r, g, b, float face colours
  c_r, c_g, c_b (Mitsuba's face_c_color) and a float face scalar weight_x (face_weight);
- floor.ply: a 6 x 6 grid of squares, two triangles each (Mitsuba reads triangles only), on
  z = 0 in [-1, 1]^2 with a ushort vertex scalar w_0 (vertex_w: normalised and sRGB-decoded on
  load) and uchar face colours red, green, blue used with scale 1/255 (face_color, stored as
  is).

Deterministic (fixed seed): run it again to get the same bytes.
"""
import math
import random
import struct
import sys
from pathlib import Path


def sphere(path: Path, rng: random.Random) -> None:
    nu, nv = 12, 8
    verts = []
    for j in range(nv + 1):
        theta = math.pi * j / nv
        for i in range(nu + 1):
            phi = 2 * math.pi * i / nu
            verts.append((math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                          math.cos(theta)))
    faces = []
    for j in range(nv):
        for i in range(nu):
            a, b = j * (nu + 1) + i, j * (nu + 1) + i + 1
            c, d = a + nu + 1, b + nu + 1
            if j != 0:
                faces.append((a, c, b))
            if j != nv - 1:
                faces.append((b, c, d))
    head = ("ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(verts)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float r\nproperty float g\nproperty float b\n"
            f"element face {len(faces)}\n"
            "property list uchar int vertex_indices\n"
            "property float c_r\nproperty float c_g\nproperty float c_b\n"
            "property float weight_x\nend_header\n")
    out = bytearray(head.encode())
    for p in verts:
        col = (0.5 + 0.45 * p[0], 0.5 + 0.45 * p[1], 0.5 + 0.45 * p[2])
        out += struct.pack("<6f", *p, *col)
    for f in faces:
        out += struct.pack("<B3i", 3, *f)
        out += struct.pack("<4f", rng.random() * 0.8, rng.random() * 0.8, rng.random() * 0.8,
                           rng.random())
    path.write_bytes(bytes(out))


def floor(path: Path, rng: random.Random) -> None:
    n = 6
    verts = [(-1 + 2 * i / n, -1 + 2 * j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
    tris = []
    for j in range(n):
        for i in range(n):
            a, b = j * (n + 1) + i, j * (n + 1) + i + 1
            c, d = a + n + 1, b + n + 1
            tris += [(a, b, d), (a, d, c)]
    head = ("ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(verts)}\n"
            "property float x\nproperty float y\nproperty float z\nproperty ushort w_0\n"
            f"element face {len(tris)}\n"
            "property list uchar int vertex_indices\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")
    out = bytearray(head.encode())
    for p in verts:
        out += struct.pack("<3fH", *p, rng.randrange(65536))
    for t in tris:
        out += struct.pack("<B3i", 3, *t)
        out += struct.pack("<3B", rng.randrange(256), rng.randrange(256), rng.randrange(256))
    path.write_bytes(bytes(out))


if __name__ == "__main__":
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else
                  "crates/steradian-mitsuba/tests/reference/mesh_attribute")
    rng = random.Random(7)
    sphere(folder / "sphere.ply", rng)
    floor(folder / "floor.ply", rng)
