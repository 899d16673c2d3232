"""Builds a scene description (scenes.py, passed as JSON) in Blender and renders it with
Cycles, timing each render.

  blender -b --factory-startup --python bench/vs_cycles/blender_scene.py -- job.json

job.json: {"scene": {...}, "threads": 2, "renders": [{"out": "x.exr", "spp": 64, "seed": 1,
"time_limit": 0, "dermis_before": [{"label": ..., "out": ..., "cmd": [...]}, ...]}, ...],
"result": "result.json", "root": "<repository root>"}
Writes result.json: Blender/Cycles version, the settings as read back, and per render the
wall time of bpy.ops.render.render(); Cycles' own statistics are in each EXR's metadata.
A render's dermis_before commands (`dermis render` of the same sample count and seed) are
run just before it, their exit status, stderr and wall time returned with it ("dermis"):
the two renderers' sweeps interleaved (run.py).
"""

import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix, Vector

# Blender's Python runs this file by path, not as a module: the repository root, for the package.
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
from bench.harness import render  # noqa: E402  (standard library only)
from bench.vs_cycles import scenes  # noqa: E402  (pure Python: the ellipsoid's triangles)

args = sys.argv[sys.argv.index("--") + 1:]
job = json.load(open(args[0]))
sc = job["scene"]
ROOT = job["root"]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


# ------------------------------------------------------------------ settings

def settings(threads):
    r = scene.render
    r.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.feature_set = "SUPPORTED"
    r.threads_mode = "FIXED"
    r.threads = threads
    r.resolution_x, r.resolution_y = sc["res"]
    r.resolution_percentage = 100
    r.film_transparent = False
    r.use_persistent_data = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.use_animated_seed = False
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    d = sc["max_depth"]
    c.max_bounces = d
    c.diffuse_bounces = d
    c.glossy_bounces = d
    c.transmission_bounces = d
    c.volume_bounces = d
    c.transparent_max_bounces = d
    c.pixel_filter_type = "BOX"  # = Dermis PixelFilter "box" (radius 0.5 px = width 1 px)
    c.filter_width = 1.0
    c.film_exposure = 1.0
    # Colour management: the EXR holds scene-linear values whatever the view transform is;
    # Standard/None/0/1 also keeps the PNG previews plain sRGB.
    vs = scene.view_settings
    vs.view_transform = "Standard"
    vs.look = "None"
    vs.exposure = 0.0
    vs.gamma = 1.0
    scene.display_settings.display_device = "sRGB"
    im = r.image_settings
    im.file_format = "OPEN_EXR"
    im.color_mode = "RGB"
    im.color_depth = "32"
    im.exr_codec = "ZIP"
    r.use_file_extension = True


# ------------------------------------------------------------------ scene

def camera():
    cam = sc["camera"]
    data = bpy.data.cameras.new("cam")
    data.type = "PERSP"
    w, h = sc["res"]
    # pbrt's fov is the angle of the shorter image axis.
    if w >= h:
        data.sensor_fit = "VERTICAL"
        data.angle_y = math.radians(cam["fov"])
    else:
        data.sensor_fit = "HORIZONTAL"
        data.angle_x = math.radians(cam["fov"])
    data.clip_start = 0.1
    data.clip_end = 1e6
    obj = bpy.data.objects.new("cam", data)
    scene.collection.objects.link(obj)
    eye, target, up = Vector(cam["eye"]), Vector(cam["target"]), Vector(cam["up"])
    f = (target - eye).normalized()
    right = f.cross(up).normalized()
    u = right.cross(f)
    m = Matrix.Identity(4)
    for i in range(3):  # Blender cameras look down -Z with +Y up
        m[i][0], m[i][1], m[i][2], m[i][3] = right[i], u[i], -f[i], eye[i]
    obj.matrix_world = m
    scene.camera = obj


def world():
    w = bpy.data.worlds.new("sky")
    w.use_nodes = True
    bg = w.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*(sc["sky"] or (0.0, 0.0, 0.0)), 1.0)
    bg.inputs["Strength"].default_value = 1.0  # radiance = colour x strength
    env = sc.get("environment")
    if env:
        # The HDR environment's lat-long map (environments.py), linear, looked up at the
        # nearest pixel as pbrt-v4's infinite light looks up its equal-area map; world
        # importance sampling is Cycles' default (Auto).
        tex = w.node_tree.nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(env["latlong"])
        tex.image.colorspace_settings.name = "Non-Color"
        tex.interpolation = "Closest"
        w.node_tree.links.new(tex.outputs["Color"], bg.inputs["Color"])
    scene.world = w


