"""Conductor and IOR presets, plastics and texture options against Mitsuba 3 (see harness.py)."""

from harness import *
floor = '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
light = '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape><emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>'''
def sph(bsdf, x=0, r=0.6):
    return f'<shape type="sphere"><point name="center" x="{x}" y="{r}" z="0"/><float name="radius" value="{r}"/>{bsdf}</shape>'
def row(bsdfs):
    return ''.join(sph(b, x=-1.8 + 1.2*i, r=0.5) for i, b in enumerate(bsdfs))
# one picture in the formats Mitsuba reads besides PNG, JPEG, EXR and RGBE: colours that
# change along both axes, so that a flipped or transposed read shows
from PIL import Image
_y, _x = np.mgrid[0:24, 0:32]
_pic = np.stack([_x / 31, _y / 23, 0.5 + 0.5 * np.sin(_x / 5.0) * (_y > 11)], 2)
_pic8 = (_pic * 255).round().astype(np.uint8)
Image.fromarray(_pic8).save(f'{WORK}/pic.bmp')
Image.fromarray(_pic8).save(f'{WORK}/pic.tga')
Image.fromarray(_pic8).save(f'{WORK}/pic.ppm')
with open(f'{WORK}/pic.pfm', 'wb') as _o:
    _o.write(b'PF\n32 24\n-1.0\n' + np.ascontiguousarray(_pic[::-1].astype('<f4')).tobytes())
open(f'{WORK}/refl.spd', 'w').write('# a reflectance\n400 0.1\n450 0.2\n\n500 0.6\n550 0.8\n600 0.5\n650 0.3\n700 0.2\n')
open(f'{WORK}/lamp.spd', 'w').write('380 2.0\n480 4.0\n580 9.0\n680 12.0\n780 14.0\n')
def _tex(fname):
    return floor + light + sph(f'<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="{fname}"/></texture></bsdf>')
tests = {
 'tex_bmp': _tex('pic.bmp'),
 'tex_tga': _tex('pic.tga'),
 'tex_ppm': _tex('pic.ppm'),
 'tex_pfm': _tex('pic.pfm'),
 'spectrum_files': floor + sph('<bsdf type="diffuse"><spectrum name="reflectance" filename="refl.spd"/></bsdf>') + '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><spectrum name="radiance" filename="lamp.spd"/></emitter></shape>''',
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
