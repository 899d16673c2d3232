// Material, MakeNamedMaterial, NamedMaterial, Texture, LightSource, AreaLightSource,
// MakeNamedMedium, MediumInterface.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "dermis/scene/medium_presets.h"
#include "dermis/scene/pbrt_v4_types.h"
#include "dermis/scene/scene_parser.h"
#include "dermis/scene/spectra.h"
#include "dermis/scene/subsurface_params.h"

namespace dermis {

namespace {

std::string names_of(const std::map<std::string, int>& m) {
  std::string s;
  for (const auto& [name, index] : m) s += (s.empty() ? "" : ", ") + name;
  return s.empty() ? "none" : s;
}

RGB rgb_param(const ParamList& pl, const std::string& name, RGB def, Diagnostics& diag,
              SpectrumType type = SpectrumType::Unbounded) {
  const ParsedParam* p = pl.find(name);
  return p ? spectrum_param_rgb(*p, diag, type) : def;
}

// A light's emitted radiance or intensity: negative light would give negative pixels, and
// a value beyond float range infinite ones; both are errors at the value.
RGB emission_param(const ParamList& pl, const std::string& name, Diagnostics& diag) {
  const RGB e = rgb_param(pl, name, RGB(1), diag, SpectrumType::Illuminant);
  for (int c = 0; c < 3; ++c)
    if (!(e[c] >= 0) || !std::isfinite(e[c]))
      throw SceneError(pl.find(name)->value_loc,
                       fmt::format("\"{}\" must be finite and >= 0 in every channel (RGB {} {} {}): light cannot be "
                                   "negative, and values beyond {:g} overflow",
                                   name, e[0], e[1], e[2], double(std::numeric_limits<float>::max())));
  return e;
}

// A light's "scale", which multiplies `emission` (its "L" or "I", given as `name`): the
// product, not only each factor, must stay within float range (1e20 x 1e20 is infinite).
float light_scale_param(const ParamList& pl, RGB emission, const char* name) {
  const float scale = pl.get_float("scale", 1);
  if (!(scale >= 0) || !std::isfinite(scale))
    throw SceneError(pl.find("scale")->value_loc,
                     fmt::format("a light's \"scale\" must be finite and >= 0, got {}", scale));
  const double product = double(emission.max()) * double(scale);
  if (product > double(std::numeric_limits<float>::max()))
    throw SceneError(
        pl.find("scale")->value_loc,
        fmt::format("a light's \"scale\" {:g} times its \"{}\" {:g} is {:g}, beyond the range of 32-bit "
                    "floats ({:g}): the light would be infinite",
                    double(scale), name, double(emission.max()), product, double(std::numeric_limits<float>::max())));
  return scale;
}

// `file` (resolved) must be a regular file; else an error at the parameter's value.
std::string existing_file(const ParamList& pl, const std::string& name, const std::string& file,
                          const std::string& what) {
  const ParsedParam* p = pl.find(name);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw SceneError(p->value_loc, fmt::format("{}: could not read '{}': no such file", what, file));
  return file;
}

// pbrt-v4's 2D mappings of a texture (TextureMapping2D::Create): "uv" (uscale, vscale,
// udelta, vdelta), "spherical", "cylindrical" (no parameters), "planar" (v1, v2, udelta, vdelta).
void read_mapping_2d(const ParamList& pl, TextureDesc& t) {
  t.mapping = pl.get_string("mapping", "uv");
  if (t.mapping == "uv") {
    t.uscale = pl.get_float("uscale", 1);
    t.vscale = pl.get_float("vscale", 1);
    t.udelta = pl.get_float("udelta", 0);
    t.vdelta = pl.get_float("vdelta", 0);
  } else if (t.mapping == "planar") {
    t.v1 = pl.get_vec3("v1", {"vector3"}).value_or(t.v1);
    t.v2 = pl.get_vec3("v2", {"vector3"}).value_or(t.v2);
    t.udelta = pl.get_float("udelta", 0);
    t.vdelta = pl.get_float("vdelta", 0);
  } else if (t.mapping != "spherical" && t.mapping != "cylindrical") {
    throw SceneError(pl.find("mapping")->value_loc,
                     fmt::format("texture mapping must be \"uv\", \"spherical\", \"cylindrical\" or \"planar\", got "
                                 "\"{}\"",
                                 t.mapping));
  }
}

}  // namespace

// ---------------------------------------------------------------- materials

RGBTexture SceneParser::spectrum_or_texture(const ParamList& pl, const std::string& name, RGB def) {
  RGBTexture t;
  t.value = def;
  const ParsedParam* p = pl.find(name);
  if (!p) return t;
  if (p->type == "texture") {
    std::string tex = *pl.get_texture(name);
    auto it = spectrum_textures_.find(tex);
    if (it == spectrum_textures_.end())
      throw SceneError(p->value_loc,
                       fmt::format("unknown spectrum texture \"{}\" for \"{}\"{} (defined: {})", tex, name,
                                   float_textures_.count(tex) ? " (a float texture has that name)" : "",
                                   names_of(spectrum_textures_)));
    t.texture = it->second;
    return t;
  }
  t.value = spectrum_param_rgb(*p, s_.diagnostics);
  // Every parameter read here is a reflectance (reflectance, transmittance, albedo): a
  // spectrum given as data must lie in [0, 1] where it is seen, not only its colour.
  if (auto samples = spectrum_param_samples(*p, SpectrumType::Unbounded)) {
    std::size_t worst = 0;  // the farthest outside [0, 1]
    auto outside = [](float v) { return v < 0 ? -v : v > 1 ? v - 1 : std::isnan(v) ? INFINITY : 0.0f; };
    for (std::size_t i = 1; i < samples->size(); ++i)
      if (outside((*samples)[i]) > outside((*samples)[worst])) worst = i;
    if (outside((*samples)[worst]) > 0)
      throw SceneError(p->value_loc,
                       fmt::format("\"{}\" is a reflectance and must lie in [0, 1] at every wavelength of 360-830 nm; "
                                   "this spectrum is {:g} at {} nm",
                                   name, (*samples)[worst], 360 + worst));
    s_.spectra.push_back(std::move(*samples));  // spectral rendering reads it as data
    t.data = int(s_.spectra.size()) - 1;
  }
  return t;
}

float SceneParser::float_or_texture(const ParamList& pl, const std::string& name, float def, int& texture) {
  const ParsedParam* p = pl.find(name);
  if (!p || p->type != "texture") return pl.get_float(name, def);
  const std::string tex = *pl.get_texture(name);
  auto it = float_textures_.find(tex);
  if (it == float_textures_.end())
    throw SceneError(p->value_loc,
                     fmt::format("unknown float texture \"{}\" for \"{}\"{} (defined: {})", tex, name,
                                 spectrum_textures_.count(tex) ? " (a spectrum texture has that name)" : "",
                                 names_of(float_textures_)));
  texture = it->second;
  return def;
}

// dielectric, conductor: pbrt-v4's microfacet roughness. "roughness" sets both axes,
// "uroughness" / "vroughness" override one each; each may be a float texture (evaluated per
// hit, negative values taken as 0). The renderer maps roughness to alpha. The coated
// materials' interface and conductor read the same names with a prefix ("interface.",
// "conductor.").
void SceneParser::read_microfacet_roughness(const ParamList& pl, const std::string& prefix, MaterialDesc& m, float& u,
                                            float& v, std::array<int, 2>& textures) {
  auto read = [&](const std::string& name, float fallback, int fallback_texture, int& texture) {
    texture = pl.has(name) ? -1 : fallback_texture;  // a value given here overrides "roughness"'s texture
    const float r = float_or_texture(pl, name, fallback, texture);
    if (!(r >= 0)) throw SceneError(pl.find(name)->value_loc, fmt::format("{} must be >= 0, got {}", name, r));
    return r;
  };
  int both = -1;
  const float r = read(prefix + "roughness", 0, -1, both);
  u = read(prefix + "uroughness", r, both, textures[0]);
  v = read(prefix + "vroughness", r, both, textures[1]);
  m.remap_roughness = pl.get_bool("remaproughness", true);
  m.roughness = std::max({m.roughness, u, v, textures[0] >= 0 || textures[1] >= 0 ? 1.0f : 0.0f});
}

int SceneParser::spectrum_data(const ParamList& pl, const std::string& name, SpectrumType type) {
  const ParsedParam* p = pl.find(name);
  if (!p) return -1;
  std::optional<std::vector<float>> samples = spectrum_param_samples(*p, type);
  if (!samples) return -1;
  s_.spectra.push_back(std::move(*samples));
  return int(s_.spectra.size()) - 1;
}

int SceneParser::named_spectrum_data(const std::string& name) {
  s_.spectra.push_back(*named_spectrum_samples(name, SpectrumType::Unbounded));
  return int(s_.spectra.size()) - 1;
}

// pbrt-v4's coating parameters, common to coateddiffuse and coatedconductor; thickness and g
// may be float textures, albedo a spectrum texture (evaluated per hit, clamped to their
// ranges as pbrt-v4 does).
void SceneParser::read_coating(const ParamList& pl, MaterialDesc& m) {
  m.thickness = float_or_texture(pl, "thickness", 0.01f, m.thickness_texture);
  if (!(m.thickness >= 0) || !std::isfinite(m.thickness))
    throw SceneError(pl.find("thickness")->value_loc,
                     fmt::format("thickness must be finite and >= 0, got {}", m.thickness));
  m.g = float_or_texture(pl, "g", 0, m.g_texture);
  if (!(m.g > -1 && m.g < 1))
    throw SceneError(pl.find("g")->value_loc, fmt::format("g must lie in (-1, 1), got {}", m.g));
  const RGBTexture albedo = spectrum_or_texture(pl, "albedo", RGB(0));
  m.albedo = albedo.value;
  m.albedo_texture = albedo.texture;
  for (int c = 0; c < 3; ++c)
    if (!(m.albedo[c] >= 0 && m.albedo[c] <= 1))
      throw SceneError(pl.find("albedo")->value_loc, fmt::format("albedo must lie in [0, 1], got {}", m.albedo[c]));
  m.max_depth = pl.get_int("maxdepth", 10);
  if (m.max_depth < 1 || m.max_depth > 100000)
    throw SceneError(pl.find("maxdepth")->value_loc,
                     fmt::format("maxdepth must lie in [1, 100000], got {}", m.max_depth));
  m.n_samples = pl.get_int("nsamples", 1);
  if (m.n_samples < 1 || m.n_samples > 1024)
    throw SceneError(pl.find("nsamples")->value_loc,
                     fmt::format("nsamples must lie in [1, 1024], got {}", m.n_samples));
}

// A mix's two materials: named materials made before it, neither an interface nor a
// subsurface material.
void SceneParser::read_mix_materials(const ParamList& pl, const SourceLoc& loc, MaterialDesc& m) {
  const ParsedParam* p = pl.find("materials");
  if (!p) throw SceneError(loc, "mix material needs \"string materials\" [ \"first\" \"second\" ]");
  pl.expect_type(*p, {"string"});
  if (p->param.strings.size() != 2)
    throw SceneError(p->value_loc,
                     fmt::format("\"materials\" of a mix must name two materials, got {}", p->param.strings.size()));
  for (int i = 0; i < 2; ++i) {
    const std::string& name = p->param.strings[std::size_t(i)];
    auto it = named_materials_.find(name);
    if (it == named_materials_.end())
      throw SceneError(p->value_at(std::size_t(i)),
                       fmt::format("mix: unknown named material \"{}\" (a mix names materials made before it by "
                                   "MakeNamedMaterial; defined: {})",
                                   name, names_of(named_materials_)));
    const MaterialDesc& named = s_.materials[std::size_t(it->second)];
    if (named.type == MaterialDesc::Type::Interface || named.type == MaterialDesc::Type::Subsurface)
      throw SceneError(p->value_at(std::size_t(i)),
                       fmt::format("mix: material \"{}\" is {}; a mix of {} materials is not supported", name,
                                   named.type_name, named.type_name));
    m.mix_materials[std::size_t(i)] = it->second;
  }
}

MaterialDesc SceneParser::build_material(const std::string& type, const ParamList& pl, const SourceLoc& loc) {
  MaterialDesc m;
  m.loc = loc;
  if (type == "diffuse") {
    m.type = MaterialDesc::Type::Diffuse;
    m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(0.5f));
  } else if (type == "dielectric" || type == "thindielectric") {
    if (type == "thindielectric") s_.diagnostics.warn(loc, "thindielectric is rendered as dielectric");
    m.type = MaterialDesc::Type::Dielectric;
    if (const ParsedParam* p = pl.find("eta")) m.eta = ior_param(*p, s_.diagnostics);
    m.eta_data = spectrum_data(pl, "eta", SpectrumType::Unbounded);
    if (m.eta_data >= 0) {  // dispersion where it is an index at every wavelength (a file's is 0 past its ends)
      const std::vector<float>& eta = s_.spectra[std::size_t(m.eta_data)];
      if (*std::min_element(eta.begin(), eta.end()) <= 0) s_.spectra.pop_back(), m.eta_data = -1;
    }
    read_microfacet_roughness(pl, "", m, m.uroughness, m.vroughness, m.roughness_texture);
  } else if (type == "conductor") {
    m.type = MaterialDesc::Type::Conductor;
    if (pl.has("reflectance")) {
      m.has_reflectance = true;
      m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(1.0f));
      if (pl.has("eta") || pl.has("k"))
        s_.diagnostics.warn(loc, "conductor: \"reflectance\" given, so \"eta\" and \"k\" are ignored");
      if (const ParsedParam* p = pl.find("eta")) p->used = true;
      if (const ParsedParam* p = pl.find("k")) p->used = true;
    } else {
      m.conductor_eta = *named_spectrum_rgb("metal-Cu-eta");  // pbrt-v4's defaults
      m.conductor_k = *named_spectrum_rgb("metal-Cu-k");
      m.conductor_eta = rgb_param(pl, "eta", m.conductor_eta, s_.diagnostics);
      m.conductor_k = rgb_param(pl, "k", m.conductor_k, s_.diagnostics);
      m.conductor_eta_data =
          pl.has("eta") ? spectrum_data(pl, "eta", SpectrumType::Unbounded) : named_spectrum_data("metal-Cu-eta");
      m.conductor_k_data =
          pl.has("k") ? spectrum_data(pl, "k", SpectrumType::Unbounded) : named_spectrum_data("metal-Cu-k");
    }
    read_microfacet_roughness(pl, "", m, m.uroughness, m.vroughness, m.roughness_texture);
  } else if (type == "interface" || type == "" || type == "none") {
    m.type = MaterialDesc::Type::Interface;
  } else if (type == "coateddiffuse") {
    m.type = MaterialDesc::Type::CoatedDiffuse;
    m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(0.5f));
    if (const ParsedParam* p = pl.find("eta")) m.eta = ior_param(*p, s_.diagnostics);
    read_microfacet_roughness(pl, "", m, m.uroughness, m.vroughness, m.roughness_texture);
    read_coating(pl, m);
  } else if (type == "coatedconductor") {
    m.type = MaterialDesc::Type::CoatedConductor;
    if (const ParsedParam* p = pl.find("interface.eta")) m.eta = ior_param(*p, s_.diagnostics);
    read_microfacet_roughness(pl, "interface.", m, m.uroughness, m.vroughness, m.roughness_texture);
    read_microfacet_roughness(pl, "conductor.", m, m.conductor_uroughness, m.conductor_vroughness,
                              m.conductor_roughness_texture);
    if (pl.has("reflectance")) {
      m.has_reflectance = true;
      m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(1));
      for (const char* ignored : {"conductor.eta", "conductor.k"})
        if (const ParsedParam* q = pl.find(ignored)) {
          q->used = true;
          s_.diagnostics.warn(q->param.loc,
                              fmt::format("coatedconductor: \"reflectance\" given, so \"{}\" is ignored", ignored));
        }
    } else {
      m.conductor_eta = rgb_param(pl, "conductor.eta", *named_spectrum_rgb("metal-Cu-eta"), s_.diagnostics);
      m.conductor_k = rgb_param(pl, "conductor.k", *named_spectrum_rgb("metal-Cu-k"), s_.diagnostics);
      m.conductor_eta_data = pl.has("conductor.eta") ? spectrum_data(pl, "conductor.eta", SpectrumType::Unbounded)
                                                     : named_spectrum_data("metal-Cu-eta");
      m.conductor_k_data = pl.has("conductor.k") ? spectrum_data(pl, "conductor.k", SpectrumType::Unbounded)
                                                 : named_spectrum_data("metal-Cu-k");
    }
    read_coating(pl, m);
  } else if (type == "diffusetransmission") {
    m.type = MaterialDesc::Type::DiffuseTransmission;
    m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(0.25f));
    m.transmittance = spectrum_or_texture(pl, "transmittance", RGB(0.25f));
    // pbrt-v4 reads "scale" as a float only; a texture is warned and 1 used.
    if (const ParsedParam* p = pl.find("scale"); p && p->type == "texture") {
      p->used = true;
      s_.diagnostics.warn(p->param.loc, "textured \"scale\" is not supported (pbrt-v4 reads a float); 1 is used");
    } else {
      m.scale = pl.get_float("scale", 1);
    }
    if (!(m.scale >= 0) || !std::isfinite(m.scale))
      throw SceneError(pl.find("scale")->value_loc, fmt::format("scale must be finite and >= 0, got {}", m.scale));
  } else if (type == "mix") {
    m.type = MaterialDesc::Type::Mix;
    read_mix_materials(pl, loc, m);
    m.amount = float_or_texture(pl, "amount", 0.5f, m.amount_texture);
  } else if (type == "subsurface") {
    m.type = MaterialDesc::Type::Subsurface;
    m.subsurface = read_subsurface_params(pl, loc, s_.diagnostics, [&](const ParsedParam& p, bool is_float) {
      int texture = -1;
      if (is_float)
        float_or_texture(pl, p.param.name, 0, texture);
      else
        texture = spectrum_or_texture(pl, p.param.name, RGB(1.0f)).texture;
      return texture;
    });
    if (!m.subsurface.interior.empty())
      m.subsurface.interior_medium = medium_reference(m.subsurface.interior, m.subsurface.interior_loc);
    m.eta = m.subsurface.eta;
  } else if (type == "hair") {
    // pbrt-v4's hair BSDF (Chiang et al. 2016) is not implemented: one warning, and a
    // diffuse surface of the "reflectance" given (pbrt-v4's alternative to sigma_a and
    // the melanin concentrations), else 0.5. Its other parameters are known, so they
    // are not warned one by one.
    s_.diagnostics.warn(loc,
                        "material \"hair\" is not supported: rendered as diffuse (its \"reflectance\" if "
                        "given, else 0.5)");
    m.type = MaterialDesc::Type::Diffuse;
    m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(0.5f));
    for (const char* known : {"sigma_a", "eumelanin", "pheomelanin", "eta", "beta_m", "beta_n", "alpha"})
      if (const ParsedParam* p = pl.find(known)) p->used = true;
  } else {  // pbrt-v4's "measured" (require_known_type refused unknown names)
    s_.diagnostics.warn(loc, fmt::format("unsupported material \"{}\"; using diffuse", type));
    m.type = MaterialDesc::Type::Diffuse;
    m.reflectance = spectrum_or_texture(pl, "reflectance", RGB(0.5f));  // its other parameters are warned unused
  }
  if (m.eta <= 0) throw SceneError(pl.find("eta") ? pl.find("eta")->value_loc : loc, "eta must be positive");
  pl.warn_unused(s_.diagnostics, fmt::format("material \"{}\"", type));
  m.type_name = type;
  m.params = std::make_shared<const ParamList>(pl);
  return m;
}

