#include "dermis/scene/subsurface_params.h"

#include <fmt/format.h>

#include <cmath>

#include "dermis/scene/medium_presets.h"
#include "dermis/scene/params.h"
#include "dermis/scene/spectra.h"

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
    {"gaussian", SubsurfaceParams::Profile::Gaussian},   {"skin6", SubsurfaceParams::Profile::Skin6},
    {"cubic", SubsurfaceParams::Profile::Cubic},         {"dipole", SubsurfaceParams::Profile::Dipole},
    {"burley", SubsurfaceParams::Profile::Burley},       {"burley-dmfp", SubsurfaceParams::Profile::BurleyDiffuseMfp},
    {"tabulated", SubsurfaceParams::Profile::Tabulated}, {"photonbeam", SubsurfaceParams::Profile::PhotonBeam},
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
E lookup(const Named<E> (&table)[N], const ParsedParam& pp, const char* what) {
  const Param& p = pp.param;
  if (pp.type != "string" || p.strings.size() != 1)
    throw SceneError(pp.value_loc, fmt::format("\"{}\" needs exactly one string", p.name));
  for (const auto& n : table)
    if (p.strings[0] == n.name) return n.value;
  std::string valid;
  for (const auto& n : table) valid += fmt::format("{}\"{}\"", valid.empty() ? "" : ", ", n.name);
  throw SceneError(pp.value_loc, fmt::format("unknown {} \"{}\" (valid: {})", what, p.strings[0], valid));
}

constexpr SubsurfaceParameter kParameters[] = {
    {"reflectance", "rgb | texture", "none", "surface albedo A in [0, 1] per channel, with mfp"},
    {"mfp", "rgb | texture", "none", "mean free path 1/sigma_t per channel (scene units), with reflectance"},
    {"sigma_a", "rgb | texture", "0.0011 0.0024 0.014", "absorption coefficient per scene unit"},
    {"sigma_s", "rgb | texture", "2.55 3.21 3.77", "scattering coefficient per scene unit"},
    {"name", "string", "none", "a measured medium of Jensen et al. 2001, Table 2 (per mm)"},
    {"interior", "string", "none",
     "a named medium (MakeNamedMedium) filling the object: homogeneous, or a grid medium followed by the random walk "
     "and the volumetric reference"},
    {"scale", "float", "1",
     "multiplies the coefficients and mfp, as pbrt-v4 does (or a float texture: per entry point)"},
    {"eta", "float", "1.33", "index of refraction of the boundary, in [1, 3]"},
    {"g", "float", "0", "Henyey-Greenstein anisotropy, in (-1, 1)"},
    {"roughness", "float", "0", "Trowbridge-Reitz roughness of the boundary (both tangent axes; or a float texture)"},
    {"uroughness", "float", "0", "roughness along the first tangent (overrides roughness)"},
    {"vroughness", "float", "0", "roughness along the second tangent (overrides roughness)"},
    {"remaproughness", "bool", "true", "alpha = sqrt(roughness) as pbrt-v4; false: alpha = roughness"},
    {"method", "string", "randomwalk", "how light is carried from entry to exit"},
    {"profile", "string", "burley (dipole for pointcloud)", "the diffusion profile of the profile methods"},
    {"boundary", "string", "dielectric for coefficients, diffuse for reflectance + mfp",
     "random walk: how light leaves (diffuse, dielectric, matched)"},
    {"entry", "string", "refracted",
     "random walk with the diffuse boundary: the direction light enters along, refracted or lambertian (a cosine lobe, "
     "as Cycles 3.x)"},
    {"walksampling", "string", "mis", "random walk: classical, dwivedi or mis"},
    {"backwardguiding", "bool", "false", "random walk: also guide toward the object's far side"},
    {"guidedshare", "float", "0.5",
     "random walk (mis): the share of guided flights, in [0, 1] (unset: the render's pilot chooses)"},
    {"channelpreference", "float", "0.5",
     "random walk: the exponent k of the channel choice, throughput (1 - albedo)^-k, in [0, 8] (unset: the render's "
     "pilot chooses)"},
    {"channelperwalk", "bool", "false",
     "random walk: the camera's first entry takes 3 walks, each carrying one colour channel (unset: the render's pilot "
     "chooses)"},
    {"normalaxis", "float", "0.75",
     "disk: the probability of probing along the normal, in (0, 1); the tangent and the bitangent share the rest "
     "(unset: the render's pilot chooses 0.75, 0.95 or King et al.'s 0.5)"},
    {"albedoinversion", "string", "exact", "(reflectance, mfp) to coefficients: exact or fit"},
    {"pointdensity", "float", "1", "point cloud: points per mean free path squared (with the local disk: the most)"},
    {"illuminationerror", "float", "0.02",
     "point cloud with the local disk: the relative error to which the points must represent the irradiance (0: the "
     "density, up to maxpoints)"},
    {"irradiancesamples", "integer", "64", "point cloud: irradiance samples per point"},
    {"maxpoints", "integer", "250000",
     "point cloud: the most points per object (a budget: fewer when the density asks more, with a warning)"},
    {"epsilon", "float", "0.05", "point cloud: the octree's solid-angle criterion"},
    {"localdisk", "bool", "true", "point cloud: the local disk integral"},
    {"sssgroup", "string", "none", "materials with the same group form one subsurface object"},
    {"normalmap", "string", "none", "ignored, with a warning"},
    {"displacement", "texture", "none", "ignored, with a warning"},
};

