#!/usr/bin/env python3
"""The 64-spp render time of cornell: steradian vs Mitsuba 3 (scalar_rgb and llvm_ad_rgb),
measured in one run.

    python3 benches/cornell_64spp.py [--repeat 5] [--threads N] [--json FILE]

Runs benches/render_vs_mitsuba.py's benchmark on the cornell scene at 64 spp with both Mitsuba
variants, alternating steradian / scalar_rgb / llvm_ad_rgb --repeat times, and prints the
medians:

  steradian    whole process (start-up, load, render, EXR/PNG write), and the render time it
               prints itself
  scalar_rgb   warm mi.render() (scene loaded and rendered once before, untimed)
  llvm_ad_rgb  warm mi.render() (the first, untimed render JIT-compiles the kernel; its time is
               shown as "first render")

and the ratio Mitsuba time / steradian time (> 1: steradian is faster), plus relMSE against the
reference so that a fast but wrong render does not go unnoticed.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_vs_mitsuba as rvm  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per renderer; the median is reported")
    ap.add_argument("--threads", type=int, default=0, help="worker threads for both renderers (0 = all cores)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", metavar="FILE", help="also write the full results as JSON to FILE")
    ap.add_argument("--no-pgo", action="store_true", help="time the plain release build, not the profile-guided one")
    ap.add_argument("--no-build", action="store_true", help="use the binary already built")
    a = ap.parse_args()
    variants = ["scalar_rgb", "llvm_ad_rgb"]
    res = rvm.run(["cornell"], 64, variants, a.repeat, a.threads, a.seed, build=not a.no_build, pgo=not a.no_pgo)
    if not res["scenes"]:
        sys.exit("cornell was not rendered: " + "; ".join(s["reason"] for s in res["skipped"]))
    e = res["scenes"][0]
    st = e["steradian"]
    w, h = e["res"] or ("?", "?")
    print(f"cornell {w}x{h}, 64 spp, seed {a.seed}: median of {a.repeat} runs, alternating, "
          f"{res['threads']} threads on {res['cpu_count']} cores")
    print(f"load average at start {res['loadavg_start']}, at end {res['loadavg_end']}")
    print()
    print(f"{'renderer':<28} {'time s':>7} {'cpu s':>7} {'vs steradian':>13} {'relMSE':>10}   runs")
    print(f"{'steradian (whole process)':<28} {st['time_s']:>7.3f} {st['cpu_s']:>7.3f} {'1.00x':>13} "
          f"{st['relmse']:>10.3e}   {st['times']}")
    print(f"{'steradian (own render time)':<28} {st['render_s']:>7.3f} {'':>7} {'':>13} {'':>10}")
    for v in variants:
        m = e["mitsuba"][v]
        print(f"{'Mitsuba ' + v + ' (warm)':<28} {m['time_s']:>7.3f} {m['cpu_s']:>7.3f} "
              f"{m['time_s'] / st['time_s']:>12.2f}x {m['relmse']:>10.3e}   {m['times']}")
    for v in variants:
        m = e["mitsuba"][v]
        print(f"  Mitsuba {v}: scene load {m['load_s']:.3f} s, first render {m['first_render_s']:.3f} s"
              + (" (includes the LLVM JIT compile unless Dr.Jit's kernel cache had it)" if v.startswith("llvm") else ""))
    print("'vs steradian' = Mitsuba time / steradian whole-process time (> 1: steradian is faster)")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