MaterialDesc SceneParser::rebuild_material(const MaterialDesc& old, const std::string& params_text,
                                           const std::string& source_name) {
  // Texture names as the end of the scene left them (a later definition replaces an earlier one).
  spectrum_textures_.clear();
  float_textures_.clear();
  for (std::size_t i = 0; i < s_.textures.size(); ++i)
    (s_.textures[i].is_float ? float_textures_ : spectrum_textures_)[s_.textures[i].name] = int(i);
  TokenStream changes_ts(open_text(params_text, source_name));
  changes_ts.set_base_dir(s_.base_directory);
  ParamList changes = ParamList::parse(changes_ts);
  if (!changes_ts.at_end()) {
    const Token& t = *changes_ts.peek();
    throw SceneError(changes_ts.loc(t), fmt::format("expected a parameter (\"type name\" value), found {} '{}'",
                                                    token_kind_name(t.kind), t.text));
  }
  // The parameters as written (with their places in the scene), those named again replaced.
  ParamList merged = old.params ? *old.params : ParamList();
  merged.replace(changes);
  // MakeNamedMaterial's "type" is one of its parameters; "string type" changes any material's.
  const std::string type = merged.has("type") ? merged.get_string("type", old.type_name) : old.type_name;
  MaterialDesc m = build_material(type, merged, old.loc);
  m.name = old.name;
  return m;
}

