"""Random parameters against Mitsuba 3 (see harness.py): random_scenes.py draws plugins with
their default parameters; this draws the parameters real scenes set and random_scenes.py
leaves at their defaults (anisotropic and textured roughness, conductors given as eta/k,
named IORs, `nonlinear` plastics, `principledthin` and every `principled` lobe, `pplastic`,
textured and mesh area lights, spot textures, projectors, `flip_normals`, `face_normals`,
per-vertex colours, `rawconstant`, sensor `fov_axis` and principal point, film crops and
filter parameters, `rr_depth`), and compares steradian's image with Mitsuba's. A failure is a
lead, not a verdict (random_scenes.py). From the repository root:

    python3 scripts/mitsuba_diff/random_params.py [FIRST_SEED] [COUNT]

2026-12-07 (AMD EPYC, 2 cores): seeds 0-399 found Mitsuba 3.9.1's ptracer culling light
paths by the unshifted window behind a shifted principal point (tests/ptracer.rs; such scenes
are no longer drawn) and otherwise heavy-tailed scenes only (their Mitsuba control fails too).
Mitsuba refuses a `checkerboard` radiance under `ptracer` ("sample_spectrum not implemented"),
so area lights here take a bitmap.
"""

import os
import random
import shutil
import sys

from harness import ROOT, WORK, run

REFERENCE = os.path.join(ROOT, 'crates', 'steradian-mitsuba', 'tests', 'reference')
for f in ('textures/wall.png', 'textures/leaf_mask.png', 'mesh_attribute/sphere.ply',
          'serialized/sphere_v4.serialized'):
    shutil.copy(os.path.join(REFERENCE, f), WORK)