RGB checked(RGB v, const ParsedParam& p) {
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(v[c]) || v[c] < 0)
      throw SceneError(p.value_loc, fmt::format("\"{}\" must be finite and non-negative", p.param.name));
  return v;
}

// An rgb, float, spectrum or blackbody value.
RGB read_rgb(const ParsedParam& p, Diagnostics& diag) {
  if (p.type == "float") {
    if (p.param.number_count() != 1)
      throw SceneError(p.value_loc,
                       fmt::format("\"{}\" needs 3 values (r g b) or 1, got {}", p.param.name, p.param.number_count()));
    return checked(RGB(float(p.param.numbers[0])), p);
  }
  if (p.type == "rgb" && p.param.number_count() != 3)
    throw SceneError(p.value_loc,
                     fmt::format("\"{}\" needs 3 values (r g b) or 1, got {}", p.param.name, p.param.number_count()));
  if (p.type != "rgb" && p.type != "spectrum" && p.type != "blackbody")
    throw SceneError(p.value_loc, fmt::format("\"{}\" must be an rgb, spectrum, float or texture value, not \"{}\"",
                                              p.param.name, p.param.type));
  return checked(spectrum_param_rgb(p, diag), p);
}

float read_float(const ParsedParam& p) {
  if (p.type != "float" || p.param.numbers.size() != 1)
    throw SceneError(p.value_loc, fmt::format("\"{}\" must be one float", p.param.name));
  if (!std::isfinite(p.param.numbers[0]))
    throw SceneError(p.value_loc, fmt::format("\"{}\" must be finite", p.param.name));
  return float(p.param.numbers[0]);
}