void SceneParser::material(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::Material, type, type_loc);
  ParamList pl = ParamList::parse(ts);
  s_.materials.push_back(build_material(type, pl, ts.loc(d)));
  gs_.material = int(s_.materials.size()) - 1;
}

void SceneParser::make_named_material(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc name_loc;
  std::string name = string_arg(ts, d, &name_loc);
  ParamList pl = ParamList::parse(ts);
  if (named_materials_.count(name))
    throw SceneError(name_loc, fmt::format("named material \"{}\" is defined twice (first at {})", name,
                                           s_.materials[named_materials_[name]].loc.str()));
  if (!pl.has("type")) throw SceneError(loc, fmt::format("MakeNamedMaterial \"{}\" needs \"string type\"", name));
  std::string type = pl.get_string("type", "");
  require_known_type(TypedDirective::Material, type, pl.find("type")->value_loc);
  MaterialDesc m = build_material(type, pl, loc);
  m.name = name;
  named_materials_[name] = int(s_.materials.size());
  s_.materials.push_back(std::move(m));
}

void SceneParser::named_material(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  SourceLoc name_loc;
  std::string name = string_arg(ts, d, &name_loc);
  auto it = named_materials_.find(name);
  if (it == named_materials_.end())
    throw SceneError(name_loc,
                     fmt::format("unknown named material \"{}\" (defined: {})", name, names_of(named_materials_)));
  gs_.material = it->second;
}

