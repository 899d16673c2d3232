// load_scene, Scene (inspection and changes between renders) and Material.
#include "scene.h"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <mutex>
#include <utility>
#include <vector>

#include "bindings.h"
#include "dermis/render/film.h"
#include "dermis/scene/params.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/subsurface_params.h"
#include "interruptible.h"

namespace py = pybind11;

namespace dermis::python {

void Scene::changed() {
  if (busy) throw std::runtime_error("the scene is being rendered; change it after render() returns");
  prepared.reset();
}

namespace {

void warn_all(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 2) != 0) throw py::error_already_set();
}

std::shared_ptr<Scene> load_scene(const py::object& source, const std::string& base_dir, const py::object& progress) {
  auto scene = std::make_shared<Scene>();
  const bool is_text = py::isinstance<py::str>(source) && source.cast<std::string>().find('\n') != std::string::npos;
  std::string text, path;
  if (is_text)
    text = source.cast<std::string>();
  else
    path = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
  scene->source = is_text ? "<string>" : path;

  // The parse runs on a worker thread (meshes may take a while to read); this thread
  // waits without the GIL, hands the stages reported since the last poll to `progress`
  // (each stage's latest fraction, so that a stage shorter than a poll is still seen),
  // and stops the parse on Ctrl-C.
  std::mutex mutex;
  std::vector<std::pair<std::string, double>> pending;  // guarded by mutex
  std::pair<std::string, double> reported{"", -1};
  std::atomic<bool> cancel{false};
  LoadMonitor monitor;
  monitor.cancel = &cancel;
  if (!progress.is_none())
    monitor.progress = [&](const std::string& s, double f) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!pending.empty() && pending.back().first == s)
        pending.back().second = f;
      else
        pending.emplace_back(s, f);
    };
  auto poll = [&] {
    std::vector<std::pair<std::string, double>> states;
    {
      std::lock_guard<std::mutex> lock(mutex);
      states.swap(pending);
    }
    for (auto& state : states) {
      if (state == reported) continue;
      reported = state;
      progress(state.first, state.second);
    }
  };
  auto error = run_interruptible(
      [&] {
        scene->desc = is_text ? parse_scene_string(text, "<string>", base_dir.empty() ? "." : base_dir, {}, &monitor)
                              : parse_scene_file(path, {}, &monitor);
      },
      cancel, progress.is_none() ? std::function<void()>() : std::function<void()>(poll));
  if (error) throw *error;
  warn_all(scene->desc.diagnostics.warnings);
  return scene;
}

const char* material_type_name(MaterialDesc::Type t) {
  switch (t) {
    case MaterialDesc::Type::Diffuse:
      return "diffuse";
    case MaterialDesc::Type::Dielectric:
      return "dielectric";
    case MaterialDesc::Type::Conductor:
      return "conductor";
    case MaterialDesc::Type::Interface:
      return "interface";
    case MaterialDesc::Type::Subsurface:
      return "subsurface";
    case MaterialDesc::Type::CoatedDiffuse:
      return "coateddiffuse";
    case MaterialDesc::Type::CoatedConductor:
      return "coatedconductor";
    case MaterialDesc::Type::DiffuseTransmission:
      return "diffusetransmission";
    case MaterialDesc::Type::Mix:
      return "mix";
  }
  return "?";
}

// A parameter's value as Python sees it: one number, string or bool as itself, several
// as a tuple.
py::object param_value(const Param& p) {
  py::list values;
  for (std::size_t i = 0; i < p.number_count(); ++i) {
    const double x = p.number(i);
    values.append(p.type == "integer" ? py::object(py::int_(int64_t(x))) : py::float_(x));
  }
  for (const std::string& s : p.strings) values.append(s);
  for (bool b : p.bools) values.append(py::bool_(b));
  if (values.size() == 1) return values[0];
  return py::tuple(values);
}

