#!/usr/bin/env python3
"""Tabulates a Mitsuba 3 BSDF's eval and pdf at fixed direction pairs, for steradian's tests.

    python3 scripts/bsdf_table.py principled -o crates/steradian/src/bsdf/testdata/principled.csv

Each row: the configuration's index, wi (Mitsuba's: towards the viewer), wo (the sampled
direction), Mitsuba's eval (RGB, the BSDF times |cos θ of wo|) and pdf. The configurations are
the list below for the named plugin; steradian's test builds the same ones and compares its
ρ·|cos θ| and pdf to the table. Mitsuba's `llvm_ad_rgb` variant is used (the one the image
references are made with).
"""
import argparse
import csv
import math
import random

CONFIGS = {
    "principled": [
        {},
        {"base_color": [0.8, 0.3, 0.1], "roughness": 0.3, "metallic": 0.7, "specular": 0.6,
         "spec_tint": 0.4, "anisotropic": 0.5, "sheen": 0.3, "sheen_tint": 0.2,
         "clearcoat": 0.6, "clearcoat_gloss": 0.3, "spec_trans": 0.4},
        {"base_color": [0.2, 0.5, 0.9], "roughness": 0.15, "spec_trans": 0.9, "eta": 1.33},
        {"base_color": [0.9, 0.9, 0.2], "roughness": 0.8, "flatness": 0.6, "sheen": 1.0,
         "sheen_tint": 0.7},
        {"base_color": [0.6, 0.6, 0.6], "roughness": 0.05, "clearcoat": 1.0,
         "clearcoat_gloss": 0.9, "main_specular_sampling_rate": 0.5,
         "clearcoat_sampling_rate": 2.0, "diffuse_reflectance_sampling_rate": 0.7},
        {"base_color": [0.95, 0.64, 0.54], "roughness": 0.4, "metallic": 1.0,
         "anisotropic": 0.9},
    ],
    "principledthin": [
        {},
        {"base_color": [0.8, 0.3, 0.1], "roughness": 0.3, "spec_trans": 0.6, "eta": 1.4,
         "spec_tint": 0.5, "anisotropic": 0.4, "sheen": 0.5, "sheen_tint": 0.3,
         "diff_trans": 0.8, "flatness": 0.4},
        {"base_color": [0.2, 0.5, 0.9], "roughness": 0.6, "diff_trans": 1.5},
        {"base_color": [0.5, 0.9, 0.4], "roughness": 0.1, "spec_trans": 1.0, "eta": 1.6,
         "specular_reflectance_sampling_rate": 0.5,
         "specular_transmittance_sampling_rate": 2.0,
         "diffuse_transmittance_sampling_rate": 0.3,
         "diffuse_reflectance_sampling_rate": 0.8},
    ],
    # the synthetic RGL-layout files of scripts/make_measured_bsdf.py
    "measured": [
        {"filename": "crates/steradian/src/bsdf/testdata/measured_iso_rgb.bsdf"},
        {"filename": "crates/steradian/src/bsdf/testdata/measured_aniso_rgb.bsdf"},
    ],
    # in the hair frame y runs along the fibre and z is the normal
    "hair": [
        {},
        {"eumelanin": 0.2, "pheomelanin": 0.4},
        {"sigma_a": [0.2, 0.25, 0.7], "scale": 2.0, "longitudinal_roughness": 0.15,
         "azimuthal_roughness": 0.6},
        {"eumelanin": 0.05, "pheomelanin": 0.05, "scale_tilt": 6.0, "int_ior": 1.4,
         "longitudinal_roughness": 0.5, "azimuthal_roughness": 0.2},
    ],
}


def mitsuba_dict(plugin, cfg):
    d = {"type": plugin}
    for k, v in cfg.items():
        d[k] = {"type": "rgb", "value": v} if isinstance(v, list) else v
    return d


def direction(rng, lower):
    z = rng.uniform(0.02, 1.0) * (-1.0 if lower else 1.0)
    phi = rng.uniform(0.0, 2.0 * math.pi)
    s = math.sqrt(1.0 - z * z)
    return [s * math.cos(phi), s * math.sin(phi), z]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("plugin", choices=sorted(CONFIGS))
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--pairs", type=int, default=48, help="direction pairs per configuration")
    a = ap.parse_args()

    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    rng = random.Random(7)
    rows = []
    for ci, cfg in enumerate(CONFIGS[a.plugin]):
        bsdf = mi.load_dict(mitsuba_dict(a.plugin, cfg))
        pairs = []
        for k in range(a.pairs):
            wi = direction(rng, lower=(k % 4 == 3))
            if k % 3 == 0:
                # near the specular peak, where the glossy lobes are large
                wo = [-wi[0] + rng.gauss(0, 0.15), -wi[1] + rng.gauss(0, 0.15), wi[2]]
                n = math.sqrt(sum(c * c for c in wo))
                wo = [c / n for c in wo]
            else:
                wo = direction(rng, lower=(k % 5 == 4))
            pairs.append((wi, wo))
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f([p[0][0] for p in pairs], [p[0][1] for p in pairs],
                            [p[0][2] for p in pairs])
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        si.uv = mi.Point2f(0.5, 0.5)
        wo = mi.Vector3f([p[1][0] for p in pairs], [p[1][1] for p in pairs],
                         [p[1][2] for p in pairs])
        ctx = mi.BSDFContext()
        f = bsdf.eval(ctx, si, wo)
        pdf = bsdf.pdf(ctx, si, wo)
        fr, fg, fb, pd = (list(map(float, c)) for c in (f.x, f.y, f.z, pdf))
        for k, (wi_, wo_) in enumerate(pairs):
            rows.append([ci, *wi_, *wo_, fr[k], fg[k], fb[k], pd[k]])
    with open(a.output, "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["config", "wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z",
                    "f_r", "f_g", "f_b", "pdf"])
        for r in rows:
            w.writerow([r[0]] + [repr(float(x)) for x in r[1:]])


if __name__ == "__main__":
    main()
