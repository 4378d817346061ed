#!/usr/bin/env python3
"""Makes a Mitsuba 3 reference for steradian's image tests: the mean image and the per-sample
variance image that Mitsuba's render-test rule (`steradian::film::z_test`) needs.

    pip install mitsuba numpy
    python3 scripts/mitsuba_reference.py SCENE.xml --spp 4096 --passes 64 -o tests/reference/X

writes X-ref.exr (mean radiance, float32 RGB) and X-var.exr (variance of one sample's value);
for a film with an alpha channel (`rgba`) also X-alpha-ref.exr and X-alpha-var.exr, the same
for alpha (in all three channels).
The render is split into `passes` renders of spp/passes samples with seeds 0, 1, ...; the
per-sample variance is spp/passes times the unbiased variance of the pass means (each pass
mean is an average of spp/passes independent samples: independent sampler, so the estimate
is unbiased; with 64 passes it is within about 18 % of the truth, which only scales the
test's tolerance). `-D key=value` overrides a <default>.
"""
import argparse
import sys
import time


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--spp", type=int, default=4096)
    ap.add_argument("--passes", type=int, default=64)
    ap.add_argument("--variant", default="scalar_rgb")
    ap.add_argument("-o", "--output", required=True, help="output prefix: PREFIX-ref.exr, PREFIX-var.exr")
    ap.add_argument("-D", dest="defines", action="append", default=[])
    args = ap.parse_args()
    if args.spp % args.passes or args.passes < 2:
        sys.exit("--spp must be a multiple of --passes, and --passes at least 2")

    import numpy as np
    import mitsuba as mi
    mi.set_variant(args.variant)
    params = dict(d.split("=", 1) for d in args.defines)
    # the independent sampler keeps pass means independent (Sobol-like samplers correlate
    # their points across seeds only through the scramble, but stay safe)
    scene = mi.load_file(args.scene, **params)
    sensor = scene.sensors()[0]
    spp_pass = args.spp // args.passes
    t0 = time.perf_counter()
    total = None
    total2 = None
    for k in range(args.passes):
        img = np.array(mi.render(scene, sensor=sensor, spp=spp_pass, seed=k), dtype=np.float64)
        # an `rgba` film's alpha channel, broadcast to three channels
        img = img[..., [0, 1, 2, 3, 3, 3]] if img.shape[-1] == 4 else img[..., :3]
        total = img if total is None else total + img
        total2 = img * img if total2 is None else total2 + img * img
        print(f"pass {k + 1}/{args.passes} ({time.perf_counter() - t0:.0f} s)", file=sys.stderr, flush=True)
    n = args.passes
    mean = total / n
    var_of_pass_mean = np.maximum(total2 - n * mean * mean, 0.0) / (n - 1)
    var_sample = var_of_pass_mean * spp_pass
    mi.Bitmap(mean[..., :3].astype(np.float32)).write(args.output + "-ref.exr")
    mi.Bitmap(var_sample[..., :3].astype(np.float32)).write(args.output + "-var.exr")
    if mean.shape[-1] == 6:
        mi.Bitmap(mean[..., 3:].astype(np.float32)).write(args.output + "-alpha-ref.exr")
        mi.Bitmap(var_sample[..., 3:].astype(np.float32)).write(args.output + "-alpha-var.exr")
        print(f"wrote the alpha channel to {args.output}-alpha-ref.exr and -alpha-var.exr")
    print(f"wrote {args.output}-ref.exr and {args.output}-var.exr: {args.spp} spp in {n} passes, "
          f"{time.perf_counter() - t0:.0f} s, mitsuba {mi.__version__} {args.variant}")


if __name__ == "__main__":
    main()
