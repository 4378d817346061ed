"""Materials and lights as the Mitsuba Blender add-on writes them, against Mitsuba 3 (see
harness.py): textured principled BSDFs, normal and bump maps, masks under `path` (whose
zeroing of paths through null surfaces only matters where the void lies behind), null-BSDF
area lights."""

from harness import *

floor = '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></bsdf></shape>'
area = '''<shape type="rectangle"><boolean name="flip_normals" value="true"/><transform name="to_world"><scale value="0.6"/><rotate x="1" angle="-90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="10"/></emitter><bsdf type="null"/></shape>'''
def sph(bsdf, x=0.0, y=0.6, r=0.6):
    return f'<shape type="sphere"><point name="center" x="{x}" y="{y}" z="0"/><float name="radius" value="{r}"/>{bsdf}</shape>'
tests = {
 'principled_textured': sph('<bsdf type="twosided"><bsdf type="principled"><texture type="bitmap" name="base_color"><string name="filename" value="leaf.jpg"/></texture><texture type="bitmap" name="roughness"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture><float name="metallic" value="0.3"/></bsdf></bsdf>'),
 'normalmap_principled': sph('<bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normals.png"/><boolean name="raw" value="true"/></texture><bsdf type="principled"><rgb name="base_color" value="0.6,0.5,0.2"/><float name="roughness" value="0.3"/></bsdf></bsdf>'),
 'bumpmap_roughplastic': sph('<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture><float name="scale" value="0.3"/><bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.2,0.5,0.3"/></bsdf></bsdf>'),
 'mask_leaf_path_void': sph('<bsdf type="mask"><texture type="bitmap" name="opacity"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture><bsdf type="diffuse"><rgb name="reflectance" value="0.8,0.3,0.2"/></bsdf></bsdf>', y=1.8),
 'null_light_in_view': sph('<bsdf type="diffuse"/>', x=-1.2, r=0.5),
}
only = sys.argv[1:]
for k, v in tests.items():
    if only and k not in only: continue
    light = area
    if k == 'null_light_in_view':
        # the light itself in the frame, half against the void
        light = area.replace('<rotate x="1" angle="-90"/><translate value="0.5, 3, 1"/>', '<rotate y="1" angle="180"/><translate value="0.8, 1.6, -0.5"/>')
    run(k, scene(floor + light + v, integrator='<integrator type="path"><integer name="max_depth" value="8"/></integrator>'))
