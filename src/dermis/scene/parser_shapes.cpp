// Shape, ObjectBegin, ObjectEnd, ObjectInstance.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dermis/core/cache_dir.h"
#include "dermis/scene/gzip_file.h"
#include "dermis/scene/loop_subdivision.h"
#include "dermis/scene/mesh_cache.h"
#include "dermis/scene/mesh_import.h"
#include "dermis/scene/pbrt_v4_types.h"
#include "dermis/scene/ply_reader.h"
#include "dermis/scene/scene_parser.h"
#include "dermis/scene/shape_tessellation.h"

namespace dermis {

namespace {

// Indices from an "integer indices" parameter, each checked against the vertex count
// (the error points at the offending number).
std::vector<uint32_t> checked_indices(const ParamList& pl, size_t nverts, size_t per_primitive) {
  const ParsedParam* p = pl.find("indices");
  if (!p) return {};
  std::vector<double> v = pl.get_numbers("indices", {"integer"}, per_primitive);
  std::vector<uint32_t> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    if (v[i] < 0 || v[i] >= double(nverts))
      throw SceneError(p->value_at(i),
                       fmt::format("index {} is out of range: the mesh has {} vertices (valid: 0 to {})", v[i], nverts,
                                   nverts == 0 ? 0 : nverts - 1));
    out[i] = uint32_t(v[i]);
  }
  return out;
}

std::vector<Vec2> read_uvs(const ParamList& pl, size_t nverts) {
  const char* name = pl.has("uv") ? "uv" : (pl.has("st") ? "st" : nullptr);
  if (!name) return {};
  std::vector<double> v = pl.get_numbers(name, {"point2", "float"}, 2);
  if (v.size() / 2 != nverts)
    throw SceneError(pl.find(name)->value_loc,
                     fmt::format("\"{}\" has {} entries but \"P\" has {} vertices", name, v.size() / 2, nverts));
  std::vector<Vec2> uv(nverts);
  for (size_t i = 0; i < nverts; ++i) uv[i] = Vec2(float(v[2 * i]), float(v[2 * i + 1]));
  return uv;
}

std::vector<Vec3> read_normals(const ParamList& pl, size_t nverts) {
  std::vector<Vec3> n = pl.get_vec3s("N", {"normal3"});
  if (!n.empty() && n.size() != nverts)
    throw SceneError(pl.find("N")->value_loc,
                     fmt::format("\"N\" has {} normals but \"P\" has {} vertices", n.size(), nverts));
  return n;
}

std::vector<Vec3> read_positions(const ParamList& pl, const SourceLoc& shape_loc, const std::string& type) {
  const ParsedParam* p = pl.find("P");
  if (!p) throw SceneError(shape_loc, fmt::format("Shape \"{}\" needs \"point3 P\"", type));
  return pl.get_vec3s("P", {"point3"});
}

// pbrt-v4's curve: "point3 P" in "basis" bezier|bspline of "degree" 2|3, "type"
// flat|cylinder|ribbon, "normal N" (ribbons: one per segment end), "width" (1) or
// "width0"/"width1" at its ends. "splitdepth" (pbrt-v4's own refinement) is read and not
// needed: Embree intersects the cubic segments directly.
void read_curve(const ParamList& pl, const SourceLoc& loc, ShapeDesc& sh, Diagnostics& diag) {
  std::vector<Vec3> P = read_positions(pl, loc, "curve");
  auto one_of = [&](const char* name, const char* def, std::initializer_list<const char*> allowed) {
    const std::string v = pl.get_string(name, def);
    for (const char* a : allowed)
      if (v == a) return v;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    throw SceneError(pl.find(name)->value_loc, fmt::format("curve \"{}\" \"{}\" is not one of {}", name, v, list));
  };
  const CurveBasis basis =
      one_of("basis", "bezier", {"bezier", "bspline"}) == "bspline" ? CurveBasis::BSpline : CurveBasis::Bezier;
  const std::string kind_name = one_of("type", "flat", {"flat", "cylinder", "ribbon"});
  const CurveKind kind = kind_name == "cylinder" ? CurveKind::Cylinder
                         : kind_name == "ribbon" ? CurveKind::Ribbon
                                                 : CurveKind::Flat;
  const int degree = pl.get_int("degree", 3);
  if (degree != 2 && degree != 3)
    throw SceneError(pl.find("degree")->value_loc, fmt::format("curve degree must be 2 or 3, got {}", degree));
  const float width = pl.get_float("width", 1);
  const float width0 = pl.get_float("width0", width), width1 = pl.get_float("width1", width);
  for (const char* name : {"width", "width0", "width1"})
    if (const ParsedParam* w = pl.find(name);
        w && !(pl.get_float(name, 1) >= 0 && std::isfinite(pl.get_float(name, 1))))
      throw SceneError(w->value_loc,
                       fmt::format("curve \"{}\" must be finite and >= 0, got {}", name, pl.get_float(name, 1)));
  if (!(std::max(width0, width1) > 0)) throw SceneError(loc, "a curve of width 0 has no surface");
  pl.get_int("splitdepth", 3);  // read: pbrt-v4's refinement depth, not needed with Embree
  std::vector<Vec3> N = pl.get_vec3s("N", {"normal3"});
  if (!N.empty() && kind != CurveKind::Ribbon) {
    diag.warn(pl.find("N")->param.loc, fmt::format("curve normals \"N\" are used only by \"ribbon\" curves; this "
                                                   "\"{}\" curve ignores them (as pbrt-v4)",
                                                   kind_name));
    N.clear();
  }
  try {
    sh.curve = curve_to_bezier_segments(P, basis, degree, kind, width0, width1, N);
  } catch (const std::invalid_argument& e) {
    throw SceneError(pl.find(kind == CurveKind::Ribbon && pl.has("N") ? "N" : "P")->value_loc,
                     fmt::format("Shape \"curve\": {}", e.what()));
  }
  sh.type = ShapeDesc::Type::Curve;
}

// pbrt-v4 "alpha" on any shape: a float, or the name of a float texture.
void read_alpha(const ParamList& pl, const std::map<std::string, int>& float_textures,
                const std::map<std::string, int>& spectrum_textures, Diagnostics& diagnostics, ShapeDesc& sh) {
  const ParsedParam* ap = pl.find("alpha");
  if (!ap) return;
  if (ap->type == "texture") {
    const std::string tex = *pl.get_texture("alpha");
    auto it = float_textures.find(tex);
    if (it == float_textures.end())
      throw SceneError(ap->value_loc,
                       fmt::format("unknown float texture \"{}\" for \"alpha\"{}", tex,
                                   spectrum_textures.count(tex) ? " (a spectrum texture has that name)" : ""));
    sh.alpha_texture = it->second;
  } else {
    sh.alpha = pl.get_float("alpha", 1);
  }
  if (sh.area_light && (sh.alpha < 1 || sh.alpha_texture >= 0))
    diagnostics.warn(ap->param.loc,
                     "alpha on an emissive shape: light sampling ignores the cut-outs (the "
                     "emission seen directly respects them)");
}

// A mesh file's triangles (plymesh: Dermis' PLY reader; objmesh: Assimp, through the mesh
// cache), its importer's notes as warnings; a file that cannot be read is a SceneError at loc.
TriangleMeshDesc read_mesh_file(const std::string& type, const std::string& file, const SourceLoc& loc,
                                const LoadMonitor* monitor, Diagnostics& diagnostics) {
  auto mesh_error = [&](const std::string& why) {
    return SceneError(loc, fmt::format("Shape \"{}\": could not read mesh file '{}': {}", type, file, why));
  };
  try {
    if (type == "plymesh") return read_ply(file, monitor);
    ImportedMesh im = import_mesh_cached(file, monitor, default_cache_dir());
    for (const std::string& note : im.notes) diagnostics.warn(loc, fmt::format("'{}': {}", file, note));
    return std::move(im.mesh);
  } catch (const SceneError&) {
    throw;
  } catch (const Interrupted&) {
    throw;
  } catch (const FileReadError& e) {
    throw mesh_error(e.reason());  // the message names the file already
  } catch (const std::exception& e) {
    throw mesh_error(e.what());
  }
}

// The shapes given by their parameters alone (sphere, cylinder, disk, the meshes written in
// the file): their geometry into sh. False for any other type.
bool read_parametric_shape(const std::string& type, const ParamList& pl, const SourceLoc& loc,
                           const LoadMonitor* monitor, ShapeDesc& sh) {
  if (type == "sphere") {
    const float radius = pl.get_float("radius", 1);
    if (!(radius > 0)) throw SceneError(pl.find("radius")->value_loc, "sphere radius must be positive");
    const float zmin = pl.get_float("zmin", -radius), zmax = pl.get_float("zmax", radius);
    const float phimax = pl.get_float("phimax", 360);
    // pbrt-v4 clamps zmin/zmax to [-radius, radius] and phimax to [0, 360].
    if (std::min(zmin, zmax) > -radius || std::max(zmin, zmax) < radius || phimax < 360) {
      if (std::max(zmin, zmax) <= -radius || std::min(zmin, zmax) >= radius || !(phimax > 0))
        throw SceneError(
            loc, fmt::format("partial sphere with zmin {}, zmax {}, phimax {} has no surface", zmin, zmax, phimax));
      sh.mesh = tessellate_sphere_part(radius, zmin, zmax, phimax);
    } else {
      sh.type = ShapeDesc::Type::Sphere;
      sh.radius = radius;
    }
  } else if (type == "cylinder") {
    const float radius = pl.get_float("radius", 1), zmin = pl.get_float("zmin", -1), zmax = pl.get_float("zmax", 1);
    const float phimax = pl.get_float("phimax", 360);
    if (!(radius > 0)) throw SceneError(pl.find("radius")->value_loc, "cylinder radius must be positive");
    if (!(zmin != zmax)) throw SceneError(loc, fmt::format("cylinder with zmin = zmax = {} has no surface", zmin));
    if (!(phimax > 0)) throw SceneError(pl.find("phimax")->value_loc, "cylinder phimax must be positive");
    sh.mesh = tessellate_cylinder(radius, zmin, zmax, phimax);
  } else if (type == "loopsubdiv") {
    std::vector<Vec3> P = read_positions(pl, loc, type);
    if (!pl.has("indices")) throw SceneError(loc, "Shape \"loopsubdiv\" needs \"integer indices\"");
    std::vector<uint32_t> idx = checked_indices(pl, P.size(), 3);
    const int levels = pl.get_int("levels", 3);
    try {
      sh.mesh = loop_subdivision_surface(P, idx, levels, monitor);
    } catch (const std::invalid_argument& e) {
      throw SceneError(loc, fmt::format("Shape \"loopsubdiv\": {}", e.what()));
    }
  } else if (type == "trianglemesh") {
    std::vector<Vec3> P = read_positions(pl, loc, type);
    if (P.size() < 3)
      throw SceneError(pl.find("P")->value_loc,
                       fmt::format("trianglemesh needs at least 3 vertices, got {}", P.size()));
    sh.mesh.positions = P;
    if (pl.has("indices")) {
      sh.mesh.indices = checked_indices(pl, P.size(), 3);
    } else if (P.size() == 3) {
      sh.mesh.indices = {0, 1, 2};
    } else {
      throw SceneError(loc, fmt::format("trianglemesh with {} vertices needs \"integer indices\" (they may be "
                                        "omitted only for exactly 3 vertices)",
                                        P.size()));
    }
    sh.mesh.normals = read_normals(pl, P.size());
    sh.mesh.uvs = read_uvs(pl, P.size());
  } else if (type == "bilinearmesh") {
    std::vector<Vec3> P = read_positions(pl, loc, type);
    std::vector<uint32_t> idx;
    if (pl.has("indices")) {
      idx = checked_indices(pl, P.size(), 4);
    } else if (P.size() == 4) {
      idx = {0, 1, 2, 3};
    } else {
      throw SceneError(loc, fmt::format("bilinearmesh with {} vertices needs \"integer indices\" (they may be "
                                        "omitted only for exactly 4 vertices)",
                                        P.size()));
    }
    std::vector<Vec3> N = read_normals(pl, P.size());
    std::vector<Vec2> uv = read_uvs(pl, P.size());
    sh.mesh = tessellate_bilinear_patches(P, idx, uv, N);
  } else if (type == "disk") {
    float height = pl.get_float("height", 0), radius = pl.get_float("radius", 1);
    float inner = pl.get_float("innerradius", 0);
    if (!(radius > 0)) throw SceneError(pl.find("radius")->value_loc, "disk radius must be positive");
    if (inner < 0 || inner >= radius)
      throw SceneError(pl.find("innerradius")->value_loc, "innerradius must be in [0, radius)");
    const float phimax = pl.get_float("phimax", 360);
    if (!(phimax > 0)) throw SceneError(pl.find("phimax")->value_loc, "disk phimax must be positive");
    sh.mesh = tessellate_disk(height, radius, inner, kDiskSegments, phimax);
  } else {
    return false;
  }
  return true;
}

}  // namespace

