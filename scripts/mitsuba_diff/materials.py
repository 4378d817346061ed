"""BSDF variants against Mitsuba 3 (see harness.py)."""

from harness import *
light = '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>'''
def sph(bsdf, x=0, r=0.6):
    return f'<shape type="sphere"><point name="center" x="{x}" y="{r}" z="0"/><float name="radius" value="{r}"/>{bsdf}</shape>'
tests = {
 'principled_aniso': sph('<bsdf type="principled"><rgb name="base_color" value="0.7,0.5,0.3"/><float name="anisotropic" value="0.6"/><float name="roughness" value="0.4"/><float name="metallic" value="0.8"/></bsdf>'),
 'principled_sheen_cc': sph('<bsdf type="principled"><rgb name="base_color" value="0.2,0.3,0.8"/><float name="sheen" value="0.8"/><float name="sheen_tint" value="0.5"/><float name="clearcoat" value="0.9"/><float name="clearcoat_gloss" value="0.2"/><float name="roughness" value="0.6"/></bsdf>'),
 'principled_trans': sph('<bsdf type="principled"><rgb name="base_color" value="0.9,0.9,0.9"/><float name="spec_trans" value="0.7"/><float name="eta" value="1.4"/><float name="roughness" value="0.25"/><float name="spec_tint" value="0.4"/></bsdf>'),
 'principledthin': sph('<bsdf type="principledthin"><rgb name="base_color" value="0.8,0.4,0.4"/><float name="diff_trans" value="0.5"/><float name="spec_trans" value="0.3"/><float name="eta" value="1.3"/><float name="roughness" value="0.3"/></bsdf>'),
 'pplastic': sph('<bsdf type="pplastic"><rgb name="diffuse_reflectance" value="0.1,0.6,0.2"/><float name="alpha" value="0.15"/></bsdf>'),
 'roughconductor_aC': sph('<bsdf type="roughconductor"><string name="material" value="a-C"/><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.3"/></bsdf>'),
 'twosided_two': '<shape type="rectangle"><transform name="to_world"><rotate y="1" angle="60"/><translate value="0,0.8,0"/></transform><bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.8,0.1,0.1"/></bsdf><bsdf type="roughconductor"><string name="material" value="Au"/></bsdf></bsdf></shape>',
 'blend_bump': sph('<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.6,0.2,0.1"/></bsdf><bsdf type="roughdielectric"><float name="alpha" value="0.2"/></bsdf></bsdf>'),
 'thindielectric': sph('<bsdf type="thindielectric"><float name="int_ior" value="1.6"/></bsdf>'),
 'mask_binary_tex': sph('<bsdf type="mask"><texture type="checkerboard" name="opacity"><float name="color0" value="0"/><float name="color1" value="1"/></texture><bsdf type="diffuse"/></bsdf>'),
}
only = sys.argv[1:]
for k, v in tests.items():
    if only and k not in only: continue
    run(k, scene(light + v))
