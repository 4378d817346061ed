#!/usr/bin/env python3
"""Writes the small Mitsuba `serialized` mesh files that steradian's tests read, and the
numbers they must load as (`expected.txt`), with the Python standard library only.

    python3 scripts/write_serialized.py crates/steradian-mitsuba/tests/reference/serialized
    /tmp/venv/bin/python scripts/write_serialized.py DIR --check   # also load each with Mitsuba 3

Format (little endian), per shape: u16 0x041C, u16 version (3 or 4), then one zlib stream:
u32 flags (0x1 normals, 0x2 uvs, 0x8 colours, 0x10 face normals, 0x1000 single, 0x2000
double), [v4: NUL-terminated name], u64 vertex count, u64 face count, positions, [normals],
[uvs], [colours] (f32 or f64), indices (u32). The file ends with the shape offsets (v4: u64,
v3: u32) and a u32 shape count.

expected.txt: one line per (file, shape index): vertex and face counts, whether normals and
uvs are present, Σx Σy Σz and Σ(i·(x+y+z)) over vertices i (as stored, f32-rounded for single
precision), and Σ indices and Σ(f·(a+b+c)) over faces f.
"""
import argparse
import math
import os
import struct
import sys
import zlib

HAS_NORMALS, HAS_UVS, HAS_COLORS, FACE_NORMALS = 0x1, 0x2, 0x8, 0x10
SINGLE, DOUBLE = 0x1000, 0x2000


def sphere(nu, nv, r=1.0):
    """UV sphere (poles duplicated per segment), outward normals, counter-clockwise faces."""
    pos, nrm, uv, faces = [], [], [], []
    for j in range(nv + 1):
        th = math.pi * j / nv
        for i in range(nu + 1):
            ph = 2 * math.pi * i / nu
            n = (math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th))
            pos.append(tuple(r * c for c in n))
            nrm.append(n)
            uv.append((i / nu, j / nv))
    w = nu + 1
    for j in range(nv):
        for i in range(nu):
            a, b, c, d = j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i
            if j > 0:
                faces.append((a, d, b))
            if j < nv - 1:
                faces.append((b, d, c))
    return pos, nrm, uv, faces


def torus(nu, nv, big=1.0, small=0.35):
    pos, nrm, uv, faces = [], [], [], []
    for j in range(nv):
        th = 2 * math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            n = (math.cos(th) * math.cos(ph), math.cos(th) * math.sin(ph), math.sin(th))
            pos.append(((big + small * math.cos(th)) * math.cos(ph),
                        (big + small * math.cos(th)) * math.sin(ph), small * math.sin(th)))
            nrm.append(n)
            uv.append((i / nu, j / nv))
    for j in range(nv):
        for i in range(nu):
            a, b = j * nu + i, j * nu + (i + 1) % nu
            c, d = ((j + 1) % nv) * nu + (i + 1) % nu, ((j + 1) % nv) * nu + i
            faces += [(a, b, c), (a, c, d)]
    return pos, nrm, uv, faces


def shape_stream(version, mesh, normals, uvs, colors, double, name=""):
    pos, nrm, uv, faces = mesh
    flags = (DOUBLE if double else SINGLE) | (HAS_NORMALS if normals else 0)
    flags |= (HAS_UVS if uvs else 0) | (HAS_COLORS if colors else 0)
    fmt = "d" if double else "f"
    body = struct.pack("<I", flags)
    if version == 4:
        body += name.encode() + b"\0"
    body += struct.pack("<QQ", len(pos), len(faces))

    def arr(rows):
        flat = [c for row in rows for c in row]
        return struct.pack("<%d%s" % (len(flat), fmt), *flat)

    body += arr(pos)
    if normals:
        body += arr(nrm)
    if uvs:
        body += arr(uv)
    if colors:
        body += arr([(0.5 + 0.5 * p[0], 0.5, 0.5 - 0.5 * p[2]) for p in pos])
    body += struct.pack("<%dI" % (3 * len(faces)), *[i for f in faces for i in f])
    return struct.pack("<HH", 0x041C, version) + zlib.compress(body, 9)


