#!/usr/bin/env python3
"""`steradian measure --target-error E` on the public closed-form cases.

    python3 benches/target_error/validation_cases.py [--target-error 0.01] [--seeds 5]
        [--exe target/release/steradian]

For every case of scenes/validation/cases.json (a meter with a closed-form reading) and every
seed, runs `steradian measure FILE --sensor ID --target-error E --seed S --json` and reports
the reading, its relative error against the closed form per channel, the samples per pixel
spent and the time. The rule `--target-error` states: the reading is within E of its value at
95 % confidence, so about 95 % of readings (and every one, for the deterministic cases) lie
within E of the closed form. Cases whose closed form is 0 are checked against E times the
largest closed-form value of the suite's other sensors of the same file (they read 0 exactly).
"""
import argparse
import json
import os
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--target-error", type=float, default=0.01)
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--exe", default=os.path.join(REPO, "target", "release", "steradian"))
    a = ap.parse_args()
    cases = json.load(open(os.path.join(REPO, "scenes", "validation", "cases.json")))["cases"]
    e = a.target_error
    within = total = 0
    print(f"steradian measure --target-error {e} on {len(cases)} closed-form cases, seeds 0..{a.seeds - 1}")
    print(f"{'case':<58} {'seed':>4} {'spp':>8} {'time s':>7} {'max |rel err|':>13} {'within':>6}")
    for c in cases:
        path = os.path.join(REPO, "scenes", "validation", os.path.basename(c["file"]))
        want = c["expected"]
        scale = max(abs(x) for x in want) or 1.0
        for seed in range(a.seeds):
            cmd = [a.exe, "measure", path, "--sensor", c["sensor_id"], "--target-error", str(e),
                   "--seed", str(seed), "--json"]
            t0 = time.perf_counter()
            p = subprocess.run(cmd, capture_output=True, text=True)
            dt = time.perf_counter() - t0
            if p.returncode != 0:
                sys.exit(f"{' '.join(cmd)} failed: {p.stderr.strip()}")
            m = json.loads(p.stdout.strip().splitlines()[-1])
            rel = [abs(v - w) / (abs(w) if w else scale) for v, w in zip(m["value"], want)]
            ok = max(rel) <= e
            within += ok
            total += 1
            name = f"{os.path.basename(c['file'])}:{c['sensor_id']}"
            print(f"{name:<58} {seed:>4} {m['spp']:>8} {dt:>7.2f} {max(rel):>13.2e} {'yes' if ok else 'NO':>6}")
    print(f"{within} of {total} readings within {e} of the closed form")
    return 0 if within == total else 1


if __name__ == "__main__":
    sys.exit(main())
