// The parameters of pbrt-v4's grid media (media.cpp GridMedium::Create,
// RGBGridMedium::Create, CloudMedium::Create), read into a MediumDesc; MakeNamedMedium
// itself is in parser_appearance.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "dermis/scene/scene_parser.h"
#include "dermis/scene/spectra.h"

namespace dermis {

namespace {

// A coefficient given as a colour or a spectrum, or `def`.
RGB coefficient_param(const ParamList& pl, const char* name, RGB def, Diagnostics& diag) {
  const ParsedParam* p = pl.find(name);
  return p ? spectrum_param_rgb(*p, diag, SpectrumType::Unbounded) : def;
}

// The grid's values of parameter `name` (`arity` floats each), null when absent: their count
// must be the grid's, and each value finite and at least zero. The parameter's own floats
// when it is long (shared, not copied): a grid exists once.
std::shared_ptr<const FloatArray> grid_values(const ParamList& pl, const MediumDesc& m, const char* name,
                                              std::initializer_list<const char*> types, std::size_t arity) {
  std::shared_ptr<const FloatArray> v = pl.get_float_array(name, types, arity);
  if (!v) return v;
  const ParsedParam& p = *pl.find(name);
  const std::size_t expected = std::size_t(m.nx) * std::size_t(m.ny) * std::size_t(m.nz);
  if (v->size() / arity != expected)
    throw SceneError(p.value_loc, fmt::format("medium \"{}\": \"{}\" has {} values; the grid nx x ny x nz = {} x {} x "
                                              "{} needs {}",
                                              m.name, name, v->size() / arity, m.nx, m.ny, m.nz, expected));
  const float* values = v->data();
  for (std::size_t i = 0; i < v->size(); ++i)
    if (!(values[i] >= 0) || !std::isfinite(values[i]))
      throw SceneError(p.value_at(i), fmt::format("medium \"{}\": \"{}\" must be finite and at least 0 (value {} of "
                                                  "the grid is {})",
                                                  m.name, name, i / arity, values[i]));
  return v;
}

// The box: pbrt-v4's Bounds3f(p0, p1), corners in any order, but with a volume.
void read_grid_box(const ParamList& pl, MediumDesc& m) {
  const Vec3 a = pl.get_vec3("p0", {"point3"}).value_or(m.p0), b = pl.get_vec3("p1", {"point3"}).value_or(m.p1);
  for (int k = 0; k < 3; ++k)
    if (!(a[k] != b[k]) || !std::isfinite(a[k]) || !std::isfinite(b[k])) {
      const ParsedParam* p = pl.find("p1") ? pl.find("p1") : pl.find("p0");
      throw SceneError(p ? p->value_loc : m.loc,
                       fmt::format("medium \"{}\": the box p0 ({} {} {}) to p1 ({} {} {}) has no volume (equal or "
                                   "non-finite {} coordinates)",
                                   m.name, a.x, a.y, a.z, b.x, b.y, b.z, "xyz"[k]));
    }
  m.p0 = min(a, b);
  m.p1 = max(a, b);
}

void read_grid_resolution(const ParamList& pl, MediumDesc& m) {
  for (auto [name, n] : {std::pair{"nx", &m.nx}, {"ny", &m.ny}, {"nz", &m.nz}}) {
    *n = pl.get_int(name, 1);
    if (*n < 1)
      throw SceneError(pl.find(name)->value_loc,
                       fmt::format("medium \"{}\": \"{}\" must be at least 1, got {}", m.name, name, *n));
  }
  if (double(m.nx) * double(m.ny) * double(m.nz) > double(std::numeric_limits<int32_t>::max()))
    throw SceneError(pl.find("nx")->value_loc,
                     fmt::format("medium \"{}\": a grid of {} x {} x {} is too large", m.name, m.nx, m.ny, m.nz));
}

// A temperature's offset and scale (pbrt-v4 reads "temperaturecutoff" as the offset where
// "temperatureoffset" is absent).
void read_temperature_mapping(const ParamList& pl, MediumDesc& m) {
  m.temperature_offset = pl.get_float("temperatureoffset", pl.get_float("temperaturecutoff", 0));
  m.temperature_scale = pl.get_float("temperaturescale", 1);
  for (const char* name : {"temperatureoffset", "temperaturecutoff", "temperaturescale"})
    if (const ParsedParam* p = pl.find(name); p && !std::isfinite(pl.get_float(name, 0)))
      throw SceneError(p->value_loc, fmt::format("medium \"{}\": \"{}\" must be finite", m.name, name));
}

}  // namespace

void SceneParser::read_grid_emission(const ParamList& pl, MediumDesc& m) {
  if (m.type == "uniformgrid") {
    if (const ParsedParam* le = pl.find("Le")) {
      m.Le = spectrum_param_rgb(*le, s_.diagnostics, SpectrumType::Illuminant);
      m.Le_data = spectrum_data(pl, "Le", SpectrumType::Illuminant);
      if (!(std::min({m.Le[0], m.Le[1], m.Le[2]}) >= 0) || !std::isfinite(m.Le.max()))
        throw SceneError(le->value_loc, fmt::format("medium \"{}\": \"Le\" must be finite and not negative", m.name));
      if (pl.find("temperature"))
        throw SceneError(
            pl.find("temperature")->param.loc,
            fmt::format("medium \"{}\": both \"Le\" and \"temperature\" given (pbrt-v4 takes one)", m.name));
    }
    m.le_scale_grid = grid_values(pl, m, "Lescale", {"float"}, 1);
    m.temperature = grid_values(pl, m, "temperature", {"float"}, 1);
    read_temperature_mapping(pl, m);
  } else if (m.type == "rgbgrid") {
    m.Le_grid = grid_values(pl, m, "Le", {"rgb"}, 3);
    if (m.Le_grid && !m.sigma_a_grid)
      throw SceneError(pl.find("Le")->value_loc,
                       fmt::format("rgbgrid medium \"{}\": \"Le\" needs \"rgb sigma_a\" (pbrt-v4)", m.name));
    m.Lescale = pl.get_float("Lescale", 1);
    if (!(m.Lescale >= 0) || !std::isfinite(m.Lescale))
      throw SceneError(pl.find("Lescale")->value_loc, "Lescale must be finite and not negative");
  }
}

void SceneParser::read_grid_medium(const ParamList& pl, MediumDesc& m) {
  m.medium_to_world = gs_.ctm;
  m.g = pl.get_float("g", 0);
  if (!(m.g > -1 && m.g < 1))
    throw SceneError(pl.find("g")->value_loc, fmt::format("g must be in (-1, 1), got {}", m.g));
  if (m.type != "rgbgrid") {  // coefficients per unit density
    m.sigma_a = coefficient_param(pl, "sigma_a", RGB(1), s_.diagnostics);
    m.sigma_s = coefficient_param(pl, "sigma_s", RGB(1), s_.diagnostics);
    m.sigma_a_data = spectrum_data(pl, "sigma_a", SpectrumType::Unbounded);
    m.sigma_s_data = spectrum_data(pl, "sigma_s", SpectrumType::Unbounded);
    for (auto [name, v] : {std::pair{"sigma_a", m.sigma_a}, {"sigma_s", m.sigma_s}})
      if (v[0] < 0 || v[1] < 0 || v[2] < 0)
        throw SceneError(pl.find(name) ? pl.find(name)->value_loc : m.loc,
                         fmt::format("medium \"{}\": \"{}\" must not be negative", m.name, name));
  }
  if (m.type != "cloud") {  // pbrt-v4's cloud has no scale
    m.scale = pl.get_float("scale", 1);
    if (!(m.scale >= 0) || !std::isfinite(m.scale))
      throw SceneError(pl.find("scale")->value_loc, "scale must be finite and not negative");
  }
  if (m.type == "nanovdb") {
    read_nanovdb_medium(pl, m);
    return;
  }
  read_grid_box(pl, m);
  if (m.type == "cloud") {
    m.cloud_density = pl.get_float("density", 1);
    m.wispiness = pl.get_float("wispiness", 1);
    m.frequency = pl.get_float("frequency", 5);
    for (const char* name : {"density", "wispiness", "frequency"})
      if (const ParsedParam* p = pl.find(name); p && !std::isfinite(pl.get_float(name, 0)))
        throw SceneError(p->value_loc, fmt::format("medium \"{}\": \"{}\" must be finite", m.name, name));
    return;
  }
  read_grid_resolution(pl, m);
  if (m.type == "uniformgrid") {
    m.density = grid_values(pl, m, "density", {"float"}, 1);
    if (!m.density)
      throw SceneError(m.loc,
                       fmt::format("uniformgrid medium \"{}\" needs \"float density\" (nx x ny x nz values)", m.name));
  } else {
    m.sigma_a_grid = grid_values(pl, m, "sigma_a", {"rgb"}, 3);
    m.sigma_s_grid = grid_values(pl, m, "sigma_s", {"rgb"}, 3);
    if (!m.sigma_a_grid && !m.sigma_s_grid)
      throw SceneError(m.loc, fmt::format("rgbgrid medium \"{}\" needs \"rgb sigma_a\" and/or \"rgb sigma_s\" (nx x "
                                          "ny x nz colours each)",
                                          m.name));
  }
  read_grid_emission(pl, m);
}

void SceneParser::read_nanovdb_medium(const ParamList& pl, MediumDesc& m) {
  const ParsedParam* file = pl.find("filename");
  if (!file)
    throw SceneError(m.loc, fmt::format("nanovdb medium \"{}\" needs \"string filename\" (an .nvdb file)", m.name));
  m.filename = scene_path(pl.get_string("filename", ""), file->value_loc, "NanoVDB");
  m.filename_loc = file->value_loc;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(m.filename, ec))
    throw SceneError(file->value_loc, fmt::format("nanovdb medium: could not read '{}': no such file", m.filename));
  m.grid_name = pl.get_string("gridname", m.grid_name);
  m.temperature_name = pl.get_string("temperaturename", m.temperature_name);
  m.Lescale = pl.get_float("Lescale", 1);
  if (!(m.Lescale >= 0) || !std::isfinite(m.Lescale))
    throw SceneError(pl.find("Lescale")->value_loc, "Lescale must be finite and not negative");
  read_temperature_mapping(pl, m);
}

