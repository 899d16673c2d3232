#include <pybind11/pybind11.h>

#include "bindings.h"
#include "dermis/scene/diagnostics.h"

PYBIND11_MODULE(_dermis, m) {
  m.doc() = "Dermis: a path tracer for translucent materials (subsurface scattering). See help(dermis).";
  m.attr("__version__") = DERMIS_VERSION;
  // Scene errors carry "file:line:col: error: what and why".
  pybind11::register_exception<dermis::SceneError>(m, "SceneError", PyExc_ValueError);
  dermis::python::bind_scene(m);
  dermis::python::bind_render(m);
  dermis::python::bind_images(m);
  dermis::python::bind_sss(m);
}