void SceneParser::shape(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc type_loc;
  std::string type = string_arg(ts, d, &type_loc);
  require_known_type(TypedDirective::Shape, type, type_loc);
  ParamList pl = ParamList::parse(ts);

  ShapeDesc sh;
  sh.loc = loc;
  sh.object_to_world = gs_.ctm;
  sh.material = gs_.material;
  sh.reverse_orientation = gs_.reverse_orientation != gs_.ctm.swaps_handedness();
  if (open_object_ < 0) {
    sh.area_light = gs_.area_light;
    sh.inside_medium = gs_.inside_medium;
    sh.outside_medium = gs_.outside_medium;
    sh.has_medium_interface = sh.inside_medium != sh.outside_medium;
  } else if (gs_.area_light) {
    s_.diagnostics.warn(loc,
                        "area lights are not supported on instanced shapes (as in pbrt-v4); the shape is not emissive");
  }

  read_alpha(pl, float_textures_, spectrum_textures_, s_.diagnostics, sh);

  if (type == "curve") {
    read_curve(pl, loc, sh, s_.diagnostics);
  } else if (type == "plymesh" || type == "objmesh") {
    const ParsedParam* fp = pl.find("filename");
    if (!fp) throw SceneError(loc, fmt::format("Shape \"{}\" needs \"string filename\"", type));
    const std::string file = scene_path(pl.get_string("filename", ""), fp->value_loc, "mesh");
    sh.mesh = read_mesh_file(type, file, loc, monitor_, s_.diagnostics);
    if (type == "plymesh" && (pl.has("displacement") || pl.has("edgelength")))
      s_.diagnostics.warn(loc, "plymesh displacement is not supported (ignored)");
  } else if (!read_parametric_shape(type, pl, loc, monitor_, sh)) {
    // Unreachable: require_known_type refused unknown names, and every pbrt-v4 shape is read.
    s_.diagnostics.warn(loc, fmt::format("unsupported Shape \"{}\" ignored", type));
    pl.warn_unused(s_.diagnostics, fmt::format("Shape \"{}\"", type));  // each of its parameters, where it is
    return;
  }

  if (sh.type == ShapeDesc::Type::Curve && sh.material >= 0 &&
      s_.materials[std::size_t(sh.material)].type == MaterialDesc::Type::Subsurface)
    s_.diagnostics.warn(loc,
                        "a subsurface material on a curve: a curve encloses no volume a random walk could "
                        "cross (not supported; rendered as written, not meaningful)");
  if (sh.type == ShapeDesc::Type::Curve && sh.area_light) {
    s_.diagnostics.warn(loc,
                        "an area light on a curve is not supported (pbrt-v4 cannot sample curves either); the "
                        "curve is not emissive");
    sh.area_light.reset();
  }
  if (sh.type == ShapeDesc::Type::TriangleMesh) {
    try {
      validate_mesh(sh.mesh);
    } catch (const std::exception& e) {
      throw SceneError(loc, fmt::format("Shape \"{}\": invalid mesh: {}", type, e.what()));
    }
  }
  pl.warn_unused(s_.diagnostics, fmt::format("Shape \"{}\"", type));
  if (open_object_ >= 0)
    s_.objects[open_object_].shapes.push_back(std::move(sh));
  else
    s_.shapes.push_back(std::move(sh));
}

