// The Python module `_dermis` (re-exported by the package `dermis`): one file per part.
#pragma once

#include <pybind11/pybind11.h>

namespace dermis::python {

void bind_scene(pybind11::module_& m);   // scene.cpp: load_scene, Scene, Material
void bind_render(pybind11::module_& m);  // render.cpp: render, RenderInterrupted
void bind_images(pybind11::module_& m);  // images.cpp: read/write, compare, error maps, masks
void bind_sss(pybind11::module_& m);     // sss.cpp: profiles, half-space simulator, albedo inversion

}  // namespace dermis::python