def mesh_object(name, verts, faces, smooth=False):
    me = bpy.data.meshes.new(name)
    me.from_pydata(verts, [], faces)
    me.update()
    for p in me.polygons:
        p.use_smooth = smooth
    obj = bpy.data.objects.new(name, me)
    scene.collection.objects.link(obj)
    return obj


def key_light(L):
    obj = mesh_object("key", [tuple(c) for c in L["corners"]], [(0, 1, 2, 3)])
    mat = bpy.data.materials.new("key")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    em = nt.nodes.new("ShaderNodeEmission")
    em.inputs["Color"].default_value = (*L["radiance"], 1.0)
    em.inputs["Strength"].default_value = 1.0  # mesh emission strength is radiance
    black = nt.nodes.new("ShaderNodeEmission")
    black.inputs["Strength"].default_value = 0.0
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    mix = nt.nodes.new("ShaderNodeMixShader")  # one-sided: the back face emits nothing
    nt.links.new(geo.outputs["Backfacing"], mix.inputs["Fac"])
    nt.links.new(em.outputs["Emission"], mix.inputs[1])
    nt.links.new(black.outputs["Emission"], mix.inputs[2])
    nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
    obj.data.materials.append(mat)
    # Cycles 3.4: mesh lights are sampled by next-event estimation when the material's
    # "Multiple Importance" (sample_as_light) is on (the default).
    mat.cycles.sample_as_light = True


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) for t in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):  # fan, winding kept (as Dermis/Assimp)
                    faces.append((idx[0], idx[k], idx[k + 1]))
    return verts, faces


def shape():
    s = sc["shape"]
    if s["kind"] == "sphere":
        # Dermis renders an exact sphere; here a fine UV sphere with smooth normals
        # (chord error 0.12% of the radius).
        bpy.ops.mesh.primitive_uv_sphere_add(segments=128, ring_count=64, radius=s["radius"],
                                             location=tuple(s["center"]))
        obj = bpy.context.active_object
        for p in obj.data.polygons:
            p.use_smooth = True
        return obj
    if s["kind"] == "ellipsoid":  # the very triangles Dermis gets, flat shaded in both
        v, f = scenes.ellipsoid_mesh(s["center"], s["semi_axes"], s["segments"], s["rings"])
        return mesh_object("ellipsoid", [tuple(x) for x in v], [tuple(x) for x in f], smooth=False)
    if s["kind"] == "obj":
        # Coordinates as written (no axis conversion: Dermis reads the file through Assimp
        # as is); flat shading, as Dermis shades with geometric normals.
        v, f = read_obj(os.path.join(ROOT, s["path"]))
        return mesh_object("obj", v, f, smooth=False)
    raise ValueError(s["kind"])


def grid_volume(m):
    """The grid medium (grid_twin.py) as a Volume object of its .vdb: Volume Scatter and Volume
    Absorption as for the homogeneous medium (material() below), their densities times the
    grid's "density" attribute; ray marched (Cycles' default step, the voxel size)."""
    bpy.ops.object.volume_import(filepath=m["vdb"])
    obj = bpy.context.selected_objects[0]
    obj.data.grids.load()
    mat = bpy.data.materials.new("grid")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    attr = nt.nodes.new("ShaderNodeAttribute")
    attr.attribute_name = "density"
    ss, sa = m["sigma_s"], m["sigma_a"]
    ds, da = max(ss), max(sa)
    shaders = []
    for node, colour, scale in (("ShaderNodeVolumeScatter", [x / ds for x in ss], ds),
                                ("ShaderNodeVolumeAbsorption", [1.0 - x / da for x in sa], da)):
        v = nt.nodes.new(node)
        v.inputs["Color"].default_value = (*colour, 1.0)
        mul = nt.nodes.new("ShaderNodeMath")
        mul.operation = "MULTIPLY"
        mul.inputs[1].default_value = scale
        nt.links.new(attr.outputs["Fac"], mul.inputs[0])
        nt.links.new(mul.outputs["Value"], v.inputs["Density"])
        if node == "ShaderNodeVolumeScatter":
            v.inputs["Anisotropy"].default_value = m["g"]
        shaders.append(v)
    add = nt.nodes.new("ShaderNodeAddShader")
    nt.links.new(shaders[0].outputs["Volume"], add.inputs[0])
    nt.links.new(shaders[1].outputs["Volume"], add.inputs[1])
    nt.links.new(add.outputs["Shader"], out.inputs["Volume"])
    mat.cycles.volume_sampling = "MULTIPLE_IMPORTANCE"
    obj.data.materials.clear()
    obj.data.materials.append(mat)