def gen(seed):
    r = random.Random(seed)
    f = lambda a, b: round(r.uniform(a, b), 3)
    rgb = lambda lo=0.05, hi=0.9: f"{f(lo,hi)}, {f(lo,hi)}, {f(lo,hi)}"

    def tex(name, lo=0.05, hi=0.9, scalar=False):
        k = r.random()
        if k < 0.15:
            return (f'<texture type="bitmap" name="{name}"><string name="filename" value="wall.png"/>'
                    f'<boolean name="raw" value="{r.choice(["true","false"])}"/>'
                    f'<transform name="to_uv"><rotate z="1" angle="{f(0,90)}"/><scale value="{f(1,3)}"/></transform></texture>')
        if k < 0.25:
            return (f'<texture type="checkerboard" name="{name}"><rgb name="color0" value="{rgb(lo,hi)}"/>'
                    f'<rgb name="color1" value="{rgb(lo,hi)}"/><transform name="to_uv"><scale value="{r.randint(2,6)}"/></transform></texture>')
        if k < 0.32 and not scalar:
            return f'<texture type="rawconstant" name="{name}"><vector name="value" x="{f(lo,hi)}" y="{f(lo,hi)}" z="{f(lo,hi)}"/></texture>'
        if scalar or k < 0.45:
            return f'<float name="{name}" value="{f(lo,hi)}"/>'
        return f'<rgb name="{name}" value="{rgb(lo,hi)}"/>'

    def alpha():
        k = r.random()
        if k < 0.4:
            return f'<float name="alpha_u" value="{f(0.05,0.5)}"/><float name="alpha_v" value="{f(0.05,0.5)}"/>'
        if k < 0.55:
            return (f'<texture type="checkerboard" name="alpha"><float name="color0" value="{f(0.05,0.2)}"/>'
                    f'<float name="color1" value="{f(0.3,0.6)}"/><transform name="to_uv"><scale value="4"/></transform></texture>')
        return f'<float name="alpha" value="{f(0.05,0.5)}"/>'

    def ior(name):
        if r.random() < 0.4:
            return f'<string name="{name}" value="{r.choice(["bk7","water","acrylic glass","diamond","polypropylene"])}"/>'
        return f'<float name="{name}" value="{f(1.2,1.8)}"/>'

    def base():
        t = r.choice(["roughconductor", "conductor", "roughplastic", "plastic", "principled",
                      "principledthin", "pplastic", "dielectric", "roughdielectric", "diffuse"])
        dist = f'<string name="distribution" value="{r.choice(["beckmann","ggx"])}"/>'
        if t == "roughconductor":
            m = (f'<rgb name="eta" value="{rgb(0.2,2)}"/><rgb name="k" value="{rgb(1,4)}"/>'
                 if r.random() < 0.5 else f'<string name="material" value="{r.choice(["Au","Cu","Al","W","Hg","CuO","Li"])}"/>')
            spec = tex("specular_reflectance", 0.5, 1) if r.random() < 0.3 else ''
            return f'<bsdf type="roughconductor">{m}{dist}{alpha()}{spec}</bsdf>'
        if t == "conductor":
            return f'<bsdf type="conductor"><rgb name="eta" value="{rgb(0.2,2)}"/><rgb name="k" value="{rgb(1,4)}"/>{tex("specular_reflectance", 0.5, 1)}</bsdf>'
        if t == "roughplastic":
            nl = f'<boolean name="nonlinear" value="{r.choice(["true","false"])}"/>'
            return f'<bsdf type="roughplastic">{tex("diffuse_reflectance")}{ior("int_ior")}{dist}<float name="alpha" value="{f(0.05,0.4)}"/>{nl}</bsdf>'
        if t == "plastic":
            nl = f'<boolean name="nonlinear" value="{r.choice(["true","false"])}"/>'
            return f'<bsdf type="plastic">{tex("diffuse_reflectance")}{ior("int_ior")}{nl}<float name="specular_reflectance" value="{f(0.3,1)}"/></bsdf>'
        if t == "principled":
            extra = ''.join(f'<float name="{p}" value="{f(0,1)}"/>' for p in
                            r.sample(["specular", "spec_tint", "sheen", "sheen_tint", "clearcoat", "clearcoat_gloss", "anisotropic", "spec_trans"], 3))
            return f'<bsdf type="principled">{tex("base_color")}{tex("metallic", 0, 1, True)}<float name="roughness" value="{f(0.2,0.9)}"/>{extra}</bsdf>'
        if t == "principledthin":
            extra = ''.join(f'<float name="{p}" value="{f(0,1)}"/>' for p in
                            r.sample(["spec_trans", "diff_trans", "sheen", "sheen_tint", "spec_tint", "anisotropic"], 3))
            return f'<bsdf type="principledthin">{tex("base_color")}<float name="roughness" value="{f(0.2,0.9)}"/><float name="eta" value="{f(1.2,1.7)}"/>{extra}</bsdf>'
        if t == "pplastic":
            return f'<bsdf type="pplastic">{tex("diffuse_reflectance")}<float name="alpha" value="{f(0.05,0.4)}"/></bsdf>'
        if t == "dielectric":
            return f'<bsdf type="dielectric">{ior("int_ior")}{tex("specular_transmittance", 0.5, 1)}</bsdf>'
        if t == "roughdielectric":
            return f'<bsdf type="roughdielectric">{ior("int_ior")}{dist}<float name="alpha" value="{f(0.15,0.4)}"/></bsdf>'
        return f'<bsdf type="diffuse">{tex("reflectance")}</bsdf>'

    def bsdf():
        b = base()
        transmits = any(t in b for t in ('dielectric"', 'principledthin', 'spec_trans'))
        return f'<bsdf type="twosided">{b}</bsdf>' if r.random() < 0.2 and not transmits else b

    shapes = [f'<shape type="rectangle"><transform name="to_world"><scale value="5"/><rotate x="1" angle="-90"/></transform>'
              f'<bsdf type="diffuse">{tex("reflectance")}</bsdf></shape>']
    for i in range(r.randint(1, 3)):
        t = r.choice(["sphere", "cube", "cylinder", "disk", "ply", "ply_colours", "serialized"])
        pos = (f(-2, 2), f(0.4, 1.2), f(-1.5, 1))
        s = f(0.3, 0.6)
        b = bsdf()
        flip = '<boolean name="flip_normals" value="true"/>' if r.random() < 0.1 else ''
        place = (f'<transform name="to_world"><scale x="{s}" y="{f(0.3,0.6)}" z="{s}"/><rotate y="1" angle="{f(0,360)}"/>'
                 f'<translate x="{pos[0]}" y="{pos[1]}" z="{pos[2]}"/></transform>')
        if t == "sphere":
            shapes.append(f'<shape type="sphere"><transform name="to_world"><scale value="{s}"/><translate x="{pos[0]}" y="{pos[1]}" z="{pos[2]}"/></transform>{flip}{b}</shape>')
        elif t == "ply":
            fn = f'<boolean name="face_normals" value="{r.choice(["true","false"])}"/>'
            shapes.append(f'<shape type="ply"><string name="filename" value="sphere.ply"/>{fn}{flip}{place}{b}</shape>')
        elif t == "ply_colours":
            attr = r.choice(["vertex_color", "face_c_color"])
            shapes.append(f'<shape type="ply"><string name="filename" value="sphere.ply"/>{place}<bsdf type="diffuse">'
                          f'<texture type="mesh_attribute" name="reflectance"><string name="name" value="{attr}"/></texture></bsdf></shape>')
        elif t == "serialized":
            shapes.append(f'<shape type="serialized"><string name="filename" value="sphere_v4.serialized"/>{flip}{place}{b}</shape>')
        elif t == "cylinder":
            shapes.append(f'<shape type="cylinder"><float name="radius" value="{f(0.5,1)}"/>{place}{flip}{b}</shape>')
        else:
            shapes.append(f'<shape type="{t}">{place}{flip}{b}</shape>')

    emitters = []
    for k in r.sample(["constant", "point", "spot", "spot_tex", "projector", "area_tex", "area_disk", "area_mesh", "area_cyl"], r.randint(1, 3)):
        look = f'<lookat origin="{f(-2,2)}, {f(3,5)}, {f(1,3)}" target="{f(-0.5,0.5)}, 0.5, {f(-0.5,0.5)}"/>'
        if k == "constant":
            emitters.append(f'<emitter type="constant"><rgb name="radiance" value="{rgb(0.2,1)}"/></emitter>')
        if k == "point":
            emitters.append(f'<emitter type="point"><point name="position" x="{f(-2,2)}" y="{f(2,4)}" z="{f(-1,3)}"/><rgb name="intensity" value="{rgb(5,20)}"/></emitter>')
        if k == "spot":
            emitters.append(f'<emitter type="spot"><transform name="to_world">{look}</transform><rgb name="intensity" value="{rgb(10,40)}"/>'
                            f'<float name="cutoff_angle" value="{f(20,40)}"/></emitter>')
        if k == "spot_tex":
            emitters.append(f'<emitter type="spot"><transform name="to_world">{look}</transform><float name="intensity" value="{f(10,40)}"/>'
                            f'<texture type="bitmap" name="texture"><string name="filename" value="wall.png"/></texture><float name="cutoff_angle" value="{f(20,40)}"/></emitter>')
        if k == "projector":
            emitters.append(f'<emitter type="projector"><transform name="to_world">{look}</transform><float name="scale" value="{f(5,20)}"/>'
                            f'<float name="fov" value="{f(30,60)}"/><texture type="bitmap" name="irradiance"><string name="filename" value="wall.png"/></texture></emitter>')
        if k == "area_tex":  # a bitmap: Mitsuba's ptracer cannot sample a checkerboard's spectrum
            shapes.append(f'<shape type="rectangle"><transform name="to_world"><scale value="{f(1.5,2.5)}"/><rotate x="1" angle="90"/><translate x="{f(-1,1)}" y="{f(2.5,3.5)}" z="{f(-1,1)}"/></transform>'
                          f'<emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="wall.png"/></texture></emitter></shape>')
        if k == "area_disk":
            shapes.append(f'<shape type="disk"><transform name="to_world"><scale value="{f(0.4,1)}"/><rotate x="1" angle="90"/><translate x="{f(-1,1)}" y="{f(2.5,3.5)}" z="{f(-1,1)}"/></transform>'
                          f'<emitter type="area"><rgb name="radiance" value="{rgb(3,10)}"/></emitter></shape>')
        if k == "area_mesh":
            shapes.append(f'<shape type="ply"><string name="filename" value="sphere.ply"/><transform name="to_world"><scale value="{f(0.2,0.4)}"/><translate x="{f(-1,1)}" y="{f(2.5,3.5)}" z="{f(-1,1)}"/></transform>'
                          f'<emitter type="area"><rgb name="radiance" value="{rgb(3,10)}"/></emitter></shape>')
        if k == "area_cyl":
            shapes.append(f'<shape type="cylinder"><float name="radius" value="0.1"/><point name="p0" x="{f(-2,-1)}" y="3" z="0"/><point name="p1" x="{f(1,2)}" y="3" z="0"/>'
                          f'<emitter type="area"><rgb name="radiance" value="{rgb(3,10)}"/></emitter></shape>')
    if not emitters and not any("emitter" in s for s in shapes):
        emitters.append('<emitter type="constant"/>')

    integ = r.choice(["path", "path", "path", "volpath", "ptracer", "direct"])
    md = r.choice([-1, 2, 3, 5])
    rr = f'<integer name="rr_depth" value="{r.randint(1,4)}"/>' if r.random() < 0.4 else ''
    ix = (f'<integrator type="direct"/>' if integ == "direct" else
          f'<integrator type="{integ}"><integer name="max_depth" value="{md}"/>{rr}</integrator>')
    w, h = r.choice([(64, 48), (48, 64), (64, 64)])
    fov_axis = r.choice(["x", "y", "diagonal", "smaller", "larger"])
    # not with ptracer: Mitsuba 3.9.1 culls light paths by the unshifted window (a band of the
    # image black; sensor/perspective.rs, tests/ptracer.rs)
    pp = (f'<float name="principal_point_offset_x" value="{f(-0.2,0.2)}"/><float name="principal_point_offset_y" value="{f(-0.2,0.2)}"/>'
          if r.random() < 0.3 and integ != "ptracer" else '')
    crop = ''
    if r.random() < 0.25:
        cw, ch = r.randint(20, w - 10), r.randint(20, h - 10)
        crop = (f'<integer name="crop_width" value="{cw}"/><integer name="crop_height" value="{ch}"/>'
                f'<integer name="crop_offset_x" value="{r.randint(0, w - cw)}"/><integer name="crop_offset_y" value="{r.randint(0, h - ch)}"/>')
    rf = r.choice(['<rfilter type="box"/>', '<rfilter type="tent"/>',
                   f'<rfilter type="gaussian"><float name="stddev" value="{f(0.3,0.8)}"/></rfilter>',
                   f'<rfilter type="mitchell"><float name="B" value="{f(0,0.6)}"/><float name="C" value="{f(0.2,0.6)}"/></rfilter>',
                   f'<rfilter type="lanczos"><integer name="lobes" value="{r.randint(2,4)}"/></rfilter>'])
    return f'''<scene version="3.0.0">
{ix}
<sensor type="perspective"><float name="fov" value="{f(35,55)}"/><string name="fov_axis" value="{fov_axis}"/>{pp}
<transform name="to_world"><lookat origin="{f(-1,1)}, {f(2,3.5)}, {f(6,8)}" target="0, 0.6, 0" up="0, 1, 0"/></transform>
<film type="hdrfilm"><integer name="width" value="{w}"/><integer name="height" value="{h}"/>{crop}{rf}<string name="pixel_format" value="rgb"/></film>
</sensor>
{chr(10).join(emitters)}
{chr(10).join(shapes)}
</scene>
'''


if __name__ == '__main__':
    first = int(sys.argv[1]) if len(sys.argv) > 1 else 0
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 40
    for s in range(first, first + count):
        run(f'params-{s}', gen(s))
