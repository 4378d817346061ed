"""Writes a UV sphere of about N triangles as a binary little-endian PLY (positions only,
faces as `uchar` counts and `int` indices: the layout most exporters write).

    python3 benches/large_mesh/make_sphere.py 20000000 /tmp/sphere20m.ply

The grid has `rings` latitude bands and `segments = 2 * rings` longitudes; the poles are
single vertices, so the sphere has 2 * segments * (rings - 1) triangles and no degenerate ones.
"""

import math
import sys

import numpy as np


def sphere(triangles: int):
    rings = max(3, int(round(math.sqrt(triangles / 4.0))))
    segments = 2 * rings
    theta = np.linspace(0.0, math.pi, rings + 1)[1:-1]  # interior latitudes
    phi = np.arange(segments) * (2.0 * math.pi / segments)
    st, ct = np.sin(theta)[:, None], np.cos(theta)[:, None]
    grid = np.stack(
        [st * np.cos(phi)[None, :], st * np.sin(phi)[None, :], np.broadcast_to(ct, (rings - 1, segments))],
        axis=-1,
    ).reshape(-1, 3)
    positions = np.concatenate([[[0.0, 0.0, 1.0]], grid, [[0.0, 0.0, -1.0]]]).astype("<f4")
    top, bottom = 0, len(positions) - 1
    ring = lambda r: 1 + r * segments + np.arange(segments)  # noqa: E731
    nxt = lambda r: 1 + r * segments + (np.arange(segments) + 1) % segments  # noqa: E731
    faces = [np.stack([np.full(segments, top), ring(0), nxt(0)], axis=1)]
    for r in range(rings - 2):
        a, b, c, d = ring(r), nxt(r), ring(r + 1), nxt(r + 1)
        faces.append(np.stack([a, c, d], axis=1))
        faces.append(np.stack([a, d, b], axis=1))
    faces.append(np.stack([ring(rings - 2), np.full(segments, bottom), nxt(rings - 2)], axis=1))
    return positions, np.concatenate(faces).astype("<i4")


def main():
    n, path = int(sys.argv[1]), sys.argv[2]
    positions, faces = sphere(n)
    records = np.empty(len(faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
    records["n"] = 3
    records["i"] = faces
    with open(path, "wb") as f:
        header = (
            "ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(positions)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"element face {len(faces)}\n"
            "property list uchar int vertex_indices\nend_header\n"
        )
        f.write(header.encode("ascii"))
        f.write(positions.tobytes())
        f.write(records.tobytes())
    print(f"{path}: {len(positions)} vertices, {len(faces)} triangles")


if __name__ == "__main__":
    main()