def fresnel_f0(eta):
    return ((eta - 1.0) / (eta + 1.0)) ** 2


def material(obj):
    m = sc["material"]
    mat = bpy.data.materials.new("obj")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    k = m["kind"]
    if k == "subsurface":
        p = nt.nodes.new("ShaderNodeBsdfPrincipled")
        p.subsurface_method = {"randomwalk": "RANDOM_WALK", "burley": "BURLEY"}[m["method"]]
        a = (*m["reflectance"], 1.0)
        p.inputs["Base Color"].default_value = a
        p.inputs["Subsurface Color"].default_value = a
        p.inputs["Subsurface"].default_value = 1.0  # weight 1, and radius multiplier 1
        p.inputs["Subsurface Radius"].default_value = m["cycles_radius"]
        if "checker" in m:
            # Cycles' checker (svm_checker.h): Color1 where the parities of floor(x), floor(y),
            # floor(z) of p x Scale sum to odd, Color2 where even (pbrt-v4's tex1), in object
            # space (the objects' transforms are the identity, the sphere at the origin: the
            # world space of the pbrt texture). The radius follows the colour (its conversion
            # depends on the reflectance: scenes.cycles_radius).
            c = m["checker"]
            coord = nt.nodes.new("ShaderNodeTexCoord")
            for socket, even, odd in (("Base Color", a, (*c["reflectance"], 1.0)),
                                      ("Subsurface Color", a, (*c["reflectance"], 1.0)),
                                      ("Subsurface Radius", (*m["cycles_radius"], 1.0), (*c["cycles_radius"], 1.0))):
                ch = nt.nodes.new("ShaderNodeTexChecker")
                ch.inputs["Scale"].default_value = 1.0 / c["cell"]
                ch.inputs["Color1"].default_value = odd
                ch.inputs["Color2"].default_value = even
                nt.links.new(coord.outputs["Object"], ch.inputs["Vector"])
                nt.links.new(ch.outputs["Color"], p.inputs[socket])
        p.inputs["Subsurface IOR"].default_value = m["eta"]
        p.inputs["Subsurface Anisotropy"].default_value = m["g"]
        p.inputs["Metallic"].default_value = 0.0
        p.inputs["Specular"].default_value = fresnel_f0(m["eta"]) / 0.08
        p.inputs["Specular Tint"].default_value = 0.0
        p.inputs["Roughness"].default_value = 0.0
        p.inputs["Sheen"].default_value = 0.0
        p.inputs["Clearcoat"].default_value = 0.0
        p.inputs["IOR"].default_value = m["eta"]
        p.inputs["Transmission"].default_value = 0.0
        nt.links.new(p.outputs["BSDF"], out.inputs["Surface"])
    elif k == "medium":
        # sigma_s = density x colour (Volume Scatter); sigma_a = density x (1 - colour)
        # (Volume Absorption).
        ss, sa = m["sigma_s"], m["sigma_a"]
        ds, da = max(ss), max(sa)
        sca = nt.nodes.new("ShaderNodeVolumeScatter")
        sca.inputs["Color"].default_value = (*[x / ds for x in ss], 1.0)
        sca.inputs["Density"].default_value = ds
        sca.inputs["Anisotropy"].default_value = m["g"]
        ab = nt.nodes.new("ShaderNodeVolumeAbsorption")
        ab.inputs["Color"].default_value = (*[1.0 - x / da for x in sa], 1.0)
        ab.inputs["Density"].default_value = da
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(sca.outputs["Volume"], add.inputs[0])
        nt.links.new(ab.outputs["Volume"], add.inputs[1])
        nt.links.new(add.outputs["Shader"], out.inputs["Volume"])
        if m["boundary"] == "matched":
            surf = nt.nodes.new("ShaderNodeBsdfTransparent")
            surf.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        else:
            surf = nt.nodes.new("ShaderNodeBsdfGlass")
            surf.distribution = "SHARP"
            surf.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
            surf.inputs["IOR"].default_value = m["eta"]
            surf.inputs["Roughness"].default_value = 0.0
        nt.links.new(surf.outputs["BSDF"], out.inputs["Surface"])
        mat.cycles.homogeneous_volume = True  # analytic free flights, no ray marching
        mat.cycles.volume_sampling = "MULTIPLE_IMPORTANCE"
    elif k == "diffuse":
        d = nt.nodes.new("ShaderNodeBsdfDiffuse")
        d.inputs["Color"].default_value = (*m["reflectance"], 1.0)
        d.inputs["Roughness"].default_value = 0.0  # Lambertian
        nt.links.new(d.outputs["BSDF"], out.inputs["Surface"])
    else:
        raise ValueError(k)
    obj.data.materials.clear()
    obj.data.materials.append(mat)


