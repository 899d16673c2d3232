// Internal: the state of the pbrt-v4 parser while it walks the directives. Split over
// parser.cpp (files, transforms, rendering options, block structure), parser_shapes.cpp
// (shapes and object instancing) and parser_appearance.cpp (materials, textures, lights,
// media).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dermis/core/load_monitor.h"
#include "dermis/scene/params.h"
#include "dermis/scene/scene_desc.h"
#include "dermis/scene/spectra.h"
#include "dermis/scene/tokenizer.h"

namespace dermis {

class SceneParser {
 public:
  // `access`: which files the scene may name; `monitor` (may be null): progress of the
  // files and meshes read, and Ctrl-C.
  explicit SceneParser(SceneDesc& scene, FileAccessOptions access = {}, const LoadMonitor* monitor = nullptr)
      : s_(scene), monitor_(monitor), access_options_(std::move(access)) {}

  // Parses one file; `from` is the Include directive's filename token, if any.
  void parse_file(const std::string& path, const SourceLoc* from);
  void parse_text(const std::string& text, const std::string& name, const std::string& base_dir);
  // After the last file: resolves ObjectInstance names, reports unclosed blocks.
  void finish(const std::string& main_file, const std::string& name);
  // `old` (a material of this scene) re-read with the parameters in `params_text`
  // (pbrt parameter text) replacing those of the same name. Throws SceneError.
  MaterialDesc rebuild_material(const MaterialDesc& old, const std::string& params_text,
                                const std::string& source_name);

 private:
  // What AttributeBegin saves (pbrt-v4's graphics state, the parts Dermis uses).
  struct GraphicsState {
    Transform ctm;
    int material = -1;
    std::optional<AreaLightDesc> area_light;
    int inside_medium = -1, outside_medium = -1;
    bool reverse_orientation = false;
  };
  enum class BlockKind { Attribute, Transform, Object };
  struct Block {
    BlockKind kind;
    GraphicsState saved;
    SourceLoc loc;
  };
  // A medium named by MediumInterface before its MakeNamedMedium: stored in the graphics
  // state as kFirstPendingMedium - (index into pending_media_).
  struct PendingMedium {
    std::string name;
    SourceLoc loc;  // the name in the MediumInterface
  };
  static constexpr int kFirstPendingMedium = -2;
  int resolve_medium(int index) const;
  // The medium a name at `at` refers to: its index, or a pending reference (resolved by
  // finish()); -1 for the empty name (vacuum).
  int medium_reference(const std::string& name, const SourceLoc& at);
  struct PendingInstance {
    std::string name;
    size_t index;  // into s_.instances
    SourceLoc loc;
  };

  void run(TokenStream& ts, const std::string& dir);
  void directive(const Token& d, TokenStream& ts);

  // Fixed arguments.
  double number_arg(TokenStream& ts, const Token& d);
  std::vector<double> numbers_arg(TokenStream& ts, const Token& d, size_t n, std::vector<SourceLoc>* locs = nullptr);
  std::string string_arg(TokenStream& ts, const Token& d, SourceLoc* loc = nullptr);
  Transform matrix_arg(TokenStream& ts, const Token& d);

  void require_world(const Token& d, TokenStream& ts) const;
  void require_options(const Token& d, TokenStream& ts) const;
  void apply(const Transform& t) { gs_.ctm = gs_.ctm * t; }

  // parser.cpp
  void camera(const Token& d, TokenStream& ts);
  void film(const Token& d, TokenStream& ts);
  void pixel_filter(const Token& d, TokenStream& ts);
  void sampler(const Token& d, TokenStream& ts);
  void integrator(const Token& d, TokenStream& ts);
  void include(const Token& d, TokenStream& ts);
  OpenText open_scene_file(const std::string& path, const SourceLoc* from, const std::vector<std::string>& chain);
  // A file named in the scene at `at`, resolved as pbrt-v4 does: against the main scene
  // file's directory (then, with a warning, beside the file that names it); an error when
  // the file access is confined and it lies outside (`what` names it in the message).
  std::string scene_path(const std::string& file, const SourceLoc& at, const std::string& what);
  std::string find_scene_file(const std::string& file, const SourceLoc& at);
  void block_end(const Token& d, TokenStream& ts, BlockKind kind);