void SceneParser::object_begin(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc name_loc;
  std::string name = string_arg(ts, d, &name_loc);
  if (open_object_ >= 0)
    throw SceneError(loc, fmt::format("ObjectBegin \"{}\" inside the definition of \"{}\" (started at {}): objects "
                                      "cannot be nested",
                                      name, s_.objects[open_object_].name, s_.objects[open_object_].loc.str()));
  if (objects_.count(name))
    throw SceneError(name_loc, fmt::format("object \"{}\" is defined twice (first at {})", name,
                                           s_.objects[objects_[name]].loc.str()));
  // pbrt-v4: ObjectBegin implies AttributeBegin.
  blocks_.push_back({BlockKind::Object, gs_, loc});
  ObjectDesc obj;
  obj.name = name;
  obj.loc = loc;
  open_object_ = int(s_.objects.size());
  objects_[name] = open_object_;
  s_.objects.push_back(std::move(obj));
}

void SceneParser::object_end(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  if (open_object_ < 0) throw SceneError(loc, "ObjectEnd without a matching ObjectBegin");
  if (blocks_.empty() || blocks_.back().kind != BlockKind::Object)
    throw SceneError(loc, fmt::format("ObjectEnd while the block opened at {} is still open",
                                      blocks_.empty() ? std::string("?") : blocks_.back().loc.str()));
  gs_ = blocks_.back().saved;
  blocks_.pop_back();
  open_object_ = -1;
}

void SceneParser::object_instance(const Token& d, TokenStream& ts) {
  require_world(d, ts);
  const SourceLoc loc = ts.loc(d);
  SourceLoc name_loc;
  std::string name = string_arg(ts, d, &name_loc);
  if (open_object_ >= 0)
    throw SceneError(loc, fmt::format("ObjectInstance inside the definition of object \"{}\" is not allowed",
                                      s_.objects[open_object_].name));
  InstanceDesc inst;
  inst.object_to_world = gs_.ctm;
  inst.loc = loc;
  // pbrt-v4 resolves instance names after parsing, so an instance may precede its object.
  pending_instances_.push_back({name, s_.instances.size(), name_loc});
  s_.instances.push_back(inst);
}

}  // namespace dermis