// One Python keyword argument as pbrt parameter text: str -> string, bool -> bool,
// int or float -> float (integer when the material already has it as one, or when it is
// a whole number and the subsurface parameter table declares it integer, e.g.
// maxpoints), a sequence of 3 numbers -> rgb, of other lengths -> float array.
std::string kwarg_text(const MaterialDesc& m, const std::string& name, const py::handle& value) {
  Param p;
  p.name = name;
  if (py::isinstance<py::str>(value)) {
    p.type = "string";
    p.strings = {value.cast<std::string>()};
  } else if (py::isinstance<py::bool_>(value)) {
    p.type = "bool";
    p.bools = {value.cast<bool>()};
  } else if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
    // A Python float with a whole value (4000.0) is an integer too; one that is not stays
    // float, and the parser refuses it where an integer is needed.
    const double x = value.cast<double>();
    const bool whole = x == std::floor(x);
    p.type = "float";
    if (m.params && whole)
      if (const ParsedParam* q = m.params->find(name); q && q->type == "integer") p.type = "integer";
    if (m.type == MaterialDesc::Type::Subsurface && whole)
      for (const SubsurfaceParameter& row : subsurface_parameters())
        if (name == row.name && std::string_view(row.type) == "integer") p.type = "integer";
    p.numbers = {x};
  } else if (py::isinstance<py::sequence>(value)) {
    p.numbers = value.cast<std::vector<double>>();
    p.type = p.numbers.size() == 3 ? "rgb" : "float";
  } else {
    throw py::type_error(fmt::format("{}: expected a str, bool, number or a sequence of numbers, got {}", name,
                                     std::string(py::str(value.get_type().attr("__name__")))));
  }
  return param_text(p);
}

std::size_t material_index(const Scene& s, const py::object& key) {
  if (py::isinstance<py::int_>(key)) {
    const int64_t i = key.cast<int64_t>();
    if (i < 0 || i >= int64_t(s.desc.materials.size()))
      throw py::index_error(fmt::format("material {} does not exist (the scene has {})", i, s.desc.materials.size()));
    return std::size_t(i);
  }
  const std::string name = key.cast<std::string>();
  std::string names;
  for (std::size_t i = 0; i < s.desc.materials.size(); ++i) {
    if (s.desc.materials[i].name == name) return i;
    if (!s.desc.materials[i].name.empty()) names += (names.empty() ? "" : ", ") + s.desc.materials[i].name;
  }
  throw py::key_error(
      fmt::format("no material named \"{}\" (named materials: {})", name, names.empty() ? "none" : names));
}

py::dict material_dict(const MaterialDesc& m, std::size_t index) {
  py::dict parameters, types;
  for (const Param& p : m.params ? m.params->as_written() : std::vector<Param>{}) {
    if (p.name == "type" && !m.name.empty()) continue;  // MakeNamedMaterial's type: .type says it
    parameters[py::str(p.name)] = param_value(p);
    types[py::str(p.name)] = p.type;
  }
  py::dict d;
  d["index"] = index;
  d["name"] = m.name;
  d["type"] = material_type_name(m.type);
  d["parameters"] = parameters;
  d["types"] = types;
  d["location"] = m.loc.str();
  return d;
}

}  // namespace

