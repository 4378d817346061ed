#!/usr/bin/env python3
"""Writes crates/steradian/src/emitter/testdata/sunsky_eval.csv: Mitsuba 3's own `sunsky`
radiance (`scalar_rgb` `eval`) in three configurations at 18 directions each (the sun's
centre, 0.3, 0.6 and 0.85 of its radius, just outside it, the zenith, horizon points, the
sky, below the horizon), which `steradian::emitter::sunsky`'s test compares with.

    pip install mitsuba numpy
    python3 scripts/sunsky_eval_table.py

Columns: config, the world direction towards the sky (dx, dy, dz; float32 values), r, g, b.
The configurations: Mitsuba's defaults; `sun_direction` (0.3, -0.5, 0.6) with turbidity 5,
albedo 0.5, sky_scale 2, sun_scale 0.5; Paris (48.85 N, 2.35 E, UTC+1) at 09:30 on
20 March 2024 with `complex_sun`. Prints the sun direction Mitsuba computes for each.
"""
import csv
import os

import numpy as np
import drjit as dr
import mitsuba as mi

mi.set_variant('scalar_rgb')

CONFIGS = [
    ('default', {}),
    ('sundir_t5', {'sun_direction': [0.3, -0.5, 0.6], 'turbidity': 5.0, 'albedo': 0.5,
                   'sky_scale': 2.0, 'sun_scale': 0.5}),
    ('paris_complex', {'latitude': 48.85, 'longitude': 2.35, 'timezone': 1.0, 'year': 2024,
                       'month': 3, 'day': 20, 'hour': 9.0, 'minute': 30.0, 'second': 0.0,
                       'complex_sun': True}),
]


def radiance(emitter, d):
    si = dr.zeros(mi.SurfaceInteraction3f)
    si.wi = -mi.Vector3f(*[float(x) for x in d])
    c = emitter.eval(si)
    return [c[0], c[1], c[2]]


def main():
    # Mitsuba's half aperture of the default sun, radians, rounded as it rounds it
    h = float(np.float32(np.float32(0.5 * 0.5358) * np.float32(np.pi / 180)))
    rows = []
    for name, params in CONFIGS:
        e = mi.load_dict(dict(type='sunsky', **params))
        sun = np.array(mi.traverse(e)['sun_direction'], dtype=np.float64)
        sun /= np.linalg.norm(sun)
        print(name, 'sun direction', sun)
        t1 = np.cross(sun, [0, 0, 1.0])
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(sun, t1)
        dirs = []
        for frac, ang in [(0, 0), (0.3, 0), (0.6, 2), (0.85, 4), (1.3, 1), (3, 0.5)]:
            a = frac * h
            dirs.append(np.cos(a) * sun + np.sin(a) * (np.cos(ang) * t1 + np.sin(ang) * t2))
        for v in [[0, 0, 1], [1, 0, 0], [0, 1, 0], [0, -1, 0.05], [1, 1, 1], [-0.5, 0.2, 0.3],
                  [0.2, -0.7, 0.4], [-sun[0], -sun[1], sun[2]], [0.6, 0.3, 0.05],
                  [0.1, 0.1, -0.5], [0, 0, -1], [0.5, 0.5, -1e-3]]:
            v = np.asarray(v, float)
            dirs.append(v / np.linalg.norm(v))
        for v in dirs:
            v32 = np.array(v, dtype=np.float32).astype(np.float64)
            rows.append([name, *v32, *radiance(e, v32)])
    out = os.path.join(os.path.dirname(__file__), '..', 'crates', 'steradian', 'src', 'emitter',
                       'testdata', 'sunsky_eval.csv')
    with open(out, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['config', 'dx', 'dy', 'dz', 'r', 'g', 'b'])
        for r in rows:
            w.writerow([r[0]] + ['%.9g' % x for x in r[1:]])
    print(out, len(rows), 'rows')


if __name__ == '__main__':
    main()