// ---------------------------------------------------------------- textures

// An imagemap texture's file and how it is read: pbrt-v4's parameters, its 2D mapping.
void SceneParser::read_image_map(const ParamList& pl, const SourceLoc& loc, TextureDesc& t) {
  t.type = TextureDesc::Type::ImageMap;
  read_mapping_2d(pl, t);
  if (!pl.has("filename")) throw SceneError(loc, "imagemap texture needs \"string filename\"");
  t.filename =
      existing_file(pl, "filename", scene_path(pl.get_string("filename", ""), pl.find("filename")->value_loc, "image"),
                    "imagemap texture");
  t.scale = pl.get_float("scale", 1);
  t.invert = pl.get_bool("invert", false);
  t.encoding = pl.get_string("encoding", t.encoding);
  if (t.encoding != "sRGB" && t.encoding != "linear" && t.encoding.rfind("gamma ", 0) != 0)
    throw SceneError(pl.find("encoding")->value_loc,
                     fmt::format("encoding must be \"sRGB\", \"linear\" or \"gamma <value>\", got \"{}\"", t.encoding));
  t.wrap = pl.get_string("wrap", t.wrap);
  if (t.wrap != "repeat" && t.wrap != "black" && t.wrap != "clamp" && t.wrap != "octahedralsphere")
    throw SceneError(pl.find("wrap")->value_loc,
                     fmt::format("wrap must be \"repeat\", \"black\" or \"clamp\", got \"{}\"", t.wrap));
  for (const char* ignored : {"filter", "maxanisotropy"})
    if (const ParsedParam* f = pl.find(ignored)) {
      f->used = true;
      s_.diagnostics.warn(f->param.loc, fmt::format("imagemap \"{}\" ignored (Dermis filters bilinearly)", ignored));
    }
}

