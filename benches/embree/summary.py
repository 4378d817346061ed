#!/usr/bin/env python3
"""Table of a benches/embree/run.sh log: per mesh, ray set and thread count the best round of
Embree and of steradian (Mrays/s), their ratio, the same per CPU second (Mrays/s divided by the
measured CPU utilisation: robust when other processes share the cores), the hit fractions and
how many rays' results differ from Embree's. Then build time and memory per triangle.

    python3 benches/embree/summary.py RUN.log
"""
import collections
import sys


def fields(line):
    out = {}
    for tok in line.split():
        if "=" in tok:
            k, v = tok.split("=", 1)
            out[k] = v
    return out


def main(path):
    best = {}  # (lib, mesh, set, threads) -> (mrays, mrays_per_cpu, record)
    builds = collections.defaultdict(list)
    for line in open(path):
        if " TRACE " in line:
            f = fields(line)
            lib = "embree" if f["lib"].startswith("embree") else "steradian"
            key = (lib, f["mesh"], f["set"], int(f["threads"]))
            m = float(f["mrays_per_s"])
            util = float(f.get("cpu_util", "0") or 0)
            per_cpu = m / util if util > 0 else float("nan")
            old = best.get(key)
            best[key] = (
                max(m, old[0]) if old else m,
                max(per_cpu, old[1]) if old else per_cpu,
                f if not old or m > old[0] else old[2],
            )
        elif " BUILD " in line:
            f = fields(line)
            lib = "embree" if f["lib"].startswith("embree") else "steradian"
            builds[(lib, f["mesh"])].append(f)

    meshes = sorted({k[1] for k in best}, key=lambda m: (m != "sphere1m", m))
    sets = ["primary", "diffuse", "bounce", "shadow"]
    print("\n### Single rays, same rays, best round: Mrays/s (ratio = steradian / Embree)\n")
    print("| mesh | rays | threads | Embree | steradian | ratio | ratio per CPU s | hit frac Embree | hit frac steradian | rays differing |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    worst = None
    for mesh in meshes:
        for s in sets:
            for th in sorted({k[3] for k in best}):
                e, r = best.get(("embree", mesh, s, th)), best.get(("steradian", mesh, s, th))
                if not e or not r:
                    continue
                ratio, ratio_cpu = r[0] / e[0], r[1] / e[1]
                differ = r[2].get("vs_embree_decision_differs", "?")
                print(f"| {mesh} | {s} | {th} | {e[0]:.2f} | {r[0]:.2f} | {ratio:.2f} | {ratio_cpu:.2f} | "
                      f"{float(e[2]['hit_frac']):.6f} | {float(r[2]['hit_frac']):.6f} | {differ} |")
                if th == 2 and (worst is None or ratio < worst[0]):
                    worst = (ratio, mesh, s)
    if worst:
        print(f"\nlowest 2-thread ratio: {worst[0]:.2f} ({worst[1]}, {worst[2]}); target >= 0.67")

    print("\n### Build (best round) and memory\n")
    print("| mesh | library | triangles | build s | MTris/s | BVH MiB | BVH B/tri | mesh B/tri | total B/tri | SAH cost |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for mesh in meshes:
        for lib in ["embree", "steradian"]:
            b = builds.get((lib, mesh))
            if not b:
                continue
            f = min(b, key=lambda x: float(x["sec"]))
            tris = int(f["tris"])
            bvh_mb = float(f["bvh_mb"])
            bvh_b = bvh_mb * 1024 * 1024 / tris
            # both libraries get the same input: f32 xyz per vertex, u32 x3 per triangle
            mesh_b = float(f["bytes_per_tri_mesh"]) if "bytes_per_tri_mesh" in f else float("nan")
            if lib == "embree":
                mesh_b = next((float(x["bytes_per_tri_mesh"]) for x in builds.get(("steradian", mesh), [])), float("nan"))
            print(f"| {mesh} | {lib} | {tris:,} | {float(f['sec']):.3f} | {float(f['mtris_per_s']):.2f} | {bvh_mb:.1f} | "
                  f"{bvh_b:.1f} | {mesh_b:.1f} | {bvh_b + mesh_b:.1f} | {f.get('sah_cost', '-')} |")


if __name__ == "__main__":
    main(sys.argv[1])
