"""Conductor and IOR presets, plastics and texture options against Mitsuba 3 (see harness.py)."""

from harness import *
floor = '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
light = '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape><emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>'''
def sph(bsdf, x=0, r=0.6):
    return f'<shape type="sphere"><point name="center" x="{x}" y="{r}" z="0"/><float name="radius" value="{r}"/>{bsdf}</shape>'
def row(bsdfs):
    return ''.join(sph(b, x=-1.8 + 1.2*i, r=0.5) for i, b in enumerate(bsdfs))
tests = {
 'conductors1': row([f'<bsdf type="conductor"><string name="material" value="{m}"/></bsdf>' for m in ['Ag','Al','AlAs','AlSb']]),
 'conductors2': row([f'<bsdf type="roughconductor"><string name="material" value="{m}"/><float name="alpha" value="0.1"/></bsdf>' for m in ['Cr','CsI','Hg','Ir']]),
 'conductors3': row([f'<bsdf type="roughconductor"><string name="material" value="{m}"/><float name="alpha" value="0.1"/></bsdf>' for m in ['Li','MgO','Mo','TiN']]),
 'conductors4': row([f'<bsdf type="roughconductor"><string name="material" value="{m}"/><float name="alpha" value="0.1"/></bsdf>' for m in ['VC','W','none','Na_palik']]),
 'dielectric_named': row([f'<bsdf type="roughdielectric"><string name="int_ior" value="{m}"/><float name="alpha" value="0.15"/></bsdf>' for m in ['bk7','water','diamond','acrylic glass']]),
 'plastics_nonlinear': row(['<bsdf type="plastic"><boolean name="nonlinear" value="true"/><rgb name="diffuse_reflectance" value="0.7,0.2,0.2"/></bsdf>','<bsdf type="roughplastic"><boolean name="nonlinear" value="true"/><string name="distribution" value="beckmann"/><float name="alpha" value="0.3"/></bsdf>','<bsdf type="roughplastic"><float name="int_ior" value="1.9"/><rgb name="specular_reflectance" value="0.5"/></bsdf>','<bsdf type="roughdielectric"><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/><string name="distribution" value="ggx"/></bsdf>']),
 'tex_bitmap_opts': floor + light + sph('<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="leaf.jpg"/><string name="wrap_mode" value="mirror"/><transform name="to_uv"><scale x="3" y="2"/></transform></texture></bsdf>'),
 'tex_checker_touv': floor + light + sph('<bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><rgb name="color0" value="0.1,0.2,0.8"/><rgb name="color1" value="0.9"/><transform name="to_uv"><scale x="8" y="4"/><rotate z="1" angle="30"/></transform></texture></bsdf>'),
 
}
only = sys.argv[1:]
for k, v in tests.items():
    if only and k not in only: continue
    if 'conductors' in k or 'dielectric' in k or 'plastics' in k: v = floor + light + v
    run(k, scene(v))