void SceneParser::texture(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string name = string_arg(ts, d);
  std::string value_type = string_arg(ts, d, &type_loc);
  SourceLoc cls_loc;
  std::string cls = string_arg(ts, d, &cls_loc);
  require_known_type(TypedDirective::Texture, cls, cls_loc);
  ParamList pl = ParamList::parse(ts);
  if (value_type == "color") {
    s_.diagnostics.warn(type_loc, "texture type \"color\" (pbrt-v3) read as \"spectrum\"");
    value_type = "spectrum";
  }
  if (value_type != "spectrum" && value_type != "float")
    throw SceneError(type_loc, fmt::format("texture type must be \"spectrum\" or \"float\", got \"{}\"", value_type));
  TextureDesc t;
  t.name = name;
  t.loc = loc;
  t.is_float = value_type == "float";
  auto value_param = [&](const std::string& pname, RGB def) {
    const ParsedParam* p = pl.find(pname);
    if (!p) return def;
    if (p->type == "float") return RGB(pl.get_float(pname, 0));
    return spectrum_param_rgb(*p, s_.diagnostics);
  };
  // A parameter that is a value or names a texture of the same kind (its index in `index`).
  auto value_or_texture = [&](const std::string& pname, RGB def, int& index) {
    const ParsedParam* p = pl.find(pname);
    if (!p || p->type != "texture") return value_param(pname, def);
    const std::string other = *pl.get_texture(pname);
    auto& table = t.is_float ? float_textures_ : spectrum_textures_;
    auto it = table.find(other);
    if (it == table.end())
      throw SceneError(p->value_loc,
                       fmt::format("unknown {} texture \"{}\" (defined: {})", value_type, other, names_of(table)));
    index = it->second;
    return def;
  };
  // pbrt-v4's classes: which kinds they come in, and how they map the surface point.
  const bool float_only = cls == "fbm" || cls == "wrinkled" || cls == "windy";
  const bool spectrum_only = cls == "marble";
  if ((float_only && !t.is_float) || (spectrum_only && t.is_float))
    throw SceneError(type_loc, fmt::format("\"{}\" is a {} texture in pbrt-v4; declare it \"{}\"", cls,
                                           float_only ? "float" : "spectrum", float_only ? "float" : "spectrum"));
  // The texture's space: the CTM at this directive (pbrt-v4's renderFromTexture).
  t.texture_from_world = gs_.ctm.inverse();
  auto octaves_param = [&](const char* pname, int def) {
    const int v = pl.get_int(pname, def);
    if (v < 0 || v > 64)
      throw SceneError(pl.find(pname)->value_loc, fmt::format("\"{}\" must be in [0, 64], got {}", pname, v));
    return v;
  };
  if (cls == "imagemap") {
    read_image_map(pl, loc, t);
  } else if (cls == "constant") {
    t.type = TextureDesc::Type::Constant;
    t.value = value_param("value", RGB(1));
  } else if (cls == "scale") {
    t.type = TextureDesc::Type::Scale;
    t.value = value_or_texture("tex", RGB(1), t.base);
    if (const ParsedParam* p = pl.find("scale")) {
      if (p->type == "texture") {
        p->used = true;
        s_.diagnostics.warn(p->param.loc, "textured \"scale\" of a scale texture ignored (1 used)");
      } else {
        t.scale = pl.get_float("scale", 1);
      }
    }
  } else if (cls == "mix") {
    // pbrt-v4: (1 - amount) tex1 + amount tex2; amount a float value or float texture.
    t.type = TextureDesc::Type::Mix;
    t.value = value_or_texture("tex1", RGB(0), t.tex1);
    t.value2 = value_or_texture("tex2", RGB(1), t.tex2);
    t.amount = float_or_texture(pl, "amount", 0.5f, t.amount_texture);
  } else if (cls == "directionmix") {
    // pbrt-v4: amount = |n . dir| (dir in the texture's space); amount tex1 + (1 - amount) tex2.
    t.type = TextureDesc::Type::DirectionMix;
    t.value = value_or_texture("tex1", RGB(0), t.tex1);
    t.value2 = value_or_texture("tex2", RGB(1), t.tex2);
    const Vec3 dir = pl.get_vec3("dir", {"vector3"}).value_or(Vec3(0, 1, 0));
    const Vec3 world = gs_.ctm.vector(dir);
    if (!(length(world) > 0) || !std::isfinite(length(world)))
      throw SceneError(pl.find("dir")->value_loc, "directionmix \"dir\" must be a non-zero, finite vector");
    t.dir = normalize(world);
  } else if (cls == "bilerp") {
    // pbrt-v4: bilinear in (s, t) between the values at the corners v00, v01, v10, v11.
    t.type = TextureDesc::Type::Bilerp;
    read_mapping_2d(pl, t);
    t.corners = {value_param("v00", RGB(0)), value_param("v01", RGB(1)), value_param("v10", RGB(0)),
                 value_param("v11", RGB(1))};
  } else if (cls == "checkerboard") {
    // pbrt-v4's checkerboard: tex1 where floor(s) + floor(t) (3D: + floor(z)) is even, tex2 where odd.
    t.type = TextureDesc::Type::Checkerboard;
    t.value = value_or_texture("tex1", RGB(1), t.tex1);
    t.value2 = value_or_texture("tex2", RGB(0), t.tex2);
    const int dimension = pl.get_int("dimension", 2);
    if (dimension != 2 && dimension != 3)
      throw SceneError(pl.find("dimension")->value_loc,
                       fmt::format("checkerboard \"dimension\" must be 2 or 3, got {}", dimension));
    if (dimension == 2)
      read_mapping_2d(pl, t);
    else
      t.mapping = "3d";
  } else if (cls == "dots") {
    // pbrt-v4's polka dots: inside (1) in the dots, outside (0) elsewhere.
    t.type = TextureDesc::Type::Dots;
    read_mapping_2d(pl, t);
    t.value = value_or_texture("inside", RGB(1), t.tex1);
    t.value2 = value_or_texture("outside", RGB(0), t.tex2);
  } else if (cls == "fbm" || cls == "wrinkled" || cls == "marble") {
    t.type = cls == "fbm"        ? TextureDesc::Type::FBm
             : cls == "wrinkled" ? TextureDesc::Type::Wrinkled
                                 : TextureDesc::Type::Marble;
    t.mapping = "3d";
    t.octaves = octaves_param("octaves", 8);
    t.roughness = pl.get_float("roughness", 0.5f);
    if (cls == "marble") {
      t.scale = pl.get_float("scale", 1);
      t.variation = pl.get_float("variation", 0.2f);
    }
  } else if (cls == "windy") {
    t.type = TextureDesc::Type::Windy;
    t.mapping = "3d";
  } else {  // "ptex", the one pbrt-v4 texture left (require_known_type refused the rest)
    // Ptex (per-face textures) needs the Ptex library, which Dermis does not use.
    for (const char* p : {"filename", "encoding", "scale"})
      if (const ParsedParam* q = pl.find(p)) q->used = true;
    s_.diagnostics.warn(loc, fmt::format("ptex textures are not supported; texture \"{}\" is the constant 1", name));
    t.type = TextureDesc::Type::Constant;
    t.value = RGB(1);
  }
  pl.warn_unused(s_.diagnostics, fmt::format("Texture \"{}\"", cls));
  auto& table = t.is_float ? float_textures_ : spectrum_textures_;
  table[name] = int(s_.textures.size());  // pbrt-v4 lets a later definition replace an earlier one
  s_.textures.push_back(std::move(t));
}

