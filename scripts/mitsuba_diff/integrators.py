"""Integrator settings, instancing and analytic shapes against Mitsuba 3 (see harness.py)."""

from harness import *
floor = '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
light = '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>'''
sph = '<shape type="sphere"><point name="center" x="0" y="0.6" z="0"/><float name="radius" value="0.6"/><bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf></shape>'
sph2 = '<shape type="sphere"><point name="center" x="-1.2" y="0.5" z="0.3"/><float name="radius" value="0.5"/><bsdf type="diffuse"><rgb name="reflectance" value="0.7,0.3,0.2"/></bsdf></shape>'
glass = '<shape type="sphere"><point name="center" x="1.2" y="0.5" z="0.3"/><float name="radius" value="0.5"/><bsdf type="dielectric"/></shape>'
env = '<emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="0.05"/></emitter>'
base = floor + sph + sph2 + light
tests = {
 'path_hide_env': scene(floor + sph + sph2 + env, integrator='<integrator type="path"><boolean name="hide_emitters" value="true"/></integrator>'),
 'path_depth1': scene(base + env, integrator='<integrator type="path"><integer name="max_depth" value="1"/></integrator>'),
 'path_depth2': scene(base + glass, integrator='<integrator type="path"><integer name="max_depth" value="2"/></integrator>'),
 'path_rr1': scene(base + glass, integrator='<integrator type="path"><integer name="rr_depth" value="1"/></integrator>'),
 'ptracer_env': scene(floor + sph2 + '<emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>', integrator='<integrator type="ptracer"/>'),
 'ptracer_directional': scene(floor + sph2 + '<emitter type="directional"><vector name="direction" x="-0.3" y="-1" z="-0.4"/><rgb name="irradiance" value="2"/></emitter>', integrator='<integrator type="ptracer"/>'),
 'ptracer_glass_point': scene(floor + glass + '<emitter type="point"><point name="position" x="1.2" y="2.5" z="0.3"/><rgb name="intensity" value="10"/></emitter>', integrator='<integrator type="ptracer"/>'),
 'instance_group': scene(floor + light + '<shape type="shapegroup" id="g"><shape type="sphere"><float name="radius" value="0.3"/><bsdf type="diffuse"><rgb name="reflectance" value="0.2,0.5,0.8"/></bsdf></shape><shape type="cube"><transform name="to_world"><scale value="0.2"/><translate x="0.5"/></transform></shape></shape>' + ''.join(f'<shape type="instance"><ref id="g"/><transform name="to_world"><rotate y="1" angle="{30*i}"/><scale value="{1+0.2*i}"/><translate x="{-1.5+i}" y="0.4"/></transform></shape>' for i in range(4))),
 'direct_defaults': scene(base + env, integrator='<integrator type="direct"/>'),
 'volpath_noMedia': scene(base + glass, integrator='<integrator type="volpath"><integer name="max_depth" value="6"/></integrator>'),
 'cylinder_disk_cube': scene(floor + light + '<shape type="cylinder"><point name="p0" x="-1" y="0" z="0"/><point name="p1" x="-1" y="1.2" z="0"/><float name="radius" value="0.3"/><bsdf type="diffuse"/></shape><shape type="disk"><transform name="to_world"><rotate x="1" angle="-60"/><translate value="0.5,0.5,0.5"/></transform><bsdf type="roughconductor"><string name="material" value="Cu"/></bsdf></shape><shape type="cube"><boolean name="flip_normals" value="false"/><transform name="to_world"><scale value="0.3"/><rotate y="1" angle="20"/><translate value="1.3,0.3,-0.3"/></transform></shape>'),
}
only = sys.argv[1:]
for k, v in tests.items():
    if only and k not in only: continue
    run(k, v)
