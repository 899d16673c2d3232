"""Dermis: a path tracer for translucent materials (subsurface scattering).

    import dermis
    scene = dermis.load_scene("scenes/demo.pbrt")
    scene.set_material(scene.subsurface_materials[0], method="disk")
    image = dermis.render(scene, spp=16, seed=1)      # float32 (height, width, 3), linear RGB
    dermis.write_image("out.exr", image)

Scenes: load_scene, Scene (resolution, spp, seed, camera, materials, set_material).
Rendering: render (releases the GIL; Ctrl-C raises RenderInterrupted with the partial
image). Images: read_image, write_image, compare, error_map, subsurface_mask.
Subsurface libraries: Profile, simulate_halfspace, chandrasekhar_albedo, AlbedoInversion.
The equal-time comparison of methods: python3 -m dermis.study (or `dermis study`).
Errors in scenes raise SceneError ("file:line:col: error: what and why").
Build-tree use: PYTHONPATH=build/python /usr/bin/python3 (see README.md).
"""

from ._dermis import (
    AlbedoInversion,
    Profile,
    RenderInterrupted,
    Scene,
    SceneError,
    __version__,
    chandrasekhar_albedo,
    compare,
    error_map,
    load_scene,
    read_image,
    render,
    simulate_halfspace,
    subsurface_mask,
    write_image,
)

for _name in ("AlbedoInversion", "Profile", "Scene", "SceneError"):
    globals()[_name].__module__ = "dermis"
del _name

__all__ = [
    "AlbedoInversion", "Profile", "RenderInterrupted", "Scene", "SceneError", "__version__",
    "chandrasekhar_albedo", "compare", "error_map", "load_scene", "read_image", "render",
    "simulate_halfspace", "subsurface_mask", "write_image",
]
