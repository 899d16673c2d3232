#include "dermis/materials/subsurface_params.h"

#include <fmt/format.h>

#include <cmath>

#include "dermis/scene/medium_presets.h"

namespace dermis {

namespace {

template <class E>
struct Named {
  const char* name;
  E value;
};

constexpr Named<SubsurfaceParams::Method> kMethods[] = {
    {"volumetric", SubsurfaceParams::Method::Volumetric},
    {"disk", SubsurfaceParams::Method::Disk},
    {"disk-single-axis", SubsurfaceParams::Method::DiskSingleAxis},
    {"sphere-lines", SubsurfaceParams::Method::SphereLines},
    {"sphere-lines-retry", SubsurfaceParams::Method::SphereLinesRetry},
    {"randomwalk", SubsurfaceParams::Method::RandomWalk},
    {"pointcloud", SubsurfaceParams::Method::PointCloud},
};
constexpr Named<SubsurfaceParams::Profile> kProfiles[] = {
    {"gaussian", SubsurfaceParams::Profile::Gaussian}, {"skin6", SubsurfaceParams::Profile::Skin6},
    {"cubic", SubsurfaceParams::Profile::Cubic},       {"dipole", SubsurfaceParams::Profile::Dipole},
    {"burley", SubsurfaceParams::Profile::Burley},     {"burley-dmfp", SubsurfaceParams::Profile::BurleyDiffuseMfp},
    {"tabulated", SubsurfaceParams::Profile::Tabulated},
};
constexpr Named<SubsurfaceParams::Boundary> kBoundaries[] = {
    {"diffuse", SubsurfaceParams::Boundary::Diffuse},
    {"dielectric", SubsurfaceParams::Boundary::Dielectric},
    {"matched", SubsurfaceParams::Boundary::Matched},
};
constexpr Named<SubsurfaceParams::WalkSampling> kWalkSamplings[] = {
    {"classical", SubsurfaceParams::WalkSampling::Classical},
    {"dwivedi", SubsurfaceParams::WalkSampling::Dwivedi},
    {"mis", SubsurfaceParams::WalkSampling::Mis},
};

template <class E, std::size_t N>
E lookup(const Named<E> (&table)[N], const Param& p, const char* what) {
  if (p.strings.size() != 1) throw SceneError(p.loc, fmt::format("\"{}\" needs exactly one string", p.name));
  for (const auto& n : table)
    if (p.strings[0] == n.name) return n.value;
  std::string valid;
  for (const auto& n : table) valid += fmt::format("{}\"{}\"", valid.empty() ? "" : ", ", n.name);
  throw SceneError(p.loc, fmt::format("unknown {} \"{}\" (valid: {})", what, p.strings[0], valid));
}

bool is_spectrum_type(const std::string& t) { return t == "rgb" || t == "color" || t == "float" || t == "spectrum"; }

RGB read_rgb(const Param& p) {
  if (!is_spectrum_type(p.type))
    throw SceneError(p.loc, fmt::format("\"{}\" must be an rgb (or float) value, not \"{}\"", p.name, p.type));
  if (p.type == "spectrum" && (!p.strings.empty() || p.numbers.size() != 3))
    throw SceneError(p.loc, fmt::format("\"{}\": give the subsurface coefficients as \"rgb {}\" [r g b]", p.name, p.name));
  RGB v;
  if (p.numbers.size() == 1)
    v = RGB(float(p.numbers[0]));
  else if (p.numbers.size() == 3)
    v = RGB(float(p.numbers[0]), float(p.numbers[1]), float(p.numbers[2]));
  else
    throw SceneError(p.loc, fmt::format("\"{}\" needs 3 values (r g b) or 1, got {}", p.name, p.numbers.size()));
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(v[c]) || v[c] < 0)
      throw SceneError(p.loc, fmt::format("\"{}\" must be finite and non-negative", p.name));
  return v;
}

float read_float(const Param& p) {
  if (p.type != "float" || p.numbers.size() != 1)
    throw SceneError(p.loc, fmt::format("\"{}\" must be one float", p.name));
  if (!std::isfinite(p.numbers[0])) throw SceneError(p.loc, fmt::format("\"{}\" must be finite", p.name));
  return float(p.numbers[0]);
}

}  // namespace

const char* to_string(SubsurfaceParams::Method m) {
  for (const auto& n : kMethods)
    if (n.value == m) return n.name;
  return "?";
}
const char* to_string(SubsurfaceParams::Profile p) {
  for (const auto& n : kProfiles)
    if (n.value == p) return n.name;
  return "?";
}

