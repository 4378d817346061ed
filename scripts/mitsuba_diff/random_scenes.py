"""Random scenes against Mitsuba 3 (see harness.py): each seed draws a small scene from the
plugins real scenes combine (shapes, instances, PLY meshes; diffuse, conductors, plastics,
dielectrics, principled, wrapped in twosided, bumpmap, normalmap, mask or blendbsdf, with
bitmap and checkerboard textures; point, spot, directional, area, constant and envmap
lights; path, volpath, direct, prb and ptracer; perspective, thinlens and orthographic
cameras; every reconstruction filter) and compares steradian's image with Mitsuba's. A
failure is a lead, not a verdict: heavy-tailed scenes (caustics of small or delta lights
through rough glass) fail Mitsuba's own control too (DIFF_CONTROL=1), and Mitsuba 3.9.1's
known errors fail on purpose (blendbsdf of a smooth and a delta BSDF, direct's delta lights
with emitter_samples > 1; the plugins' manuals). From the repository root:

    python3 scripts/mitsuba_diff/random_scenes.py [FIRST_SEED] [COUNT]

2026-12-07 (AMD EPYC, 2 cores): seeds 0-99, and 120 scenes of two simpler generators (a
sun-lit sky; homogeneous media and fog), found the thindielectric mismatch (now
tests/thindielectric.rs), both Mitsuba errors above, Mitsuba's volpath lighting a camera fog
of unbounded extent from a constant or envmap sky (steradian: black, the physical limit; the
loader now warns), and otherwise heavy-tailed scenes only. Seeds 100-159 found Mitsuba's
`ptracer` lighting a scene wrongly from a turned envmap (tests/ptracer.rs), the two Mitsuba
errors above again, and heavy-tailed scenes; `ptracer` behind `thinlens` or `orthographic`
cameras, which Mitsuba renders, steradian refuses with a message (`thinlens` is supported
since). 2026-12-08: seeds 200-239 found only the two Mitsuba errors above, `twosided` around
a transmitting BSDF (refused by both) and one heavy-tailed scene; seeds 300-481 with their PLY
sphere swapped for `ellipsoids`/`ellipsoidsmesh` clouds (16 scenes) found the shells'
texture coordinates in a vertex order not Mitsuba's (now its own templates) and Mitsuba's
variant-dependent images of small ellipsoids (see shape/ellipsoids.rs)."""

import os
import random
import shutil
import sys

import numpy as np

from harness import ROOT, WORK, mi, run

REFERENCE = os.path.join(ROOT, 'crates', 'steradian-mitsuba', 'tests', 'reference')
for f in ('textures/wall.png', 'textures/leaf_mask.png', 'mesh_attribute/sphere.ply'):
    shutil.copy(os.path.join(REFERENCE, f), WORK)


def write_sky(path):
    """A smooth sky with a soft bright patch: an environment whose light is well sampled by
    both renderers (a 2-degree sun makes every glossy scene heavy-tailed)."""
    h, w = 32, 64
    y, x = np.mgrid[0:h, 0:w]
    th, ph = (y + 0.5) / h * np.pi, (x + 0.5) / w * 2 * np.pi
    img = np.stack([0.6 + 0.3 * np.cos(th) + 0.15 * np.sin(ph), 0.6 + 0.3 * np.cos(th),
                    0.8 + 0.15 * np.cos(th) * np.cos(ph)], -1)
    img[(th < 0.6) & (np.abs(ph - 2) < 0.5)] *= 6
    mi.Bitmap(img.astype(np.float32)).write(path)


write_sky(os.path.join(WORK, 'smooth.exr'))


