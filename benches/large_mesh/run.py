#!/usr/bin/env python3
"""Large meshes: load, build and render a UV sphere of 0.2, 2 and 20 million triangles (binary
PLY, diffuse, constant sky, 128x128 at 4 spp; `sphere.xml`) with steradian and with Mitsuba 3
`scalar_rgb`, the whole process each, in one run, alternating. Prints per size the median wall
time and the peak resident memory of each, their ratios, steradian's load phases and BVH build
rate, and its memory per triangle.

    python3 benches/large_mesh/run.py [--sizes 0.2,2,20] [--repeat 3] [--work DIR] [--no-build]

Needs the pip `mitsuba` package (its `mitsuba` command) and ~1 GB in --work (default
/tmp/steradian-large-mesh) for the PLY files, which `make_sphere.py` writes once.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
SCENE = os.path.join(HERE, "sphere.xml")


def run(cmd, env=None):
    """Wall time (s), peak RSS (bytes) and stdout of one process."""
    start = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env, text=True)
    out = p.stdout.read()
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        sys.exit(f"failed ({status}): {' '.join(cmd)}\n{out}")
    return wall, usage.ru_maxrss * 1024, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="0.2,2,20", help="millions of triangles")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--work", default="/tmp/steradian-large-mesh")
    ap.add_argument("--no-build", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    mitsuba = shutil.which("mitsuba")
    if not mitsuba:
        sys.exit("the `mitsuba` command is missing: pip install mitsuba")
    if not args.no_build:
        subprocess.run(["cargo", "build", "--release", "--locked", "-p", "steradian-cli"], cwd=REPO, check=True)
    steradian = os.path.join(REPO, "target", "release", "steradian")
    with open("/proc/cpuinfo") as f:
        cpu = next((l.split(":", 1)[1].strip() for l in f if l.startswith("model name")), "?")
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True, text=True).stdout.strip()
    version = subprocess.run([sys.executable, "-c", "import mitsuba; print(mitsuba.__version__)"],
                             capture_output=True, text=True).stdout.strip()
    print(f"# {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {cpu}, {os.cpu_count()} cores, "
          f"steradian {commit}, Mitsuba {version}")

    rows = []
    for size in [float(s) for s in args.sizes.split(",")]:
        tris = int(round(size * 1e6))
        mesh = os.path.join(args.work, f"sphere{tris}.ply")
        if not os.path.exists(mesh):
            subprocess.run([sys.executable, os.path.join(HERE, "make_sphere.py"), str(tris), mesh], check=True)
        ster, mits, phases = [], [], []
        for r in range(args.repeat):
            out_ster = os.path.join(args.work, "steradian.exr")
            wall, rss, out = run([steradian, "render", SCENE, "-D", f"mesh={mesh}", "-o", out_ster, "--quiet"])
            ster.append((wall, rss))
            m = re.search(r"time: load ([\d.]+) s \(parse ([\d.]+) s, files ([\d.-]+) s, BVH build ([\d.]+) s\)", out)
            b = re.search(r"bvh: (\d+) primitives, built at ([\d.]+) M/s, ([\d.]+) MB \(([\d.]+) bytes per primitive\)", out)
            if not m or not b:
                sys.exit(f"no phase times in steradian's output:\n{out}")
            phases.append([float(x) for x in m.groups()] + [int(b.group(1)), float(b.group(2)), float(b.group(4))])
            wall, rss, _ = run([mitsuba, "-m", "scalar_rgb", f"-Dmesh={mesh}", "-o", os.path.join(args.work, "mitsuba.exr"), SCENE])
            mits.append((wall, rss))
            print(f"  {size:g} M round {r + 1}: steradian {ster[-1][0]:.2f} s {ster[-1][1] / 1e9:.2f} GB, "
                  f"Mitsuba {mits[-1][0]:.2f} s {mits[-1][1] / 1e9:.2f} GB", flush=True)
        med = lambda xs: statistics.median(xs)  # noqa: E731
        sw, sr = med([w for w, _ in ster]), med([r for _, r in ster])
        mw, mr = med([w for w, _ in mits]), med([r for _, r in mits])
        ph = [med([p[i] for p in phases]) for i in range(len(phases[0]))]
        rows.append((size, phases[0][4], sw, sr, mw, mr, ph))

    print("\n| triangles | steradian wall / peak RSS | Mitsuba 3 `scalar_rgb` wall / peak RSS | wall ratio | RSS ratio | "
          "steradian load: files / BVH build | build rate | BVH B/tri | peak RSS B/tri |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for size, prims, sw, sr, mw, mr, ph in rows:
        load, parse, files, build, _, rate, bvh_b = ph
        print(f"| {prims / 1e6:.1f} M | {sw:.2f} s / {sr / 1e6:.0f} MB | {mw:.2f} s / {mr / 1e6:.0f} MB | "
              f"{sw / mw:.2f} | {sr / mr:.2f} | {files:.2f} s / {build:.2f} s | {rate:.2f} Mtri/s | {bvh_b:.1f} | "
              f"{sr / prims:.0f} |")
    print("\nratios are steradian's over Mitsuba's (below 1: steradian takes less); medians of "
          f"{args.repeat} alternating runs")


if __name__ == "__main__":
    main()