  // parser_shapes.cpp
  void shape(const Token& d, TokenStream& ts);
  void object_begin(const Token& d, TokenStream& ts);
  void object_end(const Token& d, TokenStream& ts);
  void object_instance(const Token& d, TokenStream& ts);

  // parser_appearance.cpp
  void material(const Token& d, TokenStream& ts);
  void make_named_material(const Token& d, TokenStream& ts);
  void named_material(const Token& d, TokenStream& ts);
  MaterialDesc build_material(const std::string& type, const ParamList& pl, const SourceLoc& loc);
  // Parts of build_material shared by several material types, or long (parser_appearance.cpp).
  void read_microfacet_roughness(const ParamList& pl, const std::string& prefix, MaterialDesc& m, float& u, float& v,
                                 std::array<int, 2>& textures);
  void read_coating(const ParamList& pl, MaterialDesc& m);
  // Parameter `name`'s spectrum kept as data (SceneDesc::spectra) where it is one: its index,
  // else -1 (absent, or rgb).
  int spectrum_data(const ParamList& pl, const std::string& name, SpectrumType type);
  // A named spectrum kept as data (a default, such as pbrt-v4's copper): its index.
  int named_spectrum_data(const std::string& name);
  void read_mix_materials(const ParamList& pl, const SourceLoc& loc, MaterialDesc& m);
  void read_image_map(const ParamList& pl, const SourceLoc& loc, TextureDesc& t);
  RGBTexture spectrum_or_texture(const ParamList& pl, const std::string& name, RGB def);
  // A float parameter (or `def`), or a float texture: then its index in `texture` and `def` returned.
  float float_or_texture(const ParamList& pl, const std::string& name, float def, int& texture);
  void texture(const Token& d, TokenStream& ts);
  void light_source(const Token& d, TokenStream& ts);
  void area_light_source(const Token& d, TokenStream& ts);
  void make_named_medium(const Token& d, TokenStream& ts);
  // parser_media.cpp: the parameters of a grid medium (uniformgrid, rgbgrid, cloud).
  void read_grid_medium(const ParamList& pl, MediumDesc& m);
  void read_grid_emission(const ParamList& pl, MediumDesc& m);
  void read_nanovdb_medium(const ParamList& pl, MediumDesc& m);
  // The subsurface materials' "interior" media, once every medium is defined: a homogeneous
  // one's coefficients copied into the material, a grid one kept (SubsurfaceParams::interior).
  void resolve_subsurface_interiors();
  void medium_interface(const Token& d, TokenStream& ts);

  SceneDesc& s_;
  const LoadMonitor* monitor_;
  GraphicsState gs_;
  std::vector<Block> blocks_;
  bool in_world_ = false;
  SourceLoc world_loc_;  // the WorldBegin
  std::map<std::string, Transform> coordinate_systems_;
  std::map<std::string, int> named_materials_, spectrum_textures_, float_textures_, media_, objects_;
  int open_object_ = -1;  // index into s_.objects while between ObjectBegin and ObjectEnd
  std::vector<PendingInstance> pending_instances_;
  std::vector<PendingMedium> pending_media_;
  std::string main_dir_;                  // directory of the main scene file (pbrt-v4's search directory)
  bool warned_beside_ = false;            // scene_path's fallback has been warned about
  std::vector<std::string> outer_files_;  // while Importing: the files open in the importing streams
  FileAccessOptions access_options_;
  std::shared_ptr<const FileAccess> file_access_;  // made once the scene's directory is known
};

// An absolute, normalized path for `file` written in a scene whose directory is `dir`.
std::string resolve_path(const std::string& file, const std::string& dir);

}  // namespace dermis