def gen(seed):
    r = random.Random(seed)
    f = lambda a, b: round(r.uniform(a, b), 3)
    rgb = lambda lo=0.05, hi=0.9: f"{f(lo,hi)}, {f(lo,hi)}, {f(lo,hi)}"
    def refl(name="reflectance"):
        k = r.random()
        if k < 0.2: return f'<texture type="bitmap" name="{name}"><string name="filename" value="wall.png"/><string name="filter_type" value="{r.choice(["bilinear","nearest"])}"/><string name="wrap_mode" value="{r.choice(["repeat","mirror","clamp"])}"/><transform name="to_uv"><scale x="{f(1,3)}" y="{f(1,3)}"/></transform></texture>'
        if k < 0.35: return f'<texture type="checkerboard" name="{name}"><rgb name="color0" value="{rgb()}"/><rgb name="color1" value="{rgb()}"/><transform name="to_uv"><scale value="{r.randint(2,6)}"/></transform></texture>'
        return f'<rgb name="{name}" value="{rgb()}"/>'
    def base():
        t = r.choice(["diffuse","roughconductor","roughplastic","plastic","principled","conductor","dielectric","roughdielectric","thindielectric"])
        if t == "diffuse": return f'<bsdf type="diffuse">{refl()}</bsdf>'
        if t == "roughconductor": return f'<bsdf type="roughconductor"><string name="material" value="{r.choice(["Au","Cu","Al","Ag","Cr","a-C"])}"/><string name="distribution" value="{r.choice(["beckmann","ggx"])}"/><float name="alpha" value="{f(0.05,0.5)}"/></bsdf>'
        if t == "roughplastic": return f'<bsdf type="roughplastic">{refl("diffuse_reflectance")}<float name="alpha" value="{f(0.05,0.5)}"/></bsdf>'
        if t == "plastic": return f'<bsdf type="plastic">{refl("diffuse_reflectance")}</bsdf>'
        if t == "principled": return f'<bsdf type="principled">{refl("base_color")}<float name="metallic" value="{f(0,1)}"/><float name="roughness" value="{f(0.2,0.9)}"/></bsdf>'
        if t == "conductor": return '<bsdf type="conductor"/>'
        if t == "dielectric": return f'<bsdf type="dielectric"><float name="int_ior" value="{f(1.3,1.7)}"/></bsdf>'
        if t == "roughdielectric": return f'<bsdf type="roughdielectric"><float name="alpha" value="{f(0.1,0.4)}"/></bsdf>'
        return '<bsdf type="thindielectric"/>'
    def bsdf():
        k = r.random()
        b = base()
        if k < 0.12: return f'<bsdf type="twosided">{b}</bsdf>'
        if k < 0.22: return f'<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture><float name="scale" value="{f(0.2,2)}"/>{b}</bsdf>'
        if k < 0.32: return f'<bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normals.png"/><boolean name="raw" value="true"/></texture>{b}</bsdf>'
        if k < 0.40: return f'<bsdf type="mask"><texture type="bitmap" name="opacity"><string name="filename" value="leaf_mask.png"/><boolean name="raw" value="true"/></texture>{b}</bsdf>'
        if k < 0.48: return f'<bsdf type="blendbsdf"><float name="weight" value="{f(0.1,0.9)}"/>{b}{base()}</bsdf>'
        return b
    shapes = []
    fb = bsdf() if r.random() < 0.4 else '<bsdf type="diffuse"/>'
    shapes.append(f'<shape type="rectangle"><transform name="to_world"><scale value="5"/><rotate x="1" angle="-90"/></transform>{fb}</shape>')
    group = r.random() < 0.25
    if group:
        shapes.append(f'<shape type="shapegroup" id="g"><shape type="sphere"><float name="radius" value="0.3"/>{bsdf()}</shape><shape type="cube"><transform name="to_world"><scale value="0.2"/><translate y="0.45"/></transform>{bsdf()}</shape></shape>')
        for i in range(r.randint(1,3)):
            shapes.append(f'<shape type="instance"><ref id="g"/><transform name="to_world"><scale value="{f(0.7,1.4)}"/><rotate y="1" angle="{f(0,360)}"/><translate x="{f(-2,2)}" y="0.4" z="{f(-1.5,1)}"/></transform></shape>')
    for i in range(r.randint(1, 3)):
        t = r.choice(["sphere","cube","cylinder","disk","rectangle","ply"])
        pos = (f(-2,2), f(0.4,1.2), f(-1.5,1)); s = f(0.3, 0.6); b = bsdf()
        if t == "sphere": shapes.append(f'<shape type="sphere"><point name="center" x="{pos[0]}" y="{pos[1]}" z="{pos[2]}"/><float name="radius" value="{s}"/>{b}</shape>')
        elif t == "ply": shapes.append(f'<shape type="ply"><string name="filename" value="sphere.ply"/><transform name="to_world"><scale value="{s}"/><translate x="{pos[0]}" y="{pos[1]}" z="{pos[2]}"/></transform>{b}</shape>')
        else: shapes.append(f'<shape type="{t}"><transform name="to_world"><scale value="{s}"/><rotate y="1" angle="{f(0,360)}"/><rotate x="1" angle="{f(-40,40)}"/><translate x="{pos[0]}" y="{pos[1]}" z="{pos[2]}"/></transform>{b}</shape>')
    emitters = []
    for k in r.sample(["constant","envmap","point","spot","directional","area","areasphere"], r.randint(1, 3)):
        if k == "constant" and not any("envmap" in e for e in emitters): emitters.append(f'<emitter type="constant"><rgb name="radiance" value="{rgb(0.2,1)}"/></emitter>')
        if k == "envmap" and not any("constant" in e for e in emitters): emitters.append(f'<emitter type="envmap"><string name="filename" value="smooth.exr"/><float name="scale" value="{f(0.3,1)}"/><transform name="to_world"><rotate y="1" angle="{f(0,360)}"/></transform></emitter>')
        if k == "point": emitters.append(f'<emitter type="point"><point name="position" x="{f(-2,2)}" y="{f(2,4)}" z="{f(-1,3)}"/><rgb name="intensity" value="{rgb(5,20)}"/></emitter>')
        if k == "spot": emitters.append(f'<emitter type="spot"><transform name="to_world"><lookat origin="{f(-2,2)}, {f(3,5)}, {f(1,3)}" target="0, 0, 0"/></transform><rgb name="intensity" value="{rgb(10,40)}"/><float name="cutoff_angle" value="{f(20,40)}"/><float name="beam_width" value="{f(10,19)}"/></emitter>')
        if k == "directional": emitters.append(f'<emitter type="directional"><vector name="direction" x="{f(-1,1)}" y="-1" z="{f(-1,0)}"/><rgb name="irradiance" value="{rgb(1,3)}"/></emitter>')
        if k == "area": shapes.append(f'<shape type="rectangle"><transform name="to_world"><scale value="{f(0.3,1)}"/><rotate x="1" angle="90"/><translate x="{f(-1,1)}" y="{f(2.5,3.5)}" z="{f(-1,1)}"/></transform><emitter type="area"><rgb name="radiance" value="{rgb(3,10)}"/></emitter></shape>')
        if k == "areasphere": shapes.append(f'<shape type="sphere"><point name="center" x="{f(-2,2)}" y="{f(2.5,3.5)}" z="{f(-1,2)}"/><float name="radius" value="{f(0.2,0.4)}"/><emitter type="area"><rgb name="radiance" value="{rgb(3,10)}"/></emitter></shape>')
    if not emitters and not any("emitter" in s for s in shapes):
        emitters.append('<emitter type="constant"/>')
    integ = r.choice(["path","path","path","volpath","direct","prb","ptracer"])
    md = r.choice([-1, 2, 3, 5, 8])
    hide = r.random() < 0.1
    if integ == "direct": ix = f'<integrator type="direct"><integer name="emitter_samples" value="{r.randint(1,3)}"/><integer name="bsdf_samples" value="{r.randint(0,2)}"/></integrator>'
    else: ix = f'<integrator type="{integ}"><integer name="max_depth" value="{md}"/>' + ('<boolean name="hide_emitters" value="true"/>' if hide else '') + '</integrator>'
    sensor = r.choice(["perspective","perspective","thinlens","orthographic"])
    sx = ''
    if sensor == "thinlens": sx = f'<float name="aperture_radius" value="{f(0.02,0.1)}"/><float name="focus_distance" value="{f(5,8)}"/>'
    if sensor == "orthographic":
        tfm = f'<transform name="to_world"><scale x="3" y="3"/><lookat origin="{f(-1,1)}, {f(2,3.5)}, {f(6,8)}" target="0, 0.6, 0" up="0, 1, 0"/></transform>'
    else:
        tfm = f'<transform name="to_world"><lookat origin="{f(-1,1)}, {f(2,3.5)}, {f(6,8)}" target="0, 0.6, 0" up="0, 1, 0"/></transform>'
        sx += f'<float name="fov" value="{f(35,55)}"/>'
    rf = r.choice(["box","tent","gaussian","mitchell","lanczos","catmullrom"])
    return f'''<scene version="3.0.0">
{ix}
<sensor type="{sensor}">{sx}
{tfm}
<film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="48"/><rfilter type="{rf}"/><string name="pixel_format" value="rgb"/></film>
</sensor>
{chr(10).join(emitters)}
{chr(10).join(shapes)}
</scene>
'''


if __name__ == '__main__':
    first = int(sys.argv[1]) if len(sys.argv) > 1 else 0
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 40
    for s in range(first, first + count):
        run(f'random-{s}', gen(s))