// ---------------------------------------------------------------- lights

void SceneParser::light_source(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::LightSource, type, type_loc);
  ParamList pl = ParamList::parse(ts);
  LightDesc l;
  l.loc = loc;
  l.light_to_world = gs_.ctm;
  l.medium = gs_.outside_medium;
  for (const char* ignored : {"power", "illuminance"})
    if (const ParsedParam* p = pl.find(ignored);
        p && !(std::string(ignored) == "illuminance" && (type == "infinite" || type == "distant"))) {
      p->used = true;
      s_.diagnostics.warn(p->param.loc, fmt::format("\"{}\" ignored: Dermis uses the given radiance/intensity and "
                                                    "\"scale\" only",
                                                    ignored));
    }
  if (type == "point") {
    l.type = LightDesc::Type::Point;
    l.spectrum = emission_param(pl, "I", s_.diagnostics);
    l.spectrum_data = spectrum_data(pl, "I", SpectrumType::Illuminant);
    l.from = pl.get_vec3("from", {"point3"}).value_or(l.from);
  } else if (type == "spot") {
    l.type = LightDesc::Type::Spot;
    l.spectrum = emission_param(pl, "I", s_.diagnostics);
    l.spectrum_data = spectrum_data(pl, "I", SpectrumType::Illuminant);
    l.from = pl.get_vec3("from", {"point3"}).value_or(l.from);
    l.to = pl.get_vec3("to", {"point3"}).value_or(l.to);
    l.cone_angle = pl.get_float("coneangle", l.cone_angle);
    l.cone_delta = pl.get_float("conedelta", l.cone_delta);
    if (l.cone_angle <= 0 || l.cone_angle > 180)
      throw SceneError(pl.find("coneangle")->value_loc, "coneangle must be in (0, 180] degrees");
    if (l.cone_delta < 0) throw SceneError(pl.find("conedelta")->value_loc, "conedelta must not be negative");
    if (l.from == l.to) throw SceneError(loc, "spot light: \"from\" and \"to\" coincide");
  } else if (type == "distant") {
    l.type = LightDesc::Type::Distant;
    l.spectrum = emission_param(pl, "L", s_.diagnostics);
    l.spectrum_data = spectrum_data(pl, "L", SpectrumType::Illuminant);
    l.from = pl.get_vec3("from", {"point3"}).value_or(l.from);
    l.to = pl.get_vec3("to", {"point3"}).value_or(l.to);
    if (l.from == l.to) throw SceneError(loc, "distant light: \"from\" and \"to\" coincide");
    if (const ParsedParam* p = pl.find("illuminance")) {
      l.illuminance = pl.get_float("illuminance", -1);
      if (!(l.illuminance >= 0) || !std::isfinite(l.illuminance))
        throw SceneError(p->value_loc, "distant light \"illuminance\" must be finite and non-negative");
    }
  } else if (type == "infinite") {
    l.type = LightDesc::Type::Infinite;
    if (pl.has("L") && pl.has("filename"))
      throw SceneError(pl.find("filename")->param.loc, "infinite light: give either \"L\" or \"filename\", not both");
    l.spectrum = emission_param(pl, "L", s_.diagnostics);
    l.spectrum_data = spectrum_data(pl, "L", SpectrumType::Illuminant);
    if (pl.has("filename"))
      l.filename = existing_file(pl, "filename",
                                 scene_path(pl.get_string("filename", ""), pl.find("filename")->value_loc, "image"),
                                 "infinite light");
    // pbrt-v4 reads the image in the equal-area octahedral mapping; Dermis also takes
    // lat-long maps when asked ("string mapping" "latlong", not a pbrt-v4 parameter).
    if (const ParsedParam* p = pl.find("mapping")) {
      const std::string m = pl.get_string("mapping", "equalarea");
      if (m != "equalarea" && m != "latlong")
        throw SceneError(p->value_loc, fmt::format("infinite light \"mapping\" must be \"equalarea\" (pbrt-v4's) or "
                                                   "\"latlong\", got \"{}\"",
                                                   m));
      l.latlong = m == "latlong";
    }
    if (const ParsedParam* p = pl.find("illuminance")) {
      l.illuminance = pl.get_float("illuminance", -1);
      if (!(l.illuminance >= 0) || !std::isfinite(l.illuminance))
        throw SceneError(p->value_loc, "infinite light \"illuminance\" must be finite and non-negative");
    }
    if (const ParsedParam* p = pl.find("portal")) {
      // pbrt-v4's portal: four points of a rectangle (its check: opposite edges parallel and
      // adjacent ones perpendicular within 1e-3).
      const std::vector<double> v = pl.get_numbers("portal", {"point3"}, 12);
      if (v.size() != 12)
        throw SceneError(p->value_loc,
                         fmt::format("infinite light \"portal\" needs 4 points (12 numbers), got {}", v.size()));
      for (int i = 0; i < 4; ++i) l.portal.push_back(Vec3(float(v[3 * i]), float(v[3 * i + 1]), float(v[3 * i + 2])));
      const Vec3* q = l.portal.data();
      const Vec3 e01 = q[1] - q[0], e12 = q[2] - q[1], e32 = q[2] - q[3], e03 = q[3] - q[0];
      auto unit = [](Vec3 e) { return length(e) > 0 ? e / length(e) : e; };
      const bool rectangle =
          length(e01) > 0 && length(e12) > 0 && length(e32) > 0 && length(e03) > 0 &&
          std::abs(dot(unit(e01), unit(e32)) - 1) <= 1e-3f && std::abs(dot(unit(e12), unit(e03)) - 1) <= 1e-3f &&
          std::abs(dot(unit(e01), unit(e12))) <= 1e-3f && std::abs(dot(unit(e12), unit(e32))) <= 1e-3f &&
          std::abs(dot(unit(e32), unit(e03))) <= 1e-3f && std::abs(dot(unit(e03), unit(e01))) <= 1e-3f;
      if (!rectangle)
        throw SceneError(p->value_loc,
                         "infinite light \"portal\" is not a planar rectangle (pbrt-v4 needs p0 p1 p2 p3 "
                         "in order around a rectangle)");
    }
  } else {
    s_.diagnostics.warn(loc, fmt::format("LightSource \"{}\" is not supported and is ignored", type));
    pl.mark_all_used();
    return;
  }
  l.scale = light_scale_param(pl, l.spectrum,
                              l.type == LightDesc::Type::Point || l.type == LightDesc::Type::Spot ? "I" : "L");
  pl.warn_unused(s_.diagnostics, fmt::format("LightSource \"{}\"", type));
  s_.lights.push_back(std::move(l));
}

