#!/usr/bin/env python3
"""The lighting engineer's calculation in one run: illuminance on the 10 x 10 work plane of the
4 x 4 x 3 m room with the 3000 lm IES downlight (`scenes/lighting_room.xml`, all bounces),
by Radiance's uncached Monte Carlo (`rtrace -I -ab 10 -aa 0 -ad 1024 -u+`, replicated runs for
the standard errors) and by steradian's `workplane` (`steradian measure --json`), both on one
thread. Prints each tool's time, its per-point relative standard error (median over the
points), the time each would need for 0.2 % per point (time x (rel. se / 0.002)^2: Monte Carlo
error falls as 1/sqrt(time)), their ratio, and whether the two averages agree.

    pip install pyradiance==1.3.1 numpy
    python3 benches/radiance/work_plane_vs_radiance.py [--replicates 4] [--spp N] [--batch N]
        [--no-build]

steradian measures as the scene says (64 samples, each the mean of 64 Sobol points under a
scramble of its own); `--spp` and `--batch` override (`steradian measure --batch`; `--batch 1`
is one independent point per sample).

`room.py` and `run_radiance.py` are the peer harness's (they write the same room for
Radiance: `ies2rad` on the same synthetic IES file, the same reflectances and grid).
"""
import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent
sys.path.insert(0, str(HERE))
import room  # noqa: E402
import run_radiance as rr  # noqa: E402

TARGET = 0.002  # the per-point relative error


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--replicates", type=int, default=4, help="Radiance runs (its standard error)")
    ap.add_argument("--spp", type=int, default=None, help="steradian samples per point (default: the scene's, 64)")
    ap.add_argument("--batch", type=int, default=None, help="Sobol points per steradian sample (default: the scene's, 64)")
    ap.add_argument("--work", type=Path, default=Path("/tmp/steradian-radiance"))
    ap.add_argument("--no-build", action="store_true")
    args = ap.parse_args()
    if not args.no_build:
        subprocess.run(["cargo", "build", "--release", "--locked", "-p", "steradian-cli"], cwd=REPO, check=True)
    steradian = REPO / "target" / "release" / "steradian"
    scene = REPO / "scenes" / "lighting_room.xml"
    args.work.mkdir(parents=True, exist_ok=True)
    os.chdir(args.work)  # RAYPATH holds '.', where ies2rad writes its data file

    # Radiance
    pts = room.grid_points()
    up = np.tile([0.0, 0.0, 1.0], (len(pts), 1))
    room_text = rr.room_rad(room.RHO_WALL, room.RHO_CEILING, room.RHO_FLOOR)
    octree = rr.octree_for(args.work, "room_ies", [room_text, rr.ies_lamp_rad(args.work, "downlight", 0.0, 90.0)])
    runs = [rr.run_rtrace(octree, pts, up, rr.QUALITIES["mc10"], 1) for _ in range(args.replicates)]
    rad_lux = np.mean([r[0] for r in runs], axis=0)
    rad_se = np.std([r[0] for r in runs], axis=0, ddof=1) / np.sqrt(args.replicates)
    rad_time = sum(r[1] for r in runs)

    # steradian: the whole process, one thread
    t0 = time.perf_counter()
    out = subprocess.run(
        [str(steradian), "measure", str(scene), "--json", "--threads", "1", "--seed", "1"]
        + (["--spp", str(args.spp)] if args.spp else []) + (["--batch", str(args.batch)] if args.batch else []),
        check=True, capture_output=True, text=True).stdout
    ster_time = time.perf_counter() - t0
    d = json.loads(out)
    # the plan is seen from above with +y up: row j holds y from the top; the Radiance grid's
    # order is room.grid_points()'s, so both are compared through their sorted positions
    ster_lux = np.array(d["values"], float)
    ster_se = np.array(d["stderr"], float)

    def summary(name, lux, se, secs):
        rel = se / lux
        med = float(np.median(rel))
        t_target = secs * (med / TARGET) ** 2
        e_avg = float(lux.mean())
        se_avg = float(np.sqrt(np.sum(se ** 2)) / lux.size)
        print(f"{name:10s} {secs:8.2f} s  Eavg {e_avg:8.3f} ± {se_avg:.3f} lx  median point rel. se "
              f"{100 * med:.3f} %  time for {100 * TARGET:.1f} % per point {t_target:8.1f} s")
        return e_avg, se_avg, t_target

    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    print(f"# {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {cpu}, one thread each; "
          f"Radiance {args.replicates} runs of mc10, steradian {args.spp or 'scene'} spp × "
          f"{args.batch or 'scene'} points")
    ra, rs, rt = summary("Radiance", rad_lux, rad_se, rad_time)
    sa, ss, st = summary("steradian", ster_lux.ravel(), ster_se.ravel(), ster_time)
    z = (sa - ra) / np.hypot(rs, ss)
    print(f"Eavg difference {sa - ra:+.3f} lx (z = {z:+.2f}); "
          f"time to {100 * TARGET:.1f} % per point, Radiance over steradian: {rt / st:.2f} "
          f"(above 1: steradian is faster; goal >= 2)")


if __name__ == "__main__":
    main()