settings(job["threads"])
camera()
world()
for L in sc["lights"]:
    key_light(L)
if sc["material"] and sc["material"]["kind"] == "grid":
    grid_volume(sc["material"])
elif sc.get("shape"):  # none: the lights alone (environments.py's check)
    obj = shape()
    material(obj)

c = scene.cycles
info = dict(
    blender=bpy.app.version_string,
    sampling_pattern=c.sampling_pattern,
    sampling_pattern_name=c.bl_rna.properties["sampling_pattern"].enum_items[c.sampling_pattern].name,
    scrambling_distance=c.scrambling_distance, auto_scrambling_distance=c.auto_scrambling_distance,
    light_sampling_threshold=c.light_sampling_threshold,
    threads_mode=scene.render.threads_mode, threads=scene.render.threads,
    adaptive=c.use_adaptive_sampling, denoising=c.use_denoising,
    clamp_direct=c.sample_clamp_direct, clamp_indirect=c.sample_clamp_indirect,
    blur_glossy=c.blur_glossy, caustics_reflective=c.caustics_reflective, caustics_refractive=c.caustics_refractive,
    max_bounces=c.max_bounces, diffuse_bounces=c.diffuse_bounces, glossy_bounces=c.glossy_bounces,
    transmission_bounces=c.transmission_bounces, volume_bounces=c.volume_bounces,
    transparent_max_bounces=c.transparent_max_bounces,
    pixel_filter=c.pixel_filter_type, filter_width=c.filter_width,
    view_transform=scene.view_settings.view_transform, look=scene.view_settings.look,
    film_transparent=scene.render.film_transparent,
)
print("vs_cycles: Cycles settings:", json.dumps(info), flush=True)

results = []
for r in job["renders"]:
    # Dermis' renders of the same sample count and seed first (run.py: the two renderers'
    # sweeps interleaved, so that the shared machine's slow spells fall on both).
    dermis_runs = []
    for d in r.get("dermis_before", []):
        p = render.run(d["cmd"], check=False)
        dermis_runs.append(dict(d, returncode=p.returncode, stderr=p.log, wall=p.wall))
    c.seed = r["seed"]
    c.time_limit = r.get("time_limit", 0.0)
    c.samples = r["spp"]
    scene.render.filepath = r["out"]
    # The wall time of the operator (scene sync + render + writing the EXR); Cycles' own
    # render_time / synchronization_time land in the EXR's metadata (read by run.py), and
    # the samples reached under a time limit in the log's "Sample N/M" lines.
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    wall = time.perf_counter() - t0
    rec = dict(r, wall=wall, dermis=dermis_runs)
    results.append(rec)
    print(f"vs_cycles: rendered {r['out']} ({r['spp']} spp, seed {r['seed']}, time limit {c.time_limit:g}) "
          f"in {wall:.2f} s", flush=True)

json.dump(dict(info=info, renders=results), open(job["result"], "w"), indent=1)