void SceneParser::area_light_source(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::AreaLightSource, type, type_loc);
  ParamList pl = ParamList::parse(ts);
  if (type != "diffuse") {
    s_.diagnostics.warn(loc, fmt::format("AreaLightSource \"{}\" is not supported; shapes stay non-emissive", type));
    pl.mark_all_used();
    gs_.area_light.reset();
    return;
  }
  AreaLightDesc a;
  a.L = emission_param(pl, "L", s_.diagnostics);
  a.L_data = spectrum_data(pl, "L", SpectrumType::Illuminant);
  a.scale = light_scale_param(pl, a.L, "L");
  a.two_sided = pl.get_bool("twosided", false);
  for (const char* ignored : {"power", "filename"})
    if (const ParsedParam* p = pl.find(ignored)) {
      p->used = true;
      s_.diagnostics.warn(p->param.loc, fmt::format("area light \"{}\" ignored", ignored));
    }
  pl.warn_unused(s_.diagnostics, "AreaLightSource \"diffuse\"");
  gs_.area_light = a;
}

// ---------------------------------------------------------------- media

void SceneParser::make_named_medium(const Token& d, TokenStream& ts) {
  const SourceLoc loc = ts.loc(d);
  SourceLoc name_loc;
  std::string name = string_arg(ts, d, &name_loc);
  ParamList pl = ParamList::parse(ts);
  if (media_.count(name)) throw SceneError(name_loc, fmt::format("medium \"{}\" is defined twice", name));
  if (!pl.has("type")) throw SceneError(loc, fmt::format("MakeNamedMedium \"{}\" needs \"string type\"", name));
  std::string type = pl.get_string("type", "");
  require_known_type(TypedDirective::Medium, type, pl.find("type")->value_loc);
  MediumDesc m;
  m.name = name;
  m.loc = loc;
  m.type = type;
  if (type != "homogeneous") {
    read_grid_medium(pl, m);
    pl.warn_unused(s_.diagnostics, fmt::format("MakeNamedMedium \"{}\"", type));
    media_[name] = int(s_.media.size());
    s_.media.push_back(std::move(m));
    return;
  }
  const ParsedParam* preset = pl.find("preset");
  if (!preset) preset = pl.find("name");  // pbrt-v3 spelling
  if (preset) {
    std::string pname = pl.get_string(preset->param.name, "");
    auto p = find_medium_preset(pname);
    if (!p)
      throw SceneError(preset->value_loc, fmt::format("unknown medium preset \"{}\"{} (valid: {})", pname,
                                                      medium_preset_suggestion(pname), medium_preset_names()));
    m.preset = p->name;
    m.sigma_a = p->sigma_a;
    m.sigma_s = p->sigma_s_prime;  // as pbrt: sigma_s' with g = 0
    m.g = 0;
    for (const char* ignored : {"sigma_a", "sigma_s", "g"})
      if (const ParsedParam* q = pl.find(ignored)) {
        q->used = true;
        s_.diagnostics.warn(q->param.loc, fmt::format("\"{}\" ignored: preset \"{}\" sets it", ignored, m.preset));
      }
  } else {
    m.sigma_a = rgb_param(pl, "sigma_a", m.sigma_a, s_.diagnostics);
    m.sigma_s = rgb_param(pl, "sigma_s", m.sigma_s, s_.diagnostics);
    m.sigma_a_data = spectrum_data(pl, "sigma_a", SpectrumType::Unbounded);
    m.sigma_s_data = spectrum_data(pl, "sigma_s", SpectrumType::Unbounded);
    m.g = pl.get_float("g", 0);
    if (!(m.g > -1 && m.g < 1))
      throw SceneError(pl.find("g")->value_loc, fmt::format("g must be in (-1, 1), got {}", m.g));
  }
  for (int c = 0; c < 3; ++c)
    if (m.sigma_a[c] < 0 || m.sigma_s[c] < 0)
      throw SceneError(loc, fmt::format("medium \"{}\": sigma_a and sigma_s must not be negative", name));
  m.scale = pl.get_float("scale", 1);
  if (m.scale < 0) throw SceneError(pl.find("scale")->value_loc, "scale must not be negative");
  // Emission: pbrt-v4's Le (a spectrum at luminance 1) times Lescale.
  m.Lescale = pl.get_float("Lescale", 1);
  m.Le = rgb_param(pl, "Le", RGB(0), s_.diagnostics, SpectrumType::Illuminant);
  m.Le_data = spectrum_data(pl, "Le", SpectrumType::Illuminant);
  for (auto [what, v] : {std::pair{"Le", m.Le}, {"Lescale", RGB(m.Lescale)}})
    if (!(std::min({v[0], v[1], v[2]}) >= 0) || !std::isfinite(v.max()))
      throw SceneError(pl.find(what)->value_loc,
                       fmt::format("medium \"{}\": \"{}\" must be finite and not negative", name, what));
  pl.warn_unused(s_.diagnostics, "MakeNamedMedium \"homogeneous\"");
  media_[name] = int(s_.media.size());
  s_.media.push_back(std::move(m));
}

