#!/usr/bin/env python3
"""Ray's overhead on one machine: a distributed render of cornell (256×256) at 256 spp with
2 workers against the local 2-thread render, in one run; and the constants of the scaling
model (docs/design/2026-12-06-ray-scaling.md): per-task overhead, bundle size, sums size and
merge cost per pass.

    pip install . ray            # the default release build of the extension
    python3 benches/ray_vs_local.py [--spp 256] [--res 256] [--repeat 2] [--json out.json]

Prints the local and Ray samples/s (Ray cold: the first call, which starts the workers and
loads the scene on each; warm: later calls), their ratio, the task count and per-task times,
and checks that every image is the local image bit for bit.
"""

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import ray

import steradian
from steradian import distributed

REPO = Path(__file__).resolve().parents[1]
CORNELL = REPO / "scenes" / "cornell-box.xml"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--res", type=int, default=256)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--tasks", type=int, default=None, help="default: steradian's (one per pass)")
    ap.add_argument("--repeat", type=int, default=2, help="warm Ray runs and local runs")
    ap.add_argument("--json", default=None)
    args = ap.parse_args()
    defaults = {"res": args.res}
    scene = steradian.load_file(CORNELL, **defaults)
    pixels = args.res * args.res
    samples = pixels * args.spp
    print(f"# cornell {args.res}x{args.res} at {args.spp} spp, {os.cpu_count()} CPUs, "
          f"load average {os.getloadavg()[0]:.2f}", file=sys.stderr)

    ray.init(num_cpus=args.workers, include_dashboard=False, log_to_driver=False, configure_logging=False)
    runs = {"local": [], "ray_cold": None, "ray_warm": []}

    def local():
        t = time.perf_counter()
        img = scene.render(args.spp, 0, threads=args.workers)
        return time.perf_counter() - t, img

    def distributed_run():
        t = time.perf_counter()
        sums, sc, report = distributed.render_sums(
            CORNELL, args.spp, 0, tasks=args.tasks, progress=False, defaults=defaults
        )
        return time.perf_counter() - t, sc.develop(sums), report

    # alternate: local, Ray (cold), then local/Ray warm pairs
    t_local, want = local()
    runs["local"].append(t_local)
    t_cold, img, report = distributed_run()
    assert np.array_equal(img.view(np.uint32), want.view(np.uint32)), "Ray image differs"
    runs["ray_cold"] = t_cold
    for _ in range(args.repeat):
        t_local, _ = local()
        runs["local"].append(t_local)
        t_warm, img, report = distributed_run()
        assert np.array_equal(img.view(np.uint32), want.view(np.uint32)), "Ray image differs"
        runs["ray_warm"].append(t_warm)

    # the model's constants
    plan = scene.plan(args.spp, 0)
    bounds = plan["pass_bounds"]
    sums = scene.render_range(0, bounds[1], args.spp, 0, branches=plan["branches"])
    film_bytes = len(sums.to_bytes())
    part = scene.render_range(bounds[1], bounds[2] - bounds[1], args.spp, 0, branches=plan["branches"])
    t = time.perf_counter()
    reps = 20
    for _ in range(reps):
        s = steradian.Sums.from_bytes(sums.to_bytes())
        s.append(part)
    merge = (time.perf_counter() - t) / reps

    @ray.remote(num_cpus=1)
    def noop(x):
        return x

    ray.get([noop.remote(i) for i in range(20)])  # workers up
    t = time.perf_counter()
    n = 200
    ray.get([noop.remote(i) for i in range(n)])
    task_overhead = (time.perf_counter() - t) / n * args.workers  # CPU-seconds per task

    med_local = statistics.median(runs["local"])
    med_warm = statistics.median(runs["ray_warm"])
    per_task = sorted(report.task_seconds.values())
    out = {
        "spp": args.spp,
        "res": args.res,
        "workers": args.workers,
        "passes": len(bounds) - 1,
        "branches": plan["branches"],
        "tasks": report.tasks,
        "local_s": runs["local"],
        "ray_cold_s": runs["ray_cold"],
        "ray_warm_s": runs["ray_warm"],
        "local_msamples_per_s": samples / med_local / 1e6,
        "ray_warm_msamples_per_s": samples / med_warm / 1e6,
        "ray_cold_msamples_per_s": samples / runs["ray_cold"] / 1e6,
        "ratio_warm": med_local / med_warm,
        "ratio_cold": med_local / runs["ray_cold"],
        "task_seconds_min_median_max": [per_task[0], statistics.median(per_task), per_task[-1]],
        "bundle_bytes": report.bundle_bytes,
        "sums_bytes_per_pass": film_bytes,
        "merge_s_per_pass": merge,
        "ray_task_overhead_cpu_s": task_overhead,
    }
    print(f"local 2-thread render: {out['local_msamples_per_s']:.3f} Msamples/s "
          f"(median of {len(runs['local'])}: {med_local:.2f} s)")
    print(f"Ray, {args.workers} workers, {report.tasks} tasks over {out['passes']} passes: "
          f"warm {out['ray_warm_msamples_per_s']:.3f} Msamples/s ({med_warm:.2f} s), "
          f"cold {out['ray_cold_msamples_per_s']:.3f} Msamples/s ({runs['ray_cold']:.2f} s)")
    print(f"ratio Ray/local: warm {out['ratio_warm']:.3f}, cold {out['ratio_cold']:.3f}")
    print("per-task render seconds: min {:.2f}, median {:.2f}, max {:.2f}".format(*out["task_seconds_min_median_max"]))
    print(f"bundle {out['bundle_bytes']} B; sums {film_bytes / 1e6:.2f} MB per pass; "
          f"from_bytes + append {1e3 * merge:.2f} ms per pass; Ray task overhead "
          f"{1e3 * task_overhead:.2f} CPU-ms per task")
    print("all Ray images equal the local image bit for bit")
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=2))
    ray.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