def write_file(path, version, shapes):
    data, offsets = b"", []
    for s in shapes:
        offsets.append(len(data))
        data += shape_stream(version, **s)
    fmt = "Q" if version == 4 else "I"
    data += struct.pack("<%d%s" % (len(offsets), fmt), *offsets)
    data += struct.pack("<I", len(offsets))
    with open(path, "wb") as f:
        f.write(data)


def stored(x, double):
    return x if double else struct.unpack("<f", struct.pack("<f", x))[0]


def summary(s):
    pos, _, _, faces = s["mesh"]
    d = s["double"]
    p = [tuple(stored(c, d) for c in v) for v in pos]
    sums = [sum(v[k] for v in p) for k in range(3)]
    wsum = sum(i * (v[0] + v[1] + v[2]) for i, v in enumerate(p))
    isum = sum(sum(f) for f in faces)
    iwsum = sum(i * sum(f) for i, f in enumerate(faces))
    return (len(pos), len(faces), int(s["normals"]), int(s["uvs"]), *sums, wsum, isum, iwsum)


FILES = {
    # v4, single precision, normals and uvs
    "sphere_v4.serialized": (4, [dict(mesh=sphere(12, 8), normals=True, uvs=True,
                                      colors=False, double=False, name="sphere")]),
    # v3, double precision, no normals or uvs, vertex colours (skipped by the readers)
    "torus_v3_double.serialized": (3, [dict(mesh=torus(12, 6), normals=False, uvs=False,
                                            colors=True, double=True)]),
    # two shapes per file, each version: a single-precision sphere with uvs and a
    # double-precision torus with normals
    "two_v4.serialized": (4, [dict(mesh=sphere(10, 6), normals=False, uvs=True, colors=False,
                                   double=False, name="ball"),
                              dict(mesh=torus(10, 5), normals=True, uvs=False, colors=False,
                                   double=True, name="ring")]),
    "two_v3.serialized": (3, [dict(mesh=sphere(10, 6), normals=False, uvs=True, colors=False,
                                   double=False),
                              dict(mesh=torus(10, 5), normals=True, uvs=False, colors=False,
                                   double=True)]),
}


def check_with_mitsuba(outdir):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    import numpy as np
    for name, (_, shapes) in FILES.items():
        for idx, s in enumerate(shapes):
            m = mi.load_dict({"type": "serialized", "filename": os.path.join(outdir, name),
                              "shape_index": idx})
            params = mi.traverse(m)
            p = np.array(params["vertex_positions"]).reshape(-1, 3).astype(np.float64)
            f = np.array(params["faces"]).reshape(-1, 3).astype(np.int64)
            e = summary(s)
            got = (len(p), len(f), *p.sum(axis=0), (np.arange(len(p)) * p.sum(axis=1)).sum(),
                   f.sum(), (np.arange(len(f)) * f.sum(axis=1)).sum())
            want = (e[0], e[1], *e[4:])
            assert got[:2] == want[:2], (name, idx, got, want)
            assert np.allclose(got[2:], want[2:], rtol=1e-6, atol=1e-4), (name, idx, got, want)
            assert m.has_vertex_texcoords() == bool(s["uvs"]), (name, idx)
            print(f"mitsuba agrees: {name}@{idx}: {e[0]} vertices, {e[1]} faces")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--check", action="store_true", help="load every shape with Mitsuba 3")
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    lines = ["# file shape_index vertices faces normals uvs sum_x sum_y sum_z "
             "sum_i(x+y+z) sum_indices sum_f(a+b+c)"]
    for name, (version, shapes) in FILES.items():
        write_file(os.path.join(args.outdir, name), version, shapes)
        for idx, s in enumerate(shapes):
            e = summary(s)
            lines.append(f"{name} {idx} " + " ".join(repr(x) for x in e))
    with open(os.path.join(args.outdir, "expected.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    if args.check:
        check_with_mitsuba(args.outdir)


if __name__ == "__main__":
    sys.exit(main())