// pbrt-v4 looks media up by name when the scene is built: a medium may be defined after
// the MediumInterface (or the material's "interior") that names it. Unknown names wait as
// pending references (resolved, or reported at this name, by finish()).
int SceneParser::medium_reference(const std::string& name, const SourceLoc& at) {
  if (name.empty()) return -1;
  auto it = media_.find(name);
  if (it != media_.end()) return it->second;
  pending_media_.push_back({name, at});
  return kFirstPendingMedium - int(pending_media_.size() - 1);
}

void SceneParser::medium_interface(const Token& d, TokenStream& ts) {
  const SourceLoc loc = ts.loc(d);
  SourceLoc in_loc, out_loc;
  std::string inside = string_arg(ts, d, &in_loc), outside = inside;
  out_loc = in_loc;
  if (const Token* t = ts.peek(); t && t->kind == Token::Kind::String) outside = string_arg(ts, d, &out_loc);
  const int in = medium_reference(inside, in_loc), out = medium_reference(outside, out_loc);
  if (open_object_ >= 0) {
    s_.diagnostics.warn(loc, "MediumInterface inside ObjectBegin/ObjectEnd ignored (instanced shapes get no media)");
    return;
  }
  gs_.inside_medium = in;
  gs_.outside_medium = out;
}

}  // namespace dermis