bool read_bool(const ParsedParam& p) {
  if (p.type != "bool" || p.param.bools.size() != 1)
    throw SceneError(p.value_loc, fmt::format("\"{}\" must be one bool", p.param.name));
  return p.param.bools[0];
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

std::span<const SubsurfaceParameter> subsurface_parameters() { return kParameters; }

namespace {

// What the parameter list gave, for the rules across parameters and the medium's
// parametrisation (read_subsurface_params).
struct GivenParameters {
  float scale = 1;
  const ParsedParam *sigma_a = nullptr, *sigma_s = nullptr, *reflectance = nullptr, *mfp = nullptr, *name = nullptr;
  const ParsedParam *interior = nullptr, *scale_param = nullptr;
  const ParsedParam* entry = nullptr;
  const ParsedParam* normal_axis = nullptr;
  bool profile_given = false;
  std::optional<float> roughness, uroughness, vroughness;
};

// Each parameter of the subsurface table (kParameters) read into s, or kept in g for later;
// textures by texture_index_of; ignored ones warned.
GivenParameters read_each_parameter(const ParamList& pl, Diagnostics& diag, const TextureIndexOf& texture_index_of,
                                    SubsurfaceParams& s) {
  GivenParameters g;
  for (const ParsedParam& item : pl.items()) {
    const ParsedParam& p = item;
    const std::string& n = p.param.name;
    bool known = false;
    for (const SubsurfaceParameter& row : kParameters) known = known || n == row.name;
    if (!known) continue;  // reported by the parser as unused
    p.used = true;
    if (n == "sigma_a")
      g.sigma_a = &p;
    else if (n == "sigma_s")
      g.sigma_s = &p;
    else if (n == "reflectance")
      g.reflectance = &p;
    else if (n == "mfp")
      g.mfp = &p;
    else if (n == "name")
      g.name = &p;
    else if (n == "interior") {
      if (p.type != "string" || p.param.strings.size() != 1 || p.param.strings[0].empty())
        throw SceneError(p.value_loc, "\"interior\" needs one string: the name of a MakeNamedMedium");
      g.interior = &p;
      s.interior = p.param.strings[0];
      s.interior_loc = p.value_loc;
    } else if (n == "scale") {
      g.scale_param = &p;
      if (p.type == "texture")
        s.scale_texture = texture_index_of(p, true);
      else
        g.scale = read_float(p);
    } else if (n == "eta")
      s.eta = read_float(p);
    else if (n == "g")
      s.g = read_float(p);
    else if (n == "profile") {
      s.profile = lookup(kProfiles, p, "profile");
      g.profile_given = true;
    } else if (n == "method")
      s.method = lookup(kMethods, p, "subsurface method");
    else if (n == "boundary")
      s.boundary = lookup(kBoundaries, p, "boundary"), s.boundary_given = true;
    else if (n == "entry") {
      if (p.type != "string" || p.param.strings.size() != 1 ||
          (p.param.strings[0] != "refracted" && p.param.strings[0] != "lambertian"))
        throw SceneError(p.value_loc, "\"entry\" must be \"refracted\" or \"lambertian\"");
      s.lambertian_entry = p.param.strings[0] == "lambertian";
      g.entry = &p;
    } else if (n == "walksampling")
      s.walk_sampling = lookup(kWalkSamplings, p, "walk sampling"), s.walk_sampling_given = true;
    else if (n == "epsilon")
      s.epsilon = read_float(p);
    else if (n == "albedoinversion") {
      if (p.param.strings.size() != 1 || (p.param.strings[0] != "exact" && p.param.strings[0] != "fit"))
        throw SceneError(p.value_loc, "\"albedoinversion\" must be \"exact\" or \"fit\"");
      s.albedo_inversion_fit = p.param.strings[0] == "fit";
    } else if (n == "pointdensity")
      s.point_density = read_float(p);
    else if (n == "illuminationerror") {
      const float e = read_float(p);
      if (!(e >= 0 && e <= 1)) throw SceneError(p.value_loc, "\"illuminationerror\" must be in [0, 1] (0: off)");
      s.illumination_error = e;
    } else if (n == "backwardguiding") {
      s.backward_guiding = read_bool(p);
      s.backward_guiding_given = true;
    } else if (n == "guidedshare") {
      const float v = read_float(p);
      if (!(v >= 0 && v <= 1)) throw SceneError(p.value_loc, "\"guidedshare\" must be in [0, 1]");
      s.guided_share = v;
      s.guided_share_given = true;
    } else if (n == "channelpreference") {
      const float v = read_float(p);
      if (!(v >= 0 && v <= 8)) throw SceneError(p.value_loc, "\"channelpreference\" must be in [0, 8]");
      s.channel_preference = v;
      s.channel_preference_given = true;
    } else if (n == "normalaxis") {
      const float v = read_float(p);
      if (!(v > 0 && v < 1))
        throw SceneError(p.value_loc,
                         "\"normalaxis\" must be in (0, 1) (the probes along the tangent and the "
                         "bitangent share the rest; none along one of them would miss its hits)");
      s.normal_axis = v;
      s.normal_axis_given = true;
      g.normal_axis = &p;
    } else if (n == "channelperwalk") {
      s.channel_per_walk = read_bool(p);
      s.channel_per_walk_given = true;
    } else if (n == "localdisk")
      s.local_disk = read_bool(p);
    else if (n == "irradiancesamples") {
      const auto& v = p.param.numbers;
      if (v.size() != 1 || !(v[0] >= 1) || v[0] != std::floor(v[0]) || v[0] > (1 << 20))
        throw SceneError(p.value_loc, "\"irradiancesamples\" must be one integer in [1, 1048576]");
      s.irradiance_samples = int(v[0]);
    } else if (n == "maxpoints") {
      const auto& v = p.param.numbers;
      if (p.type != "integer" || v.size() != 1 || !(v[0] >= 16) || v[0] > 1e8)
        throw SceneError(p.value_loc, "\"maxpoints\" must be one integer in [16, 100000000]");
      s.max_points = int(v[0]);
    } else if (n == "sssgroup") {
      if (p.type != "string" || p.param.strings.size() != 1)
        throw SceneError(p.value_loc, "\"sssgroup\" needs exactly one string");
      s.group = p.param.strings[0];
    } else if (n == "roughness" || n == "uroughness" || n == "vroughness") {
      if (p.type == "texture") {
        if (n == "roughness") {
          s.roughness_texture = texture_index_of(p, true);
          continue;
        }
        diag.warn(p.param.loc, fmt::format("subsurface: textured \"{}\" is not supported (a textured \"roughness\", "
                                           "the same on both axes, is); 0 used",
                                           n));
        continue;
      }
      const float r = read_float(p);
      if (r < 0) throw SceneError(p.value_loc, fmt::format("\"{}\" must be >= 0", n));
      if (n == "roughness")
        g.roughness = r;
      else
        (n == "uroughness" ? g.uroughness : g.vroughness) = r;
    } else if (n == "remaproughness")
      s.remap_roughness = read_bool(p);
    else {  // normalmap, displacement
      diag.warn(p.param.loc, fmt::format("subsurface: \"{}\" ignored", n));
    }
  }
  return g;
}

// The rules across parameters: roughness per axis, ranges, what a method ignores, defaults
// that follow the method.
void check_across_parameters(const GivenParameters& g, const SourceLoc& loc, Diagnostics& diag, SubsurfaceParams& s) {
  // pbrt-v4: "roughness" sets both axes, "uroughness" / "vroughness" override one each.
  s.uroughness = g.uroughness.value_or(g.roughness.value_or(0));
  s.vroughness = g.vroughness.value_or(g.roughness.value_or(0));
  if (s.roughness_texture >= 0 && (g.uroughness || g.vroughness)) {
    diag.warn(loc,
              "subsurface: \"uroughness\" / \"vroughness\" ignored beside a textured \"roughness\" "
              "(a textured boundary is isotropic)");
    s.uroughness = s.vroughness = 0;
  }
  if (g.scale <= 0) throw SceneError(loc, "subsurface: \"scale\" must be positive");
  s.scale = g.scale;
  if (s.eta < 1.0f || s.eta > 3.0f)
    throw SceneError(loc, fmt::format("subsurface: \"eta\" {} is outside [1, 3]", s.eta));
  if (s.g <= -1 || s.g >= 1) throw SceneError(loc, "subsurface: \"g\" must be in (-1, 1)");
  if (!(s.epsilon > 0)) throw SceneError(loc, "subsurface: \"epsilon\" must be positive");
  if (!(s.point_density > 0)) throw SceneError(loc, "subsurface: \"pointdensity\" must be positive");
  if (s.method == SubsurfaceParams::Method::PointCloud && s.roughness_texture >= 0) {
    // Its points carry no surface coordinates at which to evaluate the texture.
    diag.warn(loc,
              "subsurface: a textured \"roughness\" is not supported by the \"pointcloud\" method "
              "(its points carry no texture coordinates); 0 used");
    s.roughness_texture = -1;
  }
  if (s.lambertian_entry && s.method == SubsurfaceParams::Method::RandomWalk &&
      s.boundary != SubsurfaceParams::Boundary::Diffuse)
    throw SceneError(g.entry->value_loc,
                     "\"entry\" \"lambertian\" needs \"boundary\" \"diffuse\" (a diffuse "
                     "transmission in and out; the other boundaries refract)");
  if (s.lambertian_entry && s.method != SubsurfaceParams::Method::RandomWalk) {
    diag.warn(
        g.entry->param.loc,
        fmt::format("subsurface: \"entry\" applies to the random walk only; ignored by \"{}\"", to_string(s.method)));
    s.lambertian_entry = false;
  }
  if (g.normal_axis && s.method != SubsurfaceParams::Method::Disk) {
    diag.warn(
        g.normal_axis->param.loc,
        fmt::format("subsurface: \"normalaxis\" applies to the disk only; ignored by \"{}\"", to_string(s.method)));
    s.normal_axis_given = false;
  }
  // The point cloud's profile is the dipole by default, as in Jensen & Buehler 2002.
  if (s.method == SubsurfaceParams::Method::PointCloud && !g.profile_given)
    s.profile = SubsurfaceParams::Profile::Dipole;
}

// The medium, given one way: a named measured medium, reflectance + mfp, or the coefficients
// (pbrt-v4's whole milk when none is given); scale applied as pbrt-v4 does.
void read_medium(const GivenParameters& g, const SourceLoc& loc, Diagnostics& diag,
                 const TextureIndexOf& texture_index_of, SubsurfaceParams& s) {
  // A spectrum parameter: its value, or its texture (the value is then a stand-in); given as a
  // spectrum, its samples too (`data`).
  auto spectrum = [&](const ParsedParam& p, int& texture, RGB stand_in,
                      std::shared_ptr<const std::vector<float>>& data) {
    if (p.type != "texture") {
      if (auto samples = spectrum_param_samples(p, SpectrumType::Unbounded))
        data = std::make_shared<const std::vector<float>>(std::move(*samples));
      return read_rgb(p, diag);
    }
    texture = texture_index_of(p, false);
    return stand_in;
  };
  int ways = (g.name != nullptr) + (g.sigma_a || g.sigma_s) + (g.reflectance || g.mfp) + (g.interior != nullptr);
  if (ways > 1)
    throw SceneError(loc,
                     "subsurface: give either \"name\", or \"sigma_a\" + \"sigma_s\", or \"reflectance\" + \"mfp\", or "
                     "\"interior\", not several");
  // An interior medium: its own "scale" and "g" apply (the parser copies a homogeneous one's
  // coefficients in; a grid medium's stay with it). Until then, and for a grid medium, the
  // coefficients below are pbrt-v4's milk: a stand-in for what needs one medium per material.
  if (g.interior && g.scale_param)
    throw SceneError(g.scale_param->param.loc,
                     "subsurface: \"scale\" does not apply beside \"interior\" (give the medium's own \"scale\" in "
                     "its MakeNamedMedium)");
  if (g.name) {
    if (g.name->param.strings.size() != 1) throw SceneError(g.name->value_loc, "\"name\" needs one string");
    auto preset = find_medium_preset(g.name->param.strings[0]);
    if (!preset)
      throw SceneError(g.name->value_loc,
                       fmt::format("unknown subsurface preset \"{}\"{} (valid: {})", g.name->param.strings[0],
                                   medium_preset_suggestion(g.name->param.strings[0]), medium_preset_names()));
    // The measured values are per mm, used per scene unit as pbrt does; scale converts.
    s.sigma_a = preset->sigma_a * g.scale;
    s.sigma_s = preset->sigma_s_prime * g.scale;
    s.g = 0;
  } else if (g.reflectance || g.mfp) {
    if (!g.reflectance || !g.mfp) throw SceneError(loc, "subsurface: \"reflectance\" needs \"mfp\" and vice versa");
    RGB a = spectrum(*g.reflectance, s.reflectance_texture, RGB(0.5f), s.reflectance_spectrum);
    RGB l = spectrum(*g.mfp, s.mfp_texture, RGB(1.0f), s.mfp_spectrum);
    for (int c = 0; c < 3; ++c) {
      if (a[c] > 1) throw SceneError(g.reflectance->value_loc, "subsurface: \"reflectance\" must be in [0, 1]");
      if (l[c] <= 0) throw SceneError(g.mfp->value_loc, "subsurface: \"mfp\" must be positive");
    }
    s.reflectance = a;
    // pbrt-v4 multiplies mfp by scale too (SubsurfaceMaterial::GetBSSRDF: mfree = scale * mfp).
    s.mfp = l * g.scale;
  } else {
    // pbrt-v4's defaults when nothing is given: whole milk, per scene unit.
    RGB sa(0.0011f, 0.0024f, 0.014f), ss(2.55f, 3.21f, 3.77f);
    if (g.sigma_a) sa = spectrum(*g.sigma_a, s.sigma_a_texture, sa, s.sigma_a_spectrum);
    if (g.sigma_s) ss = spectrum(*g.sigma_s, s.sigma_s_texture, ss, s.sigma_s_spectrum);
    s.sigma_a = sa * g.scale;
    s.sigma_s = ss * g.scale;
    for (int c = 0; c < 3; ++c)
      if ((*s.sigma_a)[c] + (*s.sigma_s)[c] <= 0)
        throw SceneError(loc, "subsurface: g.sigma_a + g.sigma_s must be positive in every channel");
  }
}

}  // namespace

SubsurfaceParams::Boundary default_walk_boundary(const SubsurfaceParams& s) {
  return s.coefficient_given() ? SubsurfaceParams::Boundary::Dielectric : SubsurfaceParams::Boundary::Diffuse;
}

SubsurfaceParams read_subsurface_params(const ParamList& pl, const SourceLoc& loc, Diagnostics& diag,
                                        const TextureIndexOf& texture_index_of) {
  SubsurfaceParams s;
  s.loc = loc;
  const GivenParameters g = read_each_parameter(pl, diag, texture_index_of, s);
  check_across_parameters(g, loc, diag, s);
  read_medium(g, loc, diag, texture_index_of, s);
  // "entry" "lambertian" is the diffuse boundary's: it keeps that boundary.
  if (!s.boundary_given && !s.lambertian_entry) s.boundary = default_walk_boundary(s);
  return s;
}

}  // namespace dermis
