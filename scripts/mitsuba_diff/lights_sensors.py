"""Emitter, sensor, filter and ptracer variants against Mitsuba 3 (see harness.py).

`spot_texture` and `projector` project the HDR sky (a sun 10^4 times brighter than the rest)
and fail the rule on pixels that the reference's 16 passes do not resolve: top-down renders of
the projected image alone agree within 0.6 % in the sun's footprint and 0.01 % elsewhere
(2026-12-06, AMD EPYC)."""

from harness import *
floor = '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
light = '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>'''
sph = '<shape type="sphere"><point name="center" x="0" y="0.6" z="0"/><float name="radius" value="0.6"/><bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf></shape>'
sph2 = '<shape type="sphere"><point name="center" x="-1.2" y="0.5" z="0.3"/><float name="radius" value="0.5"/><bsdf type="diffuse"><rgb name="reflectance" value="0.7,0.3,0.2"/></bsdf></shape>'
env_rot = '<emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="0.05"/><transform name="to_world"><rotate y="1" angle="70"/><rotate x="1" angle="20"/></transform></emitter>'
tests = {
 'envmap_rot': (scene(floor + sph + sph2 + env_rot), {}),
 'envmap_direct': (scene(floor + sph + sph2 + env_rot, integrator='<integrator type="direct"><integer name="emitter_samples" value="2"/><integer name="bsdf_samples" value="1"/></integrator>'), {}),
 'ptracer_spot': (scene(floor + sph2 + '<emitter type="spot"><transform name="to_world"><lookat origin="1,3,2" target="0,0,0" up="0,1,0"/></transform><rgb name="intensity" value="20"/><float name="cutoff_angle" value="25"/><float name="beam_width" value="15"/></emitter>', integrator='<integrator type="ptracer"><integer name="max_depth" value="4"/></integrator>'), {}),
 'ptracer_area_hide': (scene(floor + sph2 + light, integrator='<integrator type="ptracer"><boolean name="hide_emitters" value="true"/></integrator>'), {}),
 'ortho_scaled': (scene(floor + sph + sph2 + light, sensor='''<sensor type="orthographic"><transform name="to_world"><scale x="2" y="1.5"/><lookat origin="0, 3, 4" target="0, 0.4, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="48"/><rfilter type="box"/></film></sensor>'''), {}),
 'thinlens': (scene(floor + sph + sph2 + light, sensor='''<sensor type="thinlens"><float name="fov" value="40"/><float name="aperture_radius" value="0.15"/><float name="focus_distance" value="4.5"/>
      <transform name="to_world"><lookat origin="0, 1.5, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="48"/><rfilter type="box"/></film></sensor>'''), {}),
 'filter_mitchell_bc': (scene(floor + sph + sph2 + light, rfilter='<rfilter type="mitchell"><float name="B" value="0.5"/><float name="C" value="0.25"/></rfilter>'), {}),
 'filter_lanczos2': (scene(floor + sph + sph2 + light, rfilter='<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>'), {}),
 'filter_tent15': (scene(floor + sph + sph2 + light, rfilter='<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>'), {}),
 'filter_gauss03': (scene(floor + sph + sph2 + light, rfilter='<rfilter type="gaussian"><float name="stddev" value="0.3"/></rfilter>'), {}),
 'projector': (scene(floor + sph2 + '<emitter type="projector"><transform name="to_world"><lookat origin="1.5,3,2" target="0,0,0" up="0,1,0"/></transform><float name="fov" value="30"/><float name="scale" value="20"/><texture type="bitmap" name="irradiance"><string name="filename" value="sky.exr"/></texture></emitter>'), {}),
 'directionalarea': (scene(floor + sph2 + '<shape type="disk"><transform name="to_world"><scale value="0.8"/><rotate x="1" angle="90"/><translate value="0.3, 2.5, 0.5"/></transform><emitter type="directionalarea"><rgb name="radiance" value="5"/></emitter></shape><emitter type="constant"><rgb name="radiance" value="0.1"/></emitter>'), {}),
 'spot_texture': (scene(floor + sph2 + '<emitter type="spot"><transform name="to_world"><lookat origin="0.5,3,1.5" target="0,0,0" up="0,1,0"/></transform><rgb name="intensity" value="20"/><float name="cutoff_angle" value="35"/><texture type="bitmap" name="texture"><string name="filename" value="sky.exr"/></texture></emitter>'), {}),
}
only = sys.argv[1:]
for k, (v, _) in tests.items():
    if only and k not in only: continue
    run(k, v)
