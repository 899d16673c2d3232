#include "dermis/scene/parser.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include "dermis/scene/gzip_file.h"
#include "dermis/scene/pbrt_v4_types.h"
#include "dermis/scene/scene_parser.h"
#include "dermis/spectral/named_spectra_data.h"

namespace dermis {

namespace fs = std::filesystem;

std::string resolve_path(const std::string& file, const std::string& dir) {
  fs::path p(file);
  if (p.is_relative()) p = fs::path(dir) / p;
  std::string s = fs::absolute(p).lexically_normal().string();
  if (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

namespace {

// A scene file read a chunk at a time (inflated when it is gzip data); a read error met on
// the way (gzip data found corrupt midway) is reported as an unreadable file is, at the same
// place.
class SceneFileText final : public TextSource {
 public:
  using ErrorAt = std::function<SceneError(const std::string& why)>;
  SceneFileText(const std::string& path, ErrorAt error) : error_(std::move(error)), chunks_(open(path)) {}
  std::string_view next_chunk() override {
    try {
      return chunks_->next();
    } catch (const FileReadError& e) {
      throw error_(e.reason());
    }
  }
  double fraction_read() const override { return chunks_->fraction_read(); }

 private:
  std::unique_ptr<FileChunks> open(const std::string& path) const {
    try {
      return std::make_unique<FileChunks>(path);
    } catch (const FileReadError& e) {
      throw error_(e.reason());
    }
  }
  ErrorAt error_;
  std::unique_ptr<FileChunks> chunks_;
};

// The directives this parser knows (pbrt-v4's), for suggestions.
constexpr const char* kDirectives[] = {"Identity",
                                       "Translate",
                                       "Scale",
                                       "Rotate",
                                       "LookAt",
                                       "Transform",
                                       "ConcatTransform",
                                       "CoordinateSystem",
                                       "CoordSysTransform",
                                       "ActiveTransform",
                                       "TransformTimes",
                                       "ReverseOrientation",
                                       "AttributeBegin",
                                       "AttributeEnd",
                                       "TransformBegin",
                                       "TransformEnd",
                                       "Camera",
                                       "Film",
                                       "PixelFilter",
                                       "Sampler",
                                       "Integrator",
                                       "Accelerator",
                                       "ColorSpace",
                                       "Option",
                                       "WorldBegin",
                                       "WorldEnd",
                                       "Include",
                                       "Import",
                                       "Shape",
                                       "ObjectBegin",
                                       "ObjectEnd",
                                       "ObjectInstance",
                                       "Material",
                                       "MakeNamedMaterial",
                                       "NamedMaterial",
                                       "Texture",
                                       "LightSource",
                                       "AreaLightSource",
                                       "MakeNamedMedium",
                                       "MediumInterface",
                                       "Attribute"};

// " (did you mean 'Shape'?)" for a near miss, else a hint that the file may not be a scene.
std::string did_you_mean(const std::string& name) {
  if (name.size() <= 40)
    for (const char* known : kDirectives)
      if (edit_distance(name, known) <= 2) return fmt::format(" (did you mean '{}'?)", known);
  return " (is this a pbrt-v4 scene file?)";
}

std::string describe(const Token* t) {
  if (!t) return "the end of the file";
  return fmt::format("{} '{}'", token_kind_name(t->kind), excerpt(t->text));
}

}  // namespace

// ---------------------------------------------------------------- files

// A scene file (main, Included or Imported) opened to be read, with a precise error when it
// cannot be read, would close a cycle, or nests too deep.
OpenText SceneParser::open_scene_file(const std::string& path, const SourceLoc* from,
                                      const std::vector<std::string>& chain) {
  std::string canonical = resolve_path(path, ".");
  if (std::find(chain.begin(), chain.end(), canonical) != chain.end()) {
    std::string text;
    for (const std::string& f : chain) text += f + " -> ";
    throw SceneError(*from, fmt::format("Include cycle: {}{}", text, canonical));
  }
  // A chain of Includes deeper than any real scene needs ends here, not in a stack overflow.
  constexpr std::size_t kMaxIncludeDepth = 64;
  if (from && chain.size() >= kMaxIncludeDepth)
    throw SceneError(*from, fmt::format("Include nested more than {} files deep (at '{}'); is the scene generating "
                                        "its own includes?",
                                        kMaxIncludeDepth, canonical));
  SceneFileText::ErrorAt error = [path, canonical, at = from ? *from : SourceLoc{path, 1, 1},
                                  included = from != nullptr](const std::string& why) {
    if (included) return SceneError(at, fmt::format("could not read included file '{}': {}", canonical, why));
    return SceneError(at, fmt::format("could not read scene file '{}': {}", path, why));
  };
  OpenText text;
  text.file = from ? canonical : path;
  text.source = std::make_unique<SceneFileText>(canonical, error);
  text.origin = std::make_shared<TextOrigin>(TextOrigin{text.file, [canonical, error]() -> std::unique_ptr<TextSource> {
                                                          return std::make_unique<SceneFileText>(canonical, error);
                                                        }});
  text.stage = std::make_unique<LoadStage>(monitor_, "parsing " + fs::path(canonical).filename().string());
  return text;
}

void SceneParser::parse_file(const std::string& path, const SourceLoc* from) {
  // pbrt-v4 (SetSearchDirectory in ParseFiles) resolves every relative path against the
  // directory of the main scene file, in included files too.
  main_dir_ = fs::path(resolve_path(path, ".")).parent_path().string();
  file_access_ = std::make_shared<const FileAccess>(access_options_, main_dir_);
  TokenStream ts(open_scene_file(path, from, {}));
  run(ts, main_dir_);
}

void SceneParser::parse_text(const std::string& text, const std::string& name, const std::string& base_dir) {
  main_dir_ = resolve_path(".", base_dir);
  file_access_ = std::make_shared<const FileAccess>(access_options_, main_dir_);
  TokenStream ts(open_text(text, name));
  run(ts, main_dir_);
}

std::string SceneParser::scene_path(const std::string& file, const SourceLoc& at, const std::string& what) {
  const std::string path = find_scene_file(file, at);
  if (file_access_) file_access_->check_read(path, file, at, what);
  return path;
}

std::string SceneParser::find_scene_file(const std::string& file, const SourceLoc& at) {
  const std::string main = resolve_path(file, main_dir_);
  std::error_code ec;
  if (fs::path(file).is_absolute() || fs::exists(main, ec)) return main;
  // Not where pbrt-v4 looks. Scenes written for Dermis before it followed pbrt-v4 (or for
  // renderers that resolve against the including file) may name it relative to the file
  // that names it: accepted with a warning.
  const std::string beside = resolve_path(file, fs::path(resolve_path(at.file, ".")).parent_path().string());
  if (beside != main && fs::exists(beside, ec)) {
    // One cause, one warning: the first such path is named, the others follow silently.
    if (!warned_beside_)
      s_.diagnostics.warn(at, fmt::format("'{}' is not in the main scene file's directory ('{}'), where pbrt-v4 looks; "
                                          "using '{}' beside the file that names it (further paths found this way "
                                          "are not warned)",
                                          file, main_dir_, beside));
    warned_beside_ = true;
    return beside;
  }
  return main;
}

void SceneParser::include(const Token& d, TokenStream& ts) {
  SourceLoc loc;
  std::string file = string_arg(ts, d, &loc);
  const std::string path = scene_path(file, loc, d.text);
  std::vector<std::string> chain = outer_files_;
  for (const std::string& f : ts.open_files()) chain.push_back(resolve_path(f, "."));
  if (d.text == "Include") {
    // pbrt-v4: the included tokens continue this stream (a parameter list may run on
    // past the end of the included file), sharing the graphics state.
    ts.include(open_scene_file(path, &loc, chain));
    return;
  }
  // Import (pbrt-v4: world block only): a separate stream whose graphics state does not
  // leak out; what it defines (shapes, named materials, textures, media, lights) does.
  require_world(d, ts);
  TokenStream imported(open_scene_file(path, &loc, chain));
  const GraphicsState saved = gs_;
  const std::size_t blocks = blocks_.size();
  std::swap(outer_files_, chain);
  run(imported, main_dir_);
  std::swap(outer_files_, chain);
  if (blocks_.size() != blocks)
    throw SceneError(blocks_.size() > blocks ? blocks_.back().loc : loc,
                     "an Imported file must close the AttributeBegin blocks it opens and close no others");
  gs_ = saved;
}

void SceneParser::run(TokenStream& ts, const std::string& dir) {
  ts.set_base_dir(dir);
  ts.set_file_access(file_access_);
  while (!ts.at_end()) {
    if (monitor_ && monitor_->cancelled()) throw Interrupted();
    const Token d = ts.next();
    if (d.kind != Token::Kind::Identifier)
      throw SceneError(ts.loc(d),
                       fmt::format("expected a directive, found {} '{}'", token_kind_name(d.kind), excerpt(d.text)));
    directive(d, ts);
  }
}

int SceneParser::resolve_medium(int index) const {
  if (index > kFirstPendingMedium) return index;
  const PendingMedium& p = pending_media_[std::size_t(kFirstPendingMedium - index)];
  auto it = media_.find(p.name);
  if (it == media_.end()) {
    std::string known;
    for (const auto& [name, i] : media_) known += (known.empty() ? "" : ", ") + name;
    throw SceneError(p.loc, fmt::format("unknown medium \"{}\" (no MakeNamedMedium defines it; defined: {})", p.name,
                                        known.empty() ? "none" : known));
  }
  return it->second;
}

void SceneParser::finish(const std::string& main_file, const std::string& name) {
  // As pbrt-v4 (BasicSceneBuilder::EndOfFiles): a scene without WorldBegin, or with a block
  // left open, is an error. Both are what a file cut short looks like (a download or a copy
  // that stopped), and rendering it would hide that.
  if (!in_world_)
    throw SceneError({name, 1, 1},
                     "the scene ends before WorldBegin: a scene describes its camera and film, then "
                     "WorldBegin, then its lights and shapes (is the file empty or cut short?)");
  // Media named before their definition, resolved now that every definition has been read.
  if (!pending_media_.empty()) {
    s_.camera.medium = resolve_medium(s_.camera.medium);
    for (LightDesc& l : s_.lights) l.medium = resolve_medium(l.medium);
    for (ShapeDesc& sh : s_.shapes) {
      if (sh.inside_medium > kFirstPendingMedium && sh.outside_medium > kFirstPendingMedium) continue;
      sh.inside_medium = resolve_medium(sh.inside_medium);
      sh.outside_medium = resolve_medium(sh.outside_medium);
      sh.has_medium_interface = sh.inside_medium != sh.outside_medium;
    }
  }

  resolve_subsurface_interiors();

  if (open_object_ >= 0)
    throw SceneError(s_.objects[open_object_].loc,
                     fmt::format("ObjectBegin \"{}\" has no matching ObjectEnd", s_.objects[open_object_].name));
  // pbrt-v4 renders such a scene black without a word; say why once.
  const bool lit = !s_.lights.empty() || std::any_of(s_.shapes.begin(), s_.shapes.end(),
                                                     [](const ShapeDesc& sh) { return sh.area_light.has_value(); });
  if (!lit && in_world_)
    s_.diagnostics.warn(world_loc_,
                        "the scene has no lights (no supported LightSource and no shape with an "
                        "AreaLightSource): it renders black");
  for (const Block& b : blocks_)
    throw SceneError(b.loc, b.kind == BlockKind::Attribute
                                ? "AttributeBegin has no matching AttributeEnd (is the file cut short?)"
                                : "TransformBegin has no matching TransformEnd (is the file cut short?)");
  for (const PendingInstance& p : pending_instances_) {
    auto it = objects_.find(p.name);
    if (it == objects_.end()) {
      std::string known;
      for (const auto& [name, index] : objects_) known += (known.empty() ? "" : ", ") + name;
      throw SceneError(p.loc, fmt::format("ObjectInstance of unknown object \"{}\" (defined objects: {})", p.name,
                                          known.empty() ? "none" : known));
    }
    s_.instances[p.index].object = it->second;
  }
  s_.base_directory =
      main_file.empty() ? s_.base_directory : fs::path(resolve_path(main_file, ".")).parent_path().string();
}

// ---------------------------------------------------------------- arguments

double SceneParser::number_arg(TokenStream& ts, const Token& d) {
  const Token* t = ts.peek();
  if (!t || t->kind != Token::Kind::Number)
    throw SceneError(t ? ts.loc(*t) : ts.end_loc(),
                     fmt::format("{} expects a number here, found {}", d.text, describe(t)));
  return ts.next().number;
}

std::vector<double> SceneParser::numbers_arg(TokenStream& ts, const Token& d, size_t n, std::vector<SourceLoc>* locs) {
  std::vector<double> v;
  for (size_t i = 0; i < n; ++i) {
    const Token* t = ts.peek();
    if (!t || t->kind != Token::Kind::Number)
      throw SceneError(t ? ts.loc(*t) : ts.end_loc(),
                       fmt::format("{} expects {} numbers, found {} after {}", d.text, n, describe(t), i));
    if (locs) locs->push_back(ts.loc(*t));
    v.push_back(ts.next().number);
  }
  return v;
}

std::string SceneParser::string_arg(TokenStream& ts, const Token& d, SourceLoc* loc) {
  const Token* t = ts.peek();
  if (!t || t->kind != Token::Kind::String)
    throw SceneError(t ? ts.loc(*t) : ts.end_loc(),
                     fmt::format("{} expects a quoted string here, found {}", d.text, describe(t)));
  if (loc) *loc = ts.loc(*t);
  return ts.next().text;
}

Transform SceneParser::matrix_arg(TokenStream& ts, const Token& d) {
  const Token* open = ts.peek();
  bool bracketed = open && open->kind == Token::Kind::LBracket;
  SourceLoc start = open ? ts.loc(*open) : ts.end_loc();
  if (bracketed) ts.next();
  std::vector<double> v = numbers_arg(ts, d, 16);
  if (bracketed) {
    const Token* close = ts.peek();
    if (!close || close->kind != Token::Kind::RBracket)
      throw SceneError(close ? ts.loc(*close) : ts.end_loc(),
                       fmt::format("{}: missing ']' after 16 numbers, found {}", d.text, describe(close)));
    ts.next();
  }
  // pbrt writes the matrix column by column (it transposes on input).
  Mat4 m;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m.m[j][i] = v[4 * i + j];
  Mat4 inv;
  if (!m.invert(inv)) throw SceneError(start, fmt::format("{}: the matrix is singular", d.text));
  return Transform(m, inv);
}

void SceneParser::require_world(const Token& d, TokenStream& ts) const {
  if (!in_world_) throw SceneError(ts.loc(d), fmt::format("{} is only allowed after WorldBegin", d.text));
}

void SceneParser::require_options(const Token& d, TokenStream& ts) const {
  if (in_world_) throw SceneError(ts.loc(d), fmt::format("{} is only allowed before WorldBegin", d.text));
}

// ---------------------------------------------------------------- dispatch

void SceneParser::directive(const Token& d, TokenStream& ts) {
  const std::string& n = d.text;
  const SourceLoc loc = ts.loc(d);
  if (n == "Identity") {
    gs_.ctm = Transform();
  } else if (n == "Translate") {
    std::vector<double> v = numbers_arg(ts, d, 3);
    apply(Transform::translate({v[0], v[1], v[2]}));
  } else if (n == "Scale") {
    std::vector<SourceLoc> locs;
    std::vector<double> v = numbers_arg(ts, d, 3, &locs);
    for (int i = 0; i < 3; ++i)
      if (v[i] == 0) throw SceneError(locs[i], "Scale by zero makes the transformation singular");
    apply(Transform::scale({v[0], v[1], v[2]}));
  } else if (n == "Rotate") {
    std::vector<double> v = numbers_arg(ts, d, 4);
    if (v[1] == 0 && v[2] == 0 && v[3] == 0) throw SceneError(loc, "Rotate: the rotation axis has zero length");
    apply(Transform::rotate(v[0], {v[1], v[2], v[3]}));
  } else if (n == "LookAt") {
    std::vector<double> v = numbers_arg(ts, d, 9);
    try {
      apply(Transform::look_at({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}));
    } catch (const std::invalid_argument& e) {
      throw SceneError(loc, fmt::format("degenerate LookAt ({})", e.what()));
    }
  } else if (n == "Transform") {
    gs_.ctm = matrix_arg(ts, d);
  } else if (n == "ConcatTransform") {
    apply(matrix_arg(ts, d));
  } else if (n == "CoordinateSystem") {
    coordinate_systems_[string_arg(ts, d)] = gs_.ctm;
  } else if (n == "CoordSysTransform") {
    std::string name = string_arg(ts, d);
    auto it = coordinate_systems_.find(name);
    if (it == coordinate_systems_.end())
      s_.diagnostics.warn(loc, fmt::format("CoordSysTransform: no coordinate system named \"{}\" (ignored)", name));
    else
      gs_.ctm = it->second;
  } else if (n == "ActiveTransform") {
    const Token* t = ts.peek();
    if (t && t->kind == Token::Kind::Identifier && (t->text == "All" || t->text == "StartTime" || t->text == "EndTime"))
      ts.next();
    else
      throw SceneError(t ? ts.loc(*t) : ts.end_loc(),
                       fmt::format("ActiveTransform expects All, StartTime or EndTime, found {}", describe(t)));
    s_.diagnostics.warn(loc, "ActiveTransform ignored: Dermis has no motion blur (one transform for all times)");
  } else if (n == "TransformTimes") {
    numbers_arg(ts, d, 2);
    s_.diagnostics.warn(loc, "TransformTimes ignored: Dermis has no motion blur");
  } else if (n == "ReverseOrientation") {
    gs_.reverse_orientation = !gs_.reverse_orientation;
  } else if (n == "AttributeBegin" || n == "TransformBegin") {
    if (n == "TransformBegin")
      s_.diagnostics.warn(loc, "TransformBegin is deprecated in pbrt-v4 (use AttributeBegin); accepted");
    blocks_.push_back({n == "AttributeBegin" ? BlockKind::Attribute : BlockKind::Transform, gs_, loc});
  } else if (n == "AttributeEnd") {
    block_end(d, ts, BlockKind::Attribute);
  } else if (n == "TransformEnd") {
    s_.diagnostics.warn(loc, "TransformEnd is deprecated in pbrt-v4 (use AttributeEnd); accepted");
    block_end(d, ts, BlockKind::Transform);
  } else if (n == "Camera") {
    camera(d, ts);
  } else if (n == "Film") {
    film(d, ts);
  } else if (n == "PixelFilter") {
    pixel_filter(d, ts);
  } else if (n == "Sampler") {
    sampler(d, ts);
  } else if (n == "Integrator") {
    integrator(d, ts);
  } else if (n == "Accelerator") {
    require_options(d, ts);
    string_arg(ts, d);
    ParamList::parse(ts);
    s_.diagnostics.warn(loc, "Accelerator ignored (Dermis uses Embree's BVH)");
  } else if (n == "ColorSpace") {
    std::string cs = string_arg(ts, d);
    s_.diagnostics.warn(loc, fmt::format("ColorSpace \"{}\" ignored: Dermis renders in linear Rec.709 (sRGB) RGB", cs));
  } else if (n == "Option") {
    ParamList pl = ParamList::parse(ts);
    std::string what = pl.items().empty() ? "" : pl.items()[0].param.name;
    if (what == "spectral")  // Dermis' own: spectral transport (pbrt-v4 is always spectral)
      s_.settings.spectral = pl.get_bool("spectral", false);
    else
      s_.diagnostics.warn(loc, fmt::format("Option \"{}\" ignored", what));
  } else if (n == "WorldBegin") {
    if (in_world_) throw SceneError(loc, "WorldBegin given twice");
    in_world_ = true;
    world_loc_ = loc;
    gs_.ctm = Transform();
    coordinate_systems_["world"] = gs_.ctm;
  } else if (n == "WorldEnd") {
    // pbrt-v3's end marker: pbrt-v4 has none; accepted silently.
  } else if (n == "Include" || n == "Import") {
    include(d, ts);
  } else if (n == "Shape") {
    shape(d, ts);
  } else if (n == "ObjectBegin") {
    object_begin(d, ts);
  } else if (n == "ObjectEnd") {
    object_end(d, ts);
  } else if (n == "ObjectInstance") {
    object_instance(d, ts);
  } else if (n == "Material") {
    material(d, ts);
  } else if (n == "MakeNamedMaterial") {
    make_named_material(d, ts);
  } else if (n == "NamedMaterial") {
    named_material(d, ts);
  } else if (n == "Texture") {
    texture(d, ts);
  } else if (n == "LightSource") {
    light_source(d, ts);
  } else if (n == "AreaLightSource") {
    area_light_source(d, ts);
  } else if (n == "MakeNamedMedium") {
    make_named_medium(d, ts);
  } else if (n == "MediumInterface") {
    medium_interface(d, ts);
  } else if (n == "Attribute") {
    std::string target = string_arg(ts, d);
    ParamList pl = ParamList::parse(ts);
    std::string names;
    for (const ParsedParam& p : pl.items()) names += (names.empty() ? "" : ", ") + p.param.name;
    s_.diagnostics.warn(loc, fmt::format("Attribute \"{}\" ignored (parameters: {})", target, names));
  } else {
    // pbrt-v4 stops at an unknown directive too: what follows would be read wrongly.
    throw SceneError(loc, fmt::format("unknown directive '{}'{}", excerpt(n), did_you_mean(n)));
  }
}

void SceneParser::block_end(const Token& d, TokenStream& ts, BlockKind kind) {
  const SourceLoc loc = ts.loc(d);
  const char* begin = kind == BlockKind::Attribute ? "AttributeBegin" : "TransformBegin";
  if (blocks_.empty()) throw SceneError(loc, fmt::format("{} without a matching {}", d.text, begin));
  const Block& b = blocks_.back();
  if (b.kind == BlockKind::Object)
    throw SceneError(loc, fmt::format("{} closes the ObjectBegin at {} (use ObjectEnd)", d.text, b.loc.str()));
  if (b.kind != kind)
    throw SceneError(loc,
                     fmt::format("{} closes the {} at {}", d.text,
                                 b.kind == BlockKind::Attribute ? "AttributeBegin" : "TransformBegin", b.loc.str()));
  if (kind == BlockKind::Attribute)
    gs_ = b.saved;
  else
    gs_.ctm = b.saved.ctm;
  blocks_.pop_back();
}

// ---------------------------------------------------------------- rendering options

void SceneParser::camera(const Token& d, TokenStream& ts) {
  require_options(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::Camera, type, type_loc);
  ParamList pl = ParamList::parse(ts);
  if (type != "perspective" && type != "orthographic")
    s_.diagnostics.warn(loc, fmt::format("Camera \"{}\" is not supported; rendered as \"perspective\"", type));
  CameraDesc& c = s_.camera;
  c.loc = loc;
  c.camera_to_world = gs_.ctm.inverse();  // pbrt: the CTM at Camera is camera-from-world
  coordinate_systems_["camera"] = c.camera_to_world;
  c.medium = gs_.outside_medium;
  c.orthographic = type == "orthographic";
  if (!c.orthographic) c.fov = pl.get_float("fov", 90);  // an orthographic camera leaves "fov" unused (warned)
  if (!(c.fov > 0 && c.fov < 180))
    throw SceneError(pl.find("fov")->value_loc, fmt::format("fov must be in (0, 180) degrees, got {}", c.fov));
  c.lens_radius = pl.get_float("lensradius", 0);
  if (c.lens_radius < 0) throw SceneError(pl.find("lensradius")->value_loc, "lensradius must not be negative");
  c.focal_distance = pl.get_float("focaldistance", 1e6f);
  if (c.focal_distance <= 0) throw SceneError(pl.find("focaldistance")->value_loc, "focaldistance must be positive");
  std::vector<double> sw = pl.get_numbers("screenwindow", {"float"}, 1);
  if (!sw.empty()) {
    if (sw.size() != 4)
      throw SceneError(pl.find("screenwindow")->value_loc,
                       fmt::format("screenwindow expects 4 values (xmin xmax ymin ymax), got {}", sw.size()));
    c.screen_window = std::array<float, 4>{float(sw[0]), float(sw[1]), float(sw[2]), float(sw[3])};
  }
  pl.warn_unused(s_.diagnostics, "Camera");
}

void SceneParser::film(const Token& d, TokenStream& ts) {
  require_options(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::Film, type, type_loc);
  ParamList pl = ParamList::parse(ts);
  if (type == "gbuffer" || type == "spectral")
    s_.diagnostics.warn(loc, fmt::format("Film \"{}\" is written as an \"rgb\" film", type));
  FilmDesc& f = s_.film;
  f.xres = pl.get_int("xresolution", f.xres);
  if (f.xres <= 0)
    throw SceneError(pl.find("xresolution")->value_loc, fmt::format("xresolution must be positive, got {}", f.xres));
  f.yres = pl.get_int("yresolution", f.yres);
  if (f.yres <= 0)
    throw SceneError(pl.find("yresolution")->value_loc, fmt::format("yresolution must be positive, got {}", f.yres));
  f.filename = pl.get_string("filename", f.filename);
  if (file_access_ && pl.has("filename"))  // written relative to the working directory, as pbrt-v4 does
    file_access_->check_write(resolve_path(f.filename, "."), f.filename, pl.find("filename")->value_loc,
                              "Film \"filename\"");
  if (const ParsedParam* p = pl.find("cropwindow")) {
    // pbrt-v4: [x0 x1 y0 y1] in NDC, rendering and writing only that part of the image.
    const std::vector<double> c = pl.get_numbers("cropwindow", {"float"}, 4);
    if (c.size() != 4 || !(c[0] >= 0 && c[0] < c[1] && c[1] <= 1 && c[2] >= 0 && c[2] < c[3] && c[3] <= 1))
      throw SceneError(p->value_loc, "cropwindow must be [x0 x1 y0 y1] with 0 <= x0 < x1 <= 1 and 0 <= y0 < y1 <= 1");
    f.crop = {float(c[0]), float(c[1]), float(c[2]), float(c[3])};
  }
  {
    // The film holds 28 bytes per pixel: a resolution that cannot be allocated is an error
    // here, at the value, not a std::bad_alloc later (--res is checked again by the app).
    constexpr double kMaxFilmPixels = double(1u << 28);
    const double pixels =
        std::ceil(double(f.xres) * (f.crop[1] - f.crop[0])) * std::ceil(double(f.yres) * (f.crop[3] - f.crop[2]));
    if (pixels > kMaxFilmPixels) {
      const ParsedParam* at = pl.find("xresolution") ? pl.find("xresolution") : pl.find("yresolution");
      throw SceneError(at ? at->value_loc : loc,
                       fmt::format("a film of {}x{} pixels is too large (it would need {:.0f} GiB; at most {} pixels, "
                                   "e.g. 16384x16384): lower xresolution/yresolution or set a cropwindow",
                                   f.xres, f.yres, pixels * 28 / double(1u << 30), kMaxFilmPixels));
    }
  }
  // pbrt-v4's default sensor: pixel values are scaled by iso / 100 times the exposure time (1).
  const float iso = pl.get_float("iso", 100);
  if (!(iso > 0) || !std::isfinite(iso)) throw SceneError(pl.find("iso")->value_loc, "iso must be positive");
  f.exposure_scale = iso / 100;
  // pbrt-v4's "sensor": "cie1931" (the default) is what Dermis's film records (linear sRGB
  // from the CIE 1931 observer). A camera's sensor (canon_eos_100d, ...) would need its
  // measured r, g, b responses and pbrt-v4's fit of them to XYZ, which Dermis does not
  // have: one warning saying so, and the image is the cie1931 one (exposure as above).
  if (const ParsedParam* p = pl.find("sensor")) {
    const std::string sensor = pl.get_string("sensor", "cie1931");
    if (sensor != "cie1931") {
      bool known = false;
      std::string names = "\"cie1931\"";
      for (const char* camera : camera_sensor_names()) {
        known = known || sensor == camera;
        names += fmt::format(", \"{}\"", camera);
      }
      if (!known)  // an error in pbrt-v4 too
        throw SceneError(p->value_loc,
                         fmt::format("unknown Film \"sensor\" \"{}\" (pbrt-v4's sensors: {})", sensor, names));
      s_.diagnostics.warn(p->param.loc,
                          fmt::format("Film \"sensor\" \"{}\": camera sensor responses are not modelled; rendered "
                                      "with the \"cie1931\" sensor (the CIE 1931 observer, linear sRGB), so colours "
                                      "and white balance differ from pbrt-v4's",
                                      sensor));
    }
  }
  pl.warn_unused(s_.diagnostics, fmt::format("Film \"{}\"", type));
}

void SceneParser::pixel_filter(const Token& d, TokenStream& ts) {
  require_options(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::PixelFilter, type, type_loc);
  ParamList pl = ParamList::parse(ts);
  FilterDesc& f = s_.film.filter;
  if (type == "box") {
    f.type = FilterDesc::Type::Box;
    f.radius = Vec2(0.5f, 0.5f);
  } else {
    if (type != "gaussian")
      s_.diagnostics.warn(loc, fmt::format("PixelFilter \"{}\" is not supported; using \"gaussian\"", type));
    f.type = FilterDesc::Type::Gaussian;
    f.radius = Vec2(1.5f, 1.5f);
    f.sigma = pl.get_float("sigma", 0.5f);
    if (f.sigma <= 0) throw SceneError(pl.find("sigma")->value_loc, "sigma must be positive");
  }
  f.radius.x = pl.get_float("xradius", f.radius.x);
  f.radius.y = pl.get_float("yradius", f.radius.y);
  if (f.radius.x <= 0) throw SceneError(pl.find("xradius")->value_loc, "xradius must be positive");
  if (f.radius.y <= 0) throw SceneError(pl.find("yradius")->value_loc, "yradius must be positive");
  pl.warn_unused(s_.diagnostics, fmt::format("PixelFilter \"{}\"", type));
}

void SceneParser::sampler(const Token& d, TokenStream& ts) {
  require_options(d, ts);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  ParamList pl = ParamList::parse(ts);
  // pbrt-v4's samplers, mapped to the nearest of Dermis' (core/sampler.h): its Sobol' variants
  // (zsobol, sobol, paddedsobol) to the padded Owen-scrambled Sobol', the other
  // low-discrepancy ones to it too with a warning.
  if (type == "independent") {
    s_.settings.sampler = SamplerKind::Independent;
  } else if (type == "zsobol" || type == "sobol" || type == "paddedsobol") {
    s_.settings.sampler = SamplerKind::Sobol;
  } else if (type == "halton" || type == "pmj02bn" || type == "stratified") {
    s_.diagnostics.warn(type_loc, fmt::format("Sampler \"{}\" is not available; using \"sobol\" (Owen-scrambled "
                                              "Sobol', the nearest Dermis has)",
                                              type));
    s_.settings.sampler = SamplerKind::Sobol;
  } else {
    throw SceneError(type_loc, fmt::format("unknown Sampler \"{}\" (pbrt-v4 has zsobol, sobol, paddedsobol, halton, "
                                           "pmj02bn, stratified, independent)",
                                           type));
  }
  // Dermis always randomises by Owen scrambling; pbrt-v4's other randomisations are refused.
  const std::string randomization = pl.get_string("randomization", "owen");
  if (randomization != "owen" && randomization != "fastowen")
    s_.diagnostics.warn(
        pl.find("randomization")->value_loc,
        fmt::format("Sampler \"randomization\" \"{}\" is not available; using Owen scrambling", randomization));
  s_.settings.spp = pl.get_int("pixelsamples", s_.settings.spp);
  if (s_.settings.spp <= 0)
    throw SceneError(pl.find("pixelsamples")->value_loc,
                     fmt::format("pixelsamples must be positive, got {}", s_.settings.spp));
  s_.settings.seed = pl.get_int("seed", s_.settings.seed);
  // Dermis' adaptive sampling (pbrt-v4 has none): Cycles' noise threshold and minimum.
  s_.settings.noise_threshold = pl.get_float("noisethreshold", float(s_.settings.noise_threshold));
  if (!(s_.settings.noise_threshold >= 0) || !std::isfinite(s_.settings.noise_threshold))
    throw SceneError(pl.find("noisethreshold")->value_loc,
                     fmt::format("noisethreshold must be 0 (off) or a positive relative error such as 0.01, got {}",
                                 s_.settings.noise_threshold));
  s_.settings.min_spp = pl.get_int("minpixelsamples", s_.settings.min_spp);
  if (s_.settings.min_spp < 0)
    throw SceneError(pl.find("minpixelsamples")->value_loc,
                     fmt::format("minpixelsamples must be positive (or 0: the default), got {}", s_.settings.min_spp));
  pl.warn_unused(s_.diagnostics, fmt::format("Sampler \"{}\"", type));
}

void SceneParser::integrator(const Token& d, TokenStream& ts) {
  require_options(d, ts);
  const SourceLoc loc = ts.loc(d);
  std::string type = string_arg(ts, d);
  ParamList pl = ParamList::parse(ts);
  if (type == "volpath" || type == "path") {
    s_.settings.integrator = type;
  } else {
    s_.diagnostics.warn(loc, fmt::format("Integrator \"{}\" is not supported; using \"volpath\"", type));
    s_.settings.integrator = "volpath";
  }
  s_.settings.max_depth = pl.get_int("maxdepth", s_.settings.max_depth);
  if (s_.settings.max_depth < 0) throw SceneError(pl.find("maxdepth")->value_loc, "maxdepth must not be negative");
  s_.settings.subsurface_samples = pl.get_int("subsurfacesamples", s_.settings.subsurface_samples);
  s_.settings.subsurface_pilot = pl.get_bool("subsurfacepilot", s_.settings.subsurface_pilot);
  if (s_.settings.subsurface_samples < 1 || s_.settings.subsurface_samples > 64)
    throw SceneError(pl.find("subsurfacesamples")->value_loc,
                     fmt::format("subsurfacesamples must lie in [1, 64], got {}", s_.settings.subsurface_samples));
  s_.settings.split_threshold = pl.get_float("splitthreshold", s_.settings.split_threshold);
  if (!(s_.settings.split_threshold == 0 ||
        (s_.settings.split_threshold >= 1 && std::isfinite(s_.settings.split_threshold))))
    throw SceneError(pl.find("splitthreshold")->value_loc,
                     fmt::format("splitthreshold must be 0 (no splitting) or a finite number of at least 1, got {}",
                                 s_.settings.split_threshold));
  pl.warn_unused(s_.diagnostics, fmt::format("Integrator \"{}\"", type));
}

// ---------------------------------------------------------------- entry points

SceneDesc parse_scene_file(const std::string& path, const FileAccessOptions& access, const LoadMonitor* monitor) {
  SceneDesc scene;
  SceneParser parser(scene, access, monitor);
  parser.parse_file(path, nullptr);
  parser.finish(path, path);
  return scene;
}

SceneDesc parse_scene_string(const std::string& text, const std::string& name, const std::string& base_dir,
                             const FileAccessOptions& access, const LoadMonitor* monitor) {
  SceneDesc scene;
  scene.base_directory = resolve_path(".", base_dir);
  SceneParser parser(scene, access, monitor);
  parser.parse_text(text, name, base_dir);
  parser.finish("", name);
  return scene;
}

std::vector<std::string> set_material_parameters(SceneDesc& scene, std::size_t index, const std::string& params_text,
                                                 const std::string& source_name) {
  if (index >= scene.materials.size())
    throw std::out_of_range(
        fmt::format("material {} does not exist (the scene has {})", index, scene.materials.size()));
  const std::size_t warnings_before = scene.diagnostics.warnings.size();
  SceneParser parser(scene);
  MaterialDesc m = parser.rebuild_material(scene.materials[index], params_text, source_name);
  scene.materials[index] = std::move(m);  // only once the whole text was read: an error changes nothing
  std::vector<std::string> added(scene.diagnostics.warnings.begin() + std::ptrdiff_t(warnings_before),
                                 scene.diagnostics.warnings.end());
  scene.diagnostics.warnings.resize(warnings_before);
  return added;
}

}  // namespace dermis
