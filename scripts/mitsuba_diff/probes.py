"""Less common parameters of common plugins against Mitsuba 3 (see harness.py): camera
field-of-view axes and principal points, mirrored and non-uniformly scaled shapes, textured
and mesh emitters, edge cases of integrator depths, anisotropic and Beckmann microfacets,
spectra given as samples or a blackbody, and media under `volpath`."""

from harness import *
floor = '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>'
light = '''<shape type="rectangle"><transform name="to_world"><scale value="0.7"/><rotate x="1" angle="90"/><translate value="0.5, 3, 1"/></transform>
  <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>'''
sph = '<shape type="sphere"><point name="center" x="0" y="0.6" z="0"/><float name="radius" value="0.6"/><bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf></shape>'
sph2 = '<shape type="sphere"><point name="center" x="-1.2" y="0.5" z="0.3"/><float name="radius" value="0.5"/><bsdf type="diffuse"><rgb name="reflectance" value="0.7,0.3,0.2"/></bsdf></shape>'
base = floor + sph + sph2 + light
def persp(extra='', w=64, h=48, origin='0, 1.5, 5'):
    return f'''<sensor type="perspective">{extra}
      <transform name="to_world"><lookat origin="{origin}" target="0, 0.5, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="{w}"/><integer name="height" value="{h}"/><rfilter type="box"/></film></sensor>'''