SubsurfaceParams read_subsurface_params(const MaterialDesc& m, Diagnostics& diag) {
  SubsurfaceParams s;
  s.loc = m.loc;
  float scale = 1;
  const Param *sigma_a = nullptr, *sigma_s = nullptr, *reflectance = nullptr, *mfp = nullptr, *name = nullptr;
  bool profile_given = false;
  for (const Param& p : m.params) {
    if (p.name == "sigma_a") sigma_a = &p;
    else if (p.name == "sigma_s") sigma_s = &p;
    else if (p.name == "reflectance") reflectance = &p;
    else if (p.name == "mfp") mfp = &p;
    else if (p.name == "name") name = &p;
    else if (p.name == "scale") scale = read_float(p);
    else if (p.name == "eta") s.eta = read_float(p);
    else if (p.name == "g") s.g = read_float(p);
    else if (p.name == "profile") {
      s.profile = lookup(kProfiles, p, "profile");
      profile_given = true;
    }
    else if (p.name == "method") s.method = lookup(kMethods, p, "subsurface method");
    else if (p.name == "boundary") s.boundary = lookup(kBoundaries, p, "boundary");
    else if (p.name == "walksampling") s.walk_sampling = lookup(kWalkSamplings, p, "walk sampling");
    else if (p.name == "epsilon") s.epsilon = read_float(p);
    else if (p.name == "albedoinversion") {
      if (p.strings.size() != 1 || (p.strings[0] != "exact" && p.strings[0] != "fit"))
        throw SceneError(p.loc, "\"albedoinversion\" must be \"exact\" or \"fit\"");
      s.albedo_inversion_fit = p.strings[0] == "fit";
    }
    else if (p.name == "pointdensity") s.point_density = read_float(p);
    else if (p.name == "backwardguiding") {
      if (p.bools.size() != 1) throw SceneError(p.loc, "\"backwardguiding\" must be one bool");
      s.backward_guiding = p.bools[0];
    }
    else if (p.name == "localdisk") {
      if (p.bools.size() != 1) throw SceneError(p.loc, "\"localdisk\" must be one bool");
      s.local_disk = p.bools[0];
    } else if (p.name == "irradiancesamples") {
      if (p.numbers.size() != 1 || p.numbers[0] < 1 || p.numbers[0] != std::floor(p.numbers[0]))
        throw SceneError(p.loc, "\"irradiancesamples\" must be one positive integer");
      s.irradiance_samples = int(p.numbers[0]);
    }
    else if (p.name == "roughness" || p.name == "uroughness" || p.name == "vroughness") {
      if (!p.numbers.empty() && p.numbers[0] > 0)
        diag.warn(p.loc, "subsurface: rough boundaries are not supported; rendered smooth");
    } else if (p.name == "remaproughness" || p.name == "normalmap" || p.name == "displacement") {
      diag.warn(p.loc, fmt::format("subsurface: \"{}\" ignored", p.name));
    } else {
      diag.warn(p.loc, fmt::format("subsurface: unknown parameter \"{} {}\" ignored", p.type, p.name));
    }
  }
  if (scale <= 0) throw SceneError(m.loc, "subsurface: \"scale\" must be positive");
  s.scale = scale;
  if (s.eta < 1.0f || s.eta > 3.0f)
    throw SceneError(m.loc, fmt::format("subsurface: \"eta\" {} is outside [1, 3]", s.eta));
  if (s.g <= -1 || s.g >= 1) throw SceneError(m.loc, "subsurface: \"g\" must be in (-1, 1)");
  if (!(s.epsilon > 0)) throw SceneError(m.loc, "subsurface: \"epsilon\" must be positive");
  if (!(s.point_density > 0)) throw SceneError(m.loc, "subsurface: \"pointdensity\" must be positive");
  // The point cloud's profile is the dipole by default, as in Jensen & Buehler 2002.
  if (s.method == SubsurfaceParams::Method::PointCloud && !profile_given) s.profile = SubsurfaceParams::Profile::Dipole;

  int ways = (name != nullptr) + (sigma_a || sigma_s) + (reflectance || mfp);
  if (ways > 1)
    throw SceneError(m.loc,
                     "subsurface: give either \"name\", or \"sigma_a\" + \"sigma_s\", or \"reflectance\" + \"mfp\", not several");
  if (name) {
    if (name->strings.size() != 1) throw SceneError(name->loc, "\"name\" needs one string");
    auto preset = find_medium_preset(name->strings[0]);
    if (!preset)
      throw SceneError(name->loc, fmt::format("unknown subsurface preset \"{}\" (valid: {})", name->strings[0],
                                              medium_preset_names()));
    // Jensen et al. 2001 values are per mm, used per scene unit as pbrt does; scale converts.
    s.sigma_a = preset->sigma_a * scale;
    s.sigma_s = preset->sigma_s_prime * scale;
    s.g = 0;
  } else if (reflectance || mfp) {
    if (!reflectance || !mfp) throw SceneError(m.loc, "subsurface: \"reflectance\" needs \"mfp\" and vice versa");
    RGB a = read_rgb(*reflectance), l = read_rgb(*mfp);
    for (int c = 0; c < 3; ++c) {
      if (a[c] > 1) throw SceneError(reflectance->loc, "subsurface: \"reflectance\" must be in [0, 1]");
      if (l[c] <= 0) throw SceneError(mfp->loc, "subsurface: \"mfp\" must be positive");
    }
    s.reflectance = a;
    s.mfp = l / scale;  // pbrt-v4: scale multiplies coefficients, so it divides lengths
  } else {
    // pbrt-v4's defaults when nothing is given: whole milk, per scene unit.
    RGB sa(0.0011f, 0.0024f, 0.014f), ss(2.55f, 3.21f, 3.77f);
    if (sigma_a) sa = read_rgb(*sigma_a);
    if (sigma_s) ss = read_rgb(*sigma_s);
    s.sigma_a = sa * scale;
    s.sigma_s = ss * scale;
    for (int c = 0; c < 3; ++c)
      if ((*s.sigma_a)[c] + (*s.sigma_s)[c] <= 0)
        throw SceneError(m.loc, "subsurface: sigma_a + sigma_s must be positive in every channel");
  }
  return s;
}

}  // namespace dermis