void SceneParser::resolve_subsurface_interiors() {
  for (MaterialDesc& md : s_.materials) {
    SubsurfaceParams& sp = md.subsurface;
    if (md.type != MaterialDesc::Type::Subsurface || sp.interior.empty()) continue;
    sp.interior_medium = resolve_medium(sp.interior_medium);
    const MediumDesc& m = s_.media[std::size_t(sp.interior_medium)];
    if (m.type == "homogeneous") {
      // The medium's coefficients, as if given on the material (scale, spectra and g too):
      // every method takes them.
      if (m.Le.max() > 0)
        s_.diagnostics.warn(sp.interior_loc, fmt::format("subsurface: the emission of medium \"{}\" is not rendered "
                                                         "inside a subsurface material (its coefficients are)",
                                                         m.name));
      sp.sigma_a = m.sigma_a * m.scale;
      sp.sigma_s = m.sigma_s * m.scale;
      sp.scale = m.scale;
      sp.g = m.g;
      auto data = [&](int i) {
        return i >= 0 ? std::make_shared<const std::vector<float>>(s_.spectra[std::size_t(i)]) : nullptr;
      };
      sp.sigma_a_spectrum = data(m.sigma_a_data);
      sp.sigma_s_spectrum = data(m.sigma_s_data);
      for (int c = 0; c < 3; ++c)
        if (!((*sp.sigma_a)[c] + (*sp.sigma_s)[c] > 0))
          throw SceneError(sp.interior_loc,
                           fmt::format("subsurface: medium \"{}\" has sigma_a + sigma_s = 0 in a channel: nothing "
                                       "for light to meet inside (give it a positive extinction, or no subsurface)",
                                       m.name));
      sp.interior_medium = -1;
      continue;
    }
    using M = SubsurfaceParams::Method;
    if (sp.method != M::RandomWalk && sp.method != M::Volumetric)
      throw SceneError(sp.interior_loc,
                       fmt::format("subsurface: the grid medium \"{}\" (\"{}\") varies inside the object, which the "
                                   "\"{}\" method cannot follow (it takes one homogeneous medium): use \"method\" "
                                   "\"randomwalk\" or \"volumetric\", or a homogeneous interior",
                                   m.name, m.type, to_string(sp.method)));
    sp.g = m.g;
  }
}

}  // namespace dermis