# a small OBJ: a quad with uv, no normals, and a tilted triangle
open(f'{WORK}/quad.obj', 'w').write('v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n')
open(f'{WORK}/tri_n.obj', 'w').write('v -1 0 0\nv 1 0 0\nv 0 1.5 0.5\nvn 0 0.3 1\nvn 0.5 0 1\nvn -0.5 0.2 1\nf 1//1 2//2 3//3\n')
shutil.copy(os.path.join(ROOT, 'crates', 'steradian-mitsuba', 'tests', 'reference', 'volpath-cloud.vol'), f'{WORK}/cloud.vol')
shutil.copy(os.path.join(ROOT, 'crates', 'steradian-mitsuba', 'tests', 'reference', 'mesh_attribute', 'floor.ply'), f'{WORK}/floor.ply')
# quads, a pentagon, negative (relative) indices, a face without texture coordinates, groups and materials
open(f'{WORK}/mixed.obj', 'w').write('o a\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\ns 1\nf -4/-4 -1/-1 -2/-2 -3/-3\ng b\nv -1 0.5 -1\nv 0 1.5 -1\nv 1 0.5 -1\nv 1 0.2 -1\nv -1 0.2 -1\nf 9 8 7 6 5\n')
tex_leaf = '<texture type="bitmap" name="reflectance"><string name="filename" value="leaf.jpg"/></texture>'
tests = {
 'fov_x_wide': scene(base, sensor=persp('<float name="fov" value="50"/><string name="fov_axis" value="x"/>', w=80, h=40)),
 'fov_y_tall': scene(base, sensor=persp('<float name="fov" value="50"/><string name="fov_axis" value="y"/>', w=40, h=64)),
 'fov_diagonal': scene(base, sensor=persp('<float name="fov" value="50"/><string name="fov_axis" value="diagonal"/>', w=64, h=40)),
 'fov_larger': scene(base, sensor=persp('<float name="fov" value="50"/><string name="fov_axis" value="larger"/>', w=40, h=64)),
 'fov_smaller': scene(base, sensor=persp('<float name="fov" value="50"/><string name="fov_axis" value="smaller"/>', w=64, h=40)),
 'focal_length': scene(base, sensor=persp('<string name="focal_length" value="28mm"/>', w=64, h=40)),
 'principal_point': scene(base, sensor=persp('<float name="fov" value="40"/><float name="principal_point_offset_x" value="0.2"/><float name="principal_point_offset_y" value="-0.1"/>')),
 'near_clip_cut': scene(base, sensor=persp('<float name="fov" value="40"/><float name="near_clip" value="4.6"/>')),
 'mirrored_light': scene(floor + sph + sph2 + light.replace('<scale value="0.7"/>', '<scale x="-0.7" y="0.7" z="0.7"/>')),
 'mirrored_mesh_diffuse': scene(floor.replace('<scale value="4"/>', '<scale x="4" y="-4" z="4"/>') + sph2 + light),
 'flipped_rect_light': scene(floor + sph2 + light.replace('<shape type="rectangle">', '<shape type="rectangle"><boolean name="flip_normals" value="true"/>') + '<emitter type="constant"><rgb name="radiance" value="0.05"/></emitter>'),
 'sphere_light_tex': scene(floor + sph + '<shape type="sphere"><point name="center" x="-1.2" y="0.6" z="0.3"/><float name="radius" value="0.5"/><emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="leaf.jpg"/></texture></emitter></shape>'),
 'obj_light_tex': scene(floor + sph2 + '<shape type="obj"><string name="filename" value="quad.obj"/><transform name="to_world"><scale value="0.6"/><translate y="2.5" x="0.4"/></transform><emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="leaf.jpg"/></texture></emitter></shape>'),
 'obj_uv_diffuse': scene(light + sph2 + '<shape type="obj"><string name="filename" value="quad.obj"/><transform name="to_world"><scale value="2"/></transform><bsdf type="diffuse">' + tex_leaf + '</bsdf></shape>'),
 'obj_shading_normals': scene(floor + light + '<shape type="obj"><string name="filename" value="tri_n.obj"/><bsdf type="roughconductor"><float name="alpha" value="0.1"/></bsdf></shape>'),
 'obj_face_normals': scene(floor + light + '<shape type="obj"><string name="filename" value="tri_n.obj"/><boolean name="face_normals" value="true"/><bsdf type="roughconductor"><float name="alpha" value="0.1"/></bsdf></shape>'),
 'cube_light': scene(floor + sph + '<shape type="cube"><transform name="to_world"><scale value="0.3"/><rotate y="1" angle="30"/><translate x="-1.2" y="0.4"/></transform><emitter type="area"><rgb name="radiance" value="3,2,1"/></emitter></shape>'),
 'disk_light': scene(floor + sph + sph2 + '<shape type="disk"><transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2.5"/></transform><emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>'),
 'cyl_flip_twosided': scene(floor + sph + light + '<shape type="cylinder"><point name="p0" x="-1.2" y="0" z="0"/><point name="p1" x="-1.2" y="1.5" z="0"/><float name="radius" value="0.3"/><boolean name="flip_normals" value="true"/><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>'),
 'path_depth0': scene(base, integrator='<integrator type="path"><integer name="max_depth" value="0"/></integrator>'),
 'direct_counts': scene(base, integrator='<integrator type="direct"><integer name="emitter_samples" value="3"/><integer name="bsdf_samples" value="0"/></integrator>'),
 'rough_aniso_cond': scene(floor + light + sph.replace('<float name="alpha" value="0.2"/>', '<float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/><string name="material" value="Au"/>') + sph2),
 'rough_beckmann_nosv': scene(floor + light + sph.replace('<float name="alpha" value="0.2"/>', '<string name="distribution" value="beckmann"/><float name="alpha" value="0.3"/><boolean name="sample_visible" value="false"/>') + sph2),
 'roughdiel_beckmann': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="roughdielectric"><string name="distribution" value="beckmann"/><float name="alpha" value="0.15"/><string name="int_ior" value="diamond"/></bsdf></shape>'),
 'roughdiel_aniso_tex': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="roughdielectric"><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.3"/><rgb name="specular_transmittance" value="0.9,0.6,0.3"/></bsdf></shape>'),
 'spectrum_samples': scene(floor + sph + light + '<shape type="sphere"><point name="center" x="-1.2" y="0.5" z="0.3"/><float name="radius" value="0.5"/><bsdf type="diffuse"><spectrum name="reflectance" value="400:0.1, 500:0.8, 600:0.2, 700:0.6"/></bsdf></shape>'),
 'camera_mirrored': scene(base, sensor=persp('<float name="fov" value="40"/>').replace('<transform name="to_world">', '<transform name="to_world"><scale x="-1"/>')),
 'camera_matrix': scene(base, sensor=persp('<float name="fov" value="40"/>').replace('<lookat origin="0, 1.5, 5" target="0, 0.5, 0" up="0, 1, 0"/>', '<matrix value="0.9 0.1 0.3 0.5  0 0.95 -0.2 1.5  -0.3 0.2 0.9 5  0 0 0 1"/>')),
 'camera_scaled': scene(base, sensor=persp('<float name="fov" value="40"/>').replace('<transform name="to_world">', '<transform name="to_world"><scale x="1.5" y="0.7" z="2"/>')),
 'tex_alpha_rough': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="roughconductor"><texture type="bitmap" name="alpha"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture></bsdf></shape>'),
 'checker_tex_colors': scene(light + sph2 + '<shape type="rectangle"><transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><texture type="bitmap" name="color0"><string name="filename" value="leaf.jpg"/></texture><rgb name="color1" value="0.1,0.2,0.6"/><transform name="to_uv"><scale value="3"/></transform></texture></bsdf></shape>'),
 'blend_tex_weight': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="blendbsdf"><texture type="bitmap" name="weight"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture><bsdf type="diffuse"><rgb name="reflectance" value="0.2,0.3,0.8"/></bsdf><bsdf type="roughconductor"><float name="alpha" value="0.1"/></bsdf></bsdf></shape>'),
 'dielectric_ext_ior': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="dielectric"><string name="int_ior" value="bk7"/><string name="ext_ior" value="water"/></bsdf></shape>'),
 'sampler_stratified': scene(base).replace('<film', '<sampler type="stratified"><integer name="sample_count" value="16"/></sampler><film'),
 'sampler_multijitter': scene(base).replace('<film', '<sampler type="multijitter"/><film'),
 'sampler_ldsampler': scene(base).replace('<film', '<sampler type="ldsampler"/><film'),
 'rr_depth_big': scene(base, integrator='<integrator type="path"><integer name="max_depth" value="4"/><integer name="rr_depth" value="10"/></integrator>'),
 'twosided_area_emitter': scene(floor + sph + sph2 + light.replace('<emitter', '<bsdf type="twosided"><bsdf type="diffuse"/></bsdf><emitter').replace('<rotate x="1" angle="90"/>', '<rotate x="1" angle="60"/>')),
 'sphere_flip_light_inside': scene(floor + sph2 + '<shape type="sphere"><point name="center" x="0.4" y="0.6" z="0"/><float name="radius" value="0.5"/><boolean name="flip_normals" value="true"/><emitter type="area"><rgb name="radiance" value="4"/></emitter></shape><emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>'),
 'volpath_hetero': scene(floor + light + '<shape type="cube"><transform name="to_world"><scale value="0.7"/><translate y="0.75"/></transform><bsdf type="null"/><medium type="heterogeneous" name="interior"><rgb name="albedo" value="0.8,0.8,0.6"/><volume type="gridvolume" name="sigma_t"><string name="filename" value="cloud.vol"/></volume><float name="scale" value="4"/></medium></shape>', integrator='<integrator type="volpath"><integer name="max_depth" value="16"/></integrator>'),
 'point_in_medium': scene(floor + sph2 + '<emitter type="point"><point name="position" x="0.5" y="1.5" z="1"/><rgb name="intensity" value="10"/><ref id="fog"/></emitter>', integrator='<integrator type="volpath"><integer name="max_depth" value="8"/></integrator>', sensor=persp('<float name="fov" value="40"/><ref id="fog"/>')).replace('<sensor', '<medium type="homogeneous" id="fog"><float name="sigma_t" value="0.15"/><rgb name="albedo" value="0.9"/></medium><sensor',1),
 'envmap_jpg': scene(floor + sph + sph2 + '<emitter type="envmap"><string name="filename" value="leaf.jpg"/><float name="scale" value="2"/></emitter>'),
 'obj_quads_negative': scene(floor + light + '<shape type="obj"><string name="filename" value="mixed.obj"/><transform name="to_world"><scale value="0.5"/><translate y="0.5"/></transform><bsdf type="diffuse">' + tex_leaf + '</bsdf></shape>'),
 'sphere_light_scaled': scene(floor + sph2 + '<shape type="sphere"><transform name="to_world"><scale value="0.3"/><translate x="0.5" y="1.2" z="0.5"/></transform><emitter type="area"><rgb name="radiance" value="5,4,3"/></emitter></shape>'),
 'rect_light_nonuniform': scene(floor + sph + sph2 + light.replace('<scale value="0.7"/>', '<scale x="1.2" y="0.2"/>')),
 'cylinder_light': scene(floor + sph2 + '<shape type="cylinder"><transform name="to_world"><scale x="0.1" y="0.1" z="1.5"/><rotate y="1" angle="90"/><translate x="-0.5" y="1.8"/></transform><emitter type="area"><rgb name="radiance" value="6"/></emitter></shape>'),
 'rect_light_tex_touv': scene(floor + sph + sph2 + '<shape type="rectangle"><transform name="to_world"><scale value="0.8"/><rotate x="1" angle="90"/><translate value="0.3, 2.5, 0.5"/></transform><emitter type="area"><texture type="checkerboard" name="radiance"><rgb name="color0" value="1,0.2,0.1"/><rgb name="color1" value="0.1,0.3,1"/><transform name="to_uv"><scale value="4"/></transform></texture></emitter></shape><shape type="rectangle"><transform name="to_world"><scale value="0.5"/><translate value="1.2, 0.6, -1"/></transform><emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="leaf.jpg"/></texture></emitter></shape>'),
 'volpath_hide': scene(base, integrator='<integrator type="volpath"><boolean name="hide_emitters" value="true"/></integrator>'),
 'direct_hide': scene(base, integrator='<integrator type="direct"><boolean name="hide_emitters" value="true"/></integrator>'),
 'homog_no_emitter_sampling': scene(floor + light + '<shape type="sphere"><point name="center" x="0" y="0.8" z="0"/><float name="radius" value="0.8"/><bsdf type="thindielectric"/><medium type="homogeneous" name="interior"><rgb name="albedo" value="0.9,0.7,0.5"/><float name="sigma_t" value="1.5"/><boolean name="sample_emitters" value="false"/><phase type="rayleigh"/></medium></shape>', integrator='<integrator type="volpath"><integer name="max_depth" value="12"/></integrator>'),
 'blendphase': scene(floor + light + '<shape type="cube"><transform name="to_world"><scale value="0.7"/><translate y="0.8"/></transform><bsdf type="null"/><medium type="homogeneous" name="interior"><float name="sigma_t" value="2"/><float name="albedo" value="0.9"/><phase type="blendphase"><float name="weight" value="0.3"/><phase type="hg"><float name="g" value="0.8"/></phase><phase type="hg"><float name="g" value="-0.5"/></phase></phase></medium></shape>', integrator='<integrator type="volpath"/>'),
 'nested_media': scene(floor + light + '<shape type="sphere"><point name="center" x="0" y="0.9" z="0"/><float name="radius" value="0.9"/><bsdf type="dielectric"><float name="int_ior" value="1.33"/></bsdf><medium type="homogeneous" name="interior"><float name="sigma_t" value="0.5"/><rgb name="albedo" value="0.3,0.6,0.9"/></medium></shape><shape type="sphere"><point name="center" x="0" y="0.9" z="0"/><float name="radius" value="0.4"/><bsdf type="null"/><medium type="homogeneous" name="interior"><float name="sigma_t" value="6"/><float name="albedo" value="0.95"/></medium><medium type="homogeneous" name="exterior"><float name="sigma_t" value="0.5"/><rgb name="albedo" value="0.3,0.6,0.9"/></medium></shape>', integrator='<integrator type="volpath"><integer name="max_depth" value="32"/></integrator>'),
 'ply_vertex_colors_diffuse': scene(light + sph2 + '<shape type="ply"><string name="filename" value="floor.ply"/><bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_color"/></texture></bsdf></shape>'),
 # Mitsuba 3.9.1 renders no blackbody in RGB modes ("not implemented for non-spectral modes")
 # 'blackbody_light': scene(floor + sph + sph2 + light.replace('<rgb name="radiance" value="12"/>', '<spectrum type="blackbody" name="radiance"><float name="temperature" value="3000"/></spectrum>')),
 'spectrum_uniform': scene(floor + sph + sph2 + light.replace('<rgb name="radiance" value="12"/>', '<spectrum name="radiance" value="7"/>')),
 'point_to_world': scene(floor + sph + sph2 + '<emitter type="point"><transform name="to_world"><translate value="0.5,2.5,1"/></transform><rgb name="intensity" value="8"/></emitter>'),
 'directional_to_world': scene(floor + sph + sph2 + '<emitter type="directional"><transform name="to_world"><lookat origin="0,0,0" target="0.3,-1,-0.5" up="0,1,0"/></transform><rgb name="irradiance" value="3"/></emitter>'),
 'spot_defaults': scene(floor + sph + sph2 + '<emitter type="spot"><transform name="to_world"><lookat origin="0.5,3,1.5" target="0,0,0" up="0,1,0"/></transform><rgb name="intensity" value="20"/></emitter>'),
 'volpath_homog_hg': scene(floor + light + '<shape type="sphere"><point name="center" x="0" y="0.8" z="0"/><float name="radius" value="0.8"/><bsdf type="null"/><medium type="homogeneous" name="interior"><rgb name="albedo" value="0.9,0.7,0.5"/><float name="sigma_t" value="2"/><phase type="hg"><float name="g" value="0.6"/></phase></medium></shape>', integrator='<integrator type="volpath"><integer name="max_depth" value="12"/></integrator>'),
 'volpath_dielectric_medium': scene(floor + light + '<shape type="sphere"><point name="center" x="0" y="0.8" z="0"/><float name="radius" value="0.8"/><bsdf type="dielectric"/><medium type="homogeneous" name="interior"><rgb name="sigma_t" value="1,2,4"/><float name="scale" value="0.7"/><rgb name="albedo" value="0.8"/></medium></shape>', integrator='<integrator type="volpath"><integer name="max_depth" value="12"/></integrator>'),
 'plastic_tex_spec': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="roughplastic"><float name="alpha" value="0.2"/>' + tex_leaf.replace('"reflectance"', '"diffuse_reflectance"') + '<float name="specular_reflectance" value="0.5"/><float name="int_ior" value="1.9"/></bsdf></shape>'),
 'conductor_eta_k': scene(floor + light + sph2 + '<shape type="sphere"><point name="center" x="0.5" y="0.6" z="0.5"/><float name="radius" value="0.6"/><bsdf type="roughconductor"><rgb name="eta" value="0.2,0.9,1.1"/><rgb name="k" value="3.9,2.4,2.2"/><float name="alpha" value="0.1"/><rgb name="specular_reflectance" value="0.8,1,0.9"/></bsdf></shape>'),
 'constant_only_diffuse': scene(floor + sph + sph2 + '<emitter type="constant"/>'),
 'rgba_path_env': scene(floor + sph + sph2 + light, film_extra='<string name="pixel_format" value="rgba"/>'),
}
only = sys.argv[1:]
for k, v in tests.items():
    if only and k not in only: continue
    run(k, v)