void bind_scene(py::module_& m) {
  m.def("load_scene", &load_scene, py::arg("source"), py::arg("base_dir") = "", py::kw_only(),
        py::arg("progress") = py::none(),
        R"(Reads a pbrt-v4 scene (Dermis' subset, docs/scene-format.md).

source: a path (str or os.PathLike) of a .pbrt file (gzip-compressed or not), or the
  scene text itself when it is a str containing a newline (relative paths in it resolve
  against base_dir, default the working directory).
progress: a callable progress(stage, fraction), called on this thread about every 50 ms
  with the stage running ('loading bust.ply', 'reading bust.ply', 'subdividing
  (loopsubdiv)', ...) and the fraction of it done, in [0, 1], non-decreasing within a
  stage. Every stage is handed over at least once, with its latest fraction (a stage
  shorter than 50 ms too); the last state is always handed over.
  An exception it raises stops the load.
The file is read without the GIL; Ctrl-C stops it promptly (KeyboardInterrupt).
Meshes and textures are read once; materials can then be changed between renders
(Scene.set_material) without reading them again. Warnings (ignored or approximated
parameters) are issued as UserWarning. Raises dermis.SceneError ("file:line:col: error:
what and why") for bad input, FileNotFoundError-like SceneError for missing files.)");

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A parsed scene: see load_scene.")
      .def_property_readonly(
          "source", [](const Scene& s) { return s.source; }, "The file read, or '<string>'.")
      .def_property(
          "resolution", [](const Scene& s) { return py::make_tuple(s.desc.film.xres, s.desc.film.yres); },
          [](Scene& s, std::pair<int, int> wh) {
            const auto [w, h] = wh;
            if (w <= 0 || h <= 0 || w > 65536 || h > 65536 || int64_t(w) * h > (int64_t(1) << 28))
              throw py::value_error(
                  fmt::format("resolution {}x{}: each side must be in 1..65536 and the film at most "
                              "2^28 pixels",
                              w, h));
            s.changed();
            s.desc.film.xres = w;
            s.desc.film.yres = h;
          },
          "(width, height) of the film in pixels; settable. A crop window, if any, applies to it.")
      .def_property(
          "spp", [](const Scene& s) { return s.desc.settings.spp; },
          [](Scene& s, int spp) {
            if (spp <= 0) throw py::value_error("spp must be positive");
            s.desc.settings.spp = spp;
          },
          "Samples per pixel render() takes by default (the scene's Sampler pixelsamples); settable.")
      .def_property(
          "seed", [](const Scene& s) { return s.desc.settings.seed; },
          [](Scene& s, int seed) {
            if (seed < 0) throw py::value_error("seed must be >= 0");
            s.desc.settings.seed = seed;
          },
          "The seed render() uses by default (the scene's Sampler \"integer seed\"); settable.")
      .def_property_readonly(
          "sampler", [](const Scene& s) { return sampler_kind_name(s.desc.settings.sampler); },
          "The scene's sampler: 'sobol' or 'independent'.")
      .def_property_readonly(
          "camera",
          [](const Scene& s) {
            const CameraDesc& c = s.desc.camera;
            py::dict d;
            d["type"] = "perspective";
            d["fov"] = c.fov;
            d["lens_radius"] = c.lens_radius;
            d["focal_distance"] = c.focal_distance;
            std::vector<std::vector<float>> rows(4, std::vector<float>(4));
            for (int r = 0; r < 4; ++r)
              for (int k = 0; k < 4; ++k) rows[r][k] = c.camera_to_world.matrix().m[r][k];
            d["camera_to_world"] = rows;
            d["location"] = c.loc.str();
            return d;
          },
          "The camera: a dict with type, fov (degrees, shorter image axis), lens_radius, focal_distance, "
          "camera_to_world (4x4 rows) and location (where the scene sets it).")
      .def_property_readonly(
          "materials",
          [](const Scene& s) {
            py::list out;
            for (std::size_t i = 0; i < s.desc.materials.size(); ++i) out.append(material_dict(s.desc.materials[i], i));
            return out;
          },
          "Every material, in the order the scene defines them: dicts with index, name (MakeNamedMaterial's, or ''), "
          "type, parameters (name -> value as written: a number, str or bool, or a tuple of several), types (name -> "
          "the type as written) and location (file:line:col).")
      .def_property_readonly(
          "subsurface_materials",
          [](const Scene& s) {
            std::vector<std::size_t> out;
            for (std::size_t i = 0; i < s.desc.materials.size(); ++i)
              if (s.desc.materials[i].type == MaterialDesc::Type::Subsurface) out.push_back(i);
            return out;
          },
          "Indices of the `subsurface` materials.")
      .def_property_readonly(
          "shape_count", [](const Scene& s) { return s.desc.shapes.size(); }, "Number of top-level shapes.")
      .def_property_readonly(
          "warnings", [](const Scene& s) { return s.desc.diagnostics.warnings; },
          "The warnings parsing the scene gave.")
      .def(
          "set_material",
          [](Scene& s, const py::object& key, const std::string& text, const py::kwargs& kwargs) {
            const std::size_t i = material_index(s, key);
            std::string params = text;
            for (const auto& [name, value] : kwargs)
              params += " " + kwarg_text(s.desc.materials[i], name.cast<std::string>(), value);
            s.changed();
            warn_all(set_material_parameters(s.desc, i, params, "<set_material>"));
          },
          py::arg("material"), py::arg("text") = "",
          R"(Changes parameters of a material, as if the scene had been written with them.

material: the material's index (Scene.materials) or MakeNamedMaterial name.
text: pbrt-v4 parameter text, e.g. '"string method" "disk" "texture reflectance" "skin"'.
**params: the same as Python values: str -> "string", bool -> "bool", int or float ->
  "float" (or "integer" if the material has it so, or a subsurface material's
  integer parameter such as maxpoints), 3 numbers -> "rgb", e.g.
  set_material("skin", method="disk", mfp=(1.0, 0.5, 0.25)).
Parameters named replace the material's; the rest stay. Meshes and textures are not read
again; the next render rebuilds what depends on materials. Raises dermis.SceneError
("<set_material>:1:col: error: ...") and leaves the material unchanged on bad input.)")
      .def("__repr__", [](const Scene& s) {
        return fmt::format("<dermis.Scene '{}': {}x{}, {} materials, {} shapes>", s.source, s.desc.film.xres,
                           s.desc.film.yres, s.desc.materials.size(), s.desc.shapes.size());
      });
}

}  // namespace dermis::python
