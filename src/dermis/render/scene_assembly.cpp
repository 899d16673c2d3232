#include "dermis/render/scene_assembly.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <type_traits>

#include "dermis/render/image.h"
#include "dermis/render/light_power_range.h"
#include "dermis/render/scene_extent.h"
#include "dermis/scene/shape_tessellation.h"
#include "dermis/scene/subsurface_params.h"
#include "dermis/spectral/cie_observer.h"

namespace dermis {

namespace {

// A similarity transform (rotation, translation, uniform scale) keeps a sphere a sphere.
bool similarity_scale(const Transform& t, float& scale) {
  Vec3d x = t.vector(Vec3d(1, 0, 0)), y = t.vector(Vec3d(0, 1, 0)), z = t.vector(Vec3d(0, 0, 1));
  double lx = length(x), ly = length(y), lz = length(z);
  scale = float(lx);
  double tol = 1e-6 * lx;
  return std::abs(lx - ly) < tol && std::abs(lx - lz) < tol && std::abs(dot(x, y)) < tol * lx &&
         std::abs(dot(x, z)) < tol * lx && std::abs(dot(y, z)) < tol * lx;
}

Material make_material(const MaterialDesc& d, [[maybe_unused]] Diagnostics& diag) {
  Material m;
  m.reflectance = d.reflectance.value;
  m.reflectance_texture = d.reflectance.texture;
  if (d.type == MaterialDesc::Type::Diffuse || d.type == MaterialDesc::Type::DiffuseTransmission ||
      d.type == MaterialDesc::Type::CoatedDiffuse)
    m.reflectance_data = d.reflectance.data;
  m.eta = d.eta;
  switch (d.type) {
    case MaterialDesc::Type::Diffuse:
      m.type = Material::Type::Diffuse;
      break;
    case MaterialDesc::Type::Dielectric:
      m.type = Material::Type::Dielectric;
      m.eta_data = d.eta_data;
      break;
    case MaterialDesc::Type::Conductor:
      m.type = Material::Type::Conductor;
      m.cond_eta_data = d.conductor_eta_data;
      m.cond_k_data = d.conductor_k_data;
      if (d.has_reflectance) {
        // pbrt-v4: a conductor given a reflectance r uses eta = 1 and k = 2 sqrt(r) / sqrt(1 - r).
        m.cond_eta = RGB(1);
        m.cond_k = conductor_k_from_reflectance(d.reflectance.value);  // per hit when textured: bsdf_at()
      } else {
        m.cond_eta = d.conductor_eta;
        m.cond_k = d.conductor_k;
      }
      break;
    case MaterialDesc::Type::Interface:
      m.type = Material::Type::Interface;
      break;
    case MaterialDesc::Type::CoatedDiffuse:
    case MaterialDesc::Type::CoatedConductor: {
      m.type = Material::Type::Coated;
      CoatedLayer& c = m.coat;
      c.eta = d.eta;
      c.interface_alpha_x = roughness_to_alpha(d.uroughness, d.remap_roughness);
      c.interface_alpha_y = roughness_to_alpha(d.vroughness, d.remap_roughness);
      c.thickness = d.thickness;
      c.albedo = d.albedo;
      c.g = d.g;
      m.thickness_texture = d.thickness_texture;
      m.g_texture = d.g_texture;
      m.albedo_texture = d.albedo_texture;
      c.max_depth = d.max_depth;
      c.n_samples = d.n_samples;
      if (d.type == MaterialDesc::Type::CoatedDiffuse) {
        c.base = CoatedLayer::Base::Diffuse;  // its reflectance at the hit: bsdf_at()
      } else {
        c.base = CoatedLayer::Base::Conductor;
        m.cond_eta_data = d.conductor_eta_data;
        m.cond_k_data = d.conductor_k_data;
        c.conductor_eta = d.conductor_eta;
        c.conductor_k = d.conductor_k;
        if (d.has_reflectance) {
          c.conductor_eta = RGB(1);  // as the conductor's "reflectance" above
          c.conductor_k = conductor_k_from_reflectance(d.reflectance.value);
        }
        c.base_alpha_x = roughness_to_alpha(d.conductor_uroughness, d.remap_roughness);
        c.base_alpha_y = roughness_to_alpha(d.conductor_vroughness, d.remap_roughness);
      }
      break;
    }
    case MaterialDesc::Type::DiffuseTransmission:
      m.type = Material::Type::DiffuseTransmission;
      m.transmittance = d.transmittance.value;
      m.transmittance_texture = d.transmittance.texture;
      m.transmittance_data = d.transmittance.data;
      m.scale = d.scale;
      break;
    case MaterialDesc::Type::Mix:
      m.type = Material::Type::Mix;
      m.mix[0] = d.mix_materials[0];
      m.mix[1] = d.mix_materials[1];
      m.amount = d.amount;
      m.amount_texture = d.amount_texture;
      break;
    case MaterialDesc::Type::Subsurface:
      // Completed by assemble_scene(), which needs the scene's media.
      m.type = Material::Type::Dielectric;
      break;
  }
  m.remap_roughness = d.remap_roughness;
  m.roughness_texture[0] = d.roughness_texture[0];
  m.roughness_texture[1] = d.roughness_texture[1];
  m.base_roughness_texture[0] = d.conductor_roughness_texture[0];
  m.base_roughness_texture[1] = d.conductor_roughness_texture[1];
  if (d.type == MaterialDesc::Type::Dielectric || d.type == MaterialDesc::Type::Conductor) {
    m.alpha_x = roughness_to_alpha(d.uroughness, d.remap_roughness);  // pbrt-v4: alpha = sqrt(r)
    m.alpha_y = roughness_to_alpha(d.vroughness, d.remap_roughness);
  }
  return m;
}

Texture make_texture(const TextureDesc& d) {
  Texture t;
  t.value = d.value;
  t.scale = d.scale;
  t.invert = d.invert;
  TextureMapping& m = t.mapping;
  m.kind = d.mapping == "spherical"     ? TextureMapping::Kind::Spherical
           : d.mapping == "cylindrical" ? TextureMapping::Kind::Cylindrical
           : d.mapping == "planar"      ? TextureMapping::Kind::Planar
           : d.mapping == "3d"          ? TextureMapping::Kind::Point3D
                                        : TextureMapping::Kind::UV;
  m.su = d.uscale;
  m.sv = d.vscale;
  m.du = d.udelta;
  m.dv = d.vdelta;
  m.texture_from_world = d.texture_from_world;
  m.vs = d.v1;
  m.vt = d.v2;
  t.base = d.base;
  t.value2 = d.value2;
  t.tex1 = d.tex1;
  t.tex2 = d.tex2;
  t.amount = d.amount;
  t.amount_texture = d.amount_texture;
  t.dir = d.dir;
  t.corners = d.corners;
  t.octaves = d.octaves;
  t.omega = d.roughness;
  t.variation = d.variation;
  t.wrap = d.wrap == "black" ? Texture::Wrap::Black : d.wrap == "clamp" ? Texture::Wrap::Clamp : Texture::Wrap::Repeat;
  switch (d.type) {
    case TextureDesc::Type::Constant:
      t.type = Texture::Type::Constant;
      break;
    case TextureDesc::Type::Scale:
      t.type = Texture::Type::Scale;
      break;
    case TextureDesc::Type::Checkerboard:
      t.type = Texture::Type::Checkerboard;
      break;
    case TextureDesc::Type::Mix:
      t.type = Texture::Type::Mix;
      break;
    case TextureDesc::Type::DirectionMix:
      t.type = Texture::Type::DirectionMix;
      break;
    case TextureDesc::Type::Bilerp:
      t.type = Texture::Type::Bilerp;
      break;
    case TextureDesc::Type::Dots:
      t.type = Texture::Type::Dots;
      break;
    case TextureDesc::Type::FBm:
      t.type = Texture::Type::FBm;
      break;
    case TextureDesc::Type::Wrinkled:
      t.type = Texture::Type::Wrinkled;
      break;
    case TextureDesc::Type::Windy:
      t.type = Texture::Type::Windy;
      break;
    case TextureDesc::Type::Marble:
      t.type = Texture::Type::Marble;
      break;
    case TextureDesc::Type::ImageMap: {
      t.type = Texture::Type::Image;
      Image img;
      try {
        img = read_image(d.filename);
      } catch (const std::exception& e) {
        throw SceneError(d.loc, e.what());
      }
      auto data = std::make_shared<ImageData>();
      data->width = img.width;
      data->height = img.height;
      data->rgb = std::move(img.pixels);
      t.image = std::move(data);
      break;
    }
  }
  return t;
}

// Converts a shape description into the renderer's shape, positioned by `xf`.
Shape make_shape(const ShapeDesc& d, const Transform& xf, int default_material) {
  Shape s;
  s.material = d.material >= 0 ? d.material : default_material;
  s.inside_medium = d.inside_medium;
  s.outside_medium = d.outside_medium;
  s.has_medium_interface = d.has_medium_interface;
  // The parser's reverse_orientation already includes the handedness of the shape's
  // transform (pbrt's ReverseOrientation xor SwapsHandedness).
  s.flip_normals = d.reverse_orientation;
  s.alpha = d.alpha;
  s.alpha_texture = d.alpha_texture;
  const bool reversed_by_user = d.reverse_orientation != xf.swaps_handedness();
  float scale;
  if (d.type == ShapeDesc::Type::Sphere && similarity_scale(xf, scale)) {
    s.type = Shape::Type::Sphere;
    s.center = xf.point(Vec3(0, 0, 0));
    s.radius = d.radius * scale;
    return s;
  }
  if (d.type == ShapeDesc::Type::Curve) {
    s.type = Shape::Type::Curve;
    s.curve_kind = d.curve.kind == CurveKind::Cylinder ? Shape::CurveKind::Cylinder
                   : d.curve.kind == CurveKind::Ribbon ? Shape::CurveKind::Ribbon
                                                       : Shape::CurveKind::Flat;
    s.positions = d.curve.points;
    for (Vec3& p : s.positions) p = xf.point(p);
    // The width is in object space: scaled by the cube root of the transform's volume
    // scale (exact for a similarity; under a non-uniform scale, a round curve stays round).
    const Vec3 x = xf.vector(Vec3(1, 0, 0)), y = xf.vector(Vec3(0, 1, 0)), z = xf.vector(Vec3(0, 0, 1));
    const float width_scale = std::cbrt(std::abs(dot(x, cross(y, z))));
    s.curve_radii.resize(d.curve.widths.size());
    for (std::size_t i = 0; i < d.curve.widths.size(); ++i) s.curve_radii[i] = 0.5f * d.curve.widths[i] * width_scale;
    s.normals = d.curve.normals;
    for (Vec3& n : s.normals) n = normalize(xf.normal(n));
    return s;
  }
  s.type = Shape::Type::Mesh;
  if (d.type == ShapeDesc::Type::Sphere) {
    // An ellipsoid: tessellated finely, with pbrt's uv and the sphere's normals (transformed below).
    TriangleMeshDesc m = tessellate_sphere_part(d.radius, -d.radius, d.radius, 360);
    s.positions = std::move(m.positions);
    s.indices = std::move(m.indices);
    s.normals = std::move(m.normals);
    s.uvs = std::move(m.uvs);
  } else {
    s.positions = d.mesh.positions;
    s.indices = d.mesh.indices;
    s.normals = d.mesh.normals;
    s.uvs = d.mesh.uvs;
  }
  for (Vec3& p : s.positions) p = xf.point(p);
  for (Vec3& n : s.normals) {
    n = normalize(xf.normal(n));
    if (reversed_by_user) n = -n;  // pbrt-v4 flips the vertex normals of ReverseOrientation meshes
  }
  return s;
}

// Whether the scene has point, spot or distant lights.
bool has_delta_lights(const SceneDesc& desc) {
  for (const LightDesc& l : desc.lights)
    if (l.type != LightDesc::Type::Infinite) return true;
  return false;
}

// The walk's boundary in this scene. A material given by its coefficients whose
// "boundary" is not given has `dielectric` (default_walk_boundary), unless the scene has
// delta lights: their light enters a medium behind a smooth dielectric along single
// refracted paths that no walk samples, and the object would not see them: `diffuse`.
SubsurfaceParams::Boundary walk_boundary_in_scene(const SubsurfaceParams& sp, bool delta_lights) {
  if (sp.boundary_given || sp.boundary != SubsurfaceParams::Boundary::Dielectric || !delta_lights) return sp.boundary;
  return SubsurfaceParams::Boundary::Diffuse;
}

// One line when the scene's random walks did not all get the boundary of their
// parametrisation's default (materials given one by coefficients, one by reflectance +
// mfp; or coefficients beside delta lights): which boundary each got and why.
void note_default_boundaries(const SceneDesc& desc, bool delta_lights, Diagnostics& diag) {
  std::string list;
  bool dielectric = false, diffuse = false, for_delta_lights = false;
  for (const MaterialDesc& md : desc.materials) {
    const SubsurfaceParams& sp = md.subsurface;
    if (md.type != MaterialDesc::Type::Subsurface || sp.method != SubsurfaceParams::Method::RandomWalk ||
        sp.boundary_given)
      continue;
    const SubsurfaceParams::Boundary b = walk_boundary_in_scene(sp, delta_lights);
    const bool exact = b == SubsurfaceParams::Boundary::Dielectric;
    (exact ? dielectric : diffuse) = true;
    for_delta_lights = for_delta_lights || b != sp.boundary;
    list += fmt::format("{}{} {} ({}{})", list.empty() ? "" : ", ", sp.loc.str(), exact ? "dielectric" : "diffuse",
                        sp.coefficient_given() ? "coefficients" : "reflectance + mfp",
                        b != sp.boundary ? ", beside delta lights" : "");
  }
  if ((dielectric && diffuse) || for_delta_lights)
    diag.warnings.push_back(fmt::format(
        "note: each subsurface material's random walk got the boundary of its parametrisation (docs/materials.md, "
        "\"Which boundary\"; \"string boundary\" chooses){}: {}",
        for_delta_lights ? "; coefficients beside point, spot or distant lights get the diffuse one, whose exits "
                           "sample them"
                         : "",
        list));
}

// Subsurface materials: the parameters now, the methods at preparation. The
// `volumetric` method is the brute-force reference: the material becomes a smooth
// dielectric filled with the homogeneous medium it describes, rendered by the
// volumetric path tracer itself (its coefficients too are resolved at preparation), or
// with its grid interior medium.
// Returns, per material, the medium inside it (-1: none).
std::vector<int> resolve_subsurface_materials(const SceneDesc& desc, RenderScene& sc) {
  std::vector<int> subsurface_medium(sc.materials.size(), -1);
  const bool delta_lights = has_delta_lights(desc);
  for (std::size_t i = 0; i < desc.materials.size(); ++i) {
    const MaterialDesc& md = desc.materials[i];
    if (md.type != MaterialDesc::Type::Subsurface) continue;
    const SubsurfaceParams& sp = md.subsurface;
    Material& m = sc.materials[i];
    if (sp.method != SubsurfaceParams::Method::Volumetric) {
      m.type = Material::Type::Subsurface;
      m.subsurface = int(sc.subsurface_params.size());
      sc.subsurface_params.push_back(sp);
      sc.subsurface_params.back().boundary = walk_boundary_in_scene(sp, delta_lights);
      continue;
    }
    m.type = Material::Type::Dielectric;
    m.eta = sp.eta;
    m.alpha_x = roughness_to_alpha(sp.uroughness, sp.remap_roughness);
    m.alpha_y = roughness_to_alpha(sp.vroughness, sp.remap_roughness);
    // A textured roughness: per hit, as the walk's boundary (clamped alike:
    // subsurface/boundary_roughness.h).
    m.roughness_texture[0] = m.roughness_texture[1] = sp.roughness_texture;
    m.remap_roughness = sp.remap_roughness;
    if (sp.interior_medium >= 0) {  // a grid medium fills it (SubsurfaceParams::interior)
      subsurface_medium[i] = sp.interior_medium;
      continue;
    }
    subsurface_medium[i] = int(sc.media.size());
    sc.volumetric_media.push_back({sp, subsurface_medium[i], {}, {}});
    sc.media.push_back(HomogeneousMedium{});
  }
  return subsurface_medium;
}

// Converts a shape description into the renderer's shape, with the medium of a
// `volumetric` subsurface material inside it.
Shape make_scene_shape(const ShapeDesc& d, int default_material, const std::vector<int>& subsurface_medium) {
  Shape s = make_shape(d, d.object_to_world, default_material);
  check_shape_extent(s, Transform(), d.loc);
  if (s.material < int(subsurface_medium.size()) && subsurface_medium[s.material] >= 0) {
    s.inside_medium = subsurface_medium[s.material];
    s.outside_medium = d.outside_medium;
    s.has_medium_interface = true;
  }
  return s;
}

// The lights of an emitting shape: one sphere light, or one light per triangle.
void add_area_lights(Shape& s, const ShapeDesc& d, int shape_id, std::vector<Light>& lights) {
  RGB L = d.area_light->L * d.area_light->scale;
  if (L.is_black()) return;
  auto with_data = [&](Light& l) {
    l.spectrum_data = d.area_light->L_data;
    l.spectrum_data_rgb = d.area_light->L;
  };
  s.first_light = int(lights.size());
  if (s.type == Shape::Type::Sphere) {
    Light l;
    l.type = Light::Type::Sphere;
    l.emission = L;
    with_data(l);
    l.two_sided = d.area_light->two_sided;
    l.center = s.center;
    l.radius = s.radius;
    l.inward = s.flip_normals;
    l.shape = shape_id;
    l.medium = d.outside_medium;
    lights.push_back(l);
  } else {
    for (std::size_t t = 0; t < s.indices.size() / 3; ++t) {
      Light l;
      l.type = Light::Type::Triangle;
      l.emission = L;
      with_data(l);
      l.two_sided = d.area_light->two_sided;
      l.p0 = s.positions[s.indices[3 * t]];
      l.p1 = s.positions[s.indices[3 * t + 1]];
      l.p2 = s.positions[s.indices[3 * t + 2]];
      l.area = 0.5f * length(cross(l.p1 - l.p0, l.p2 - l.p0));
      l.shape = shape_id;
      l.prim = int(t);
      if (s.normals.empty()) {
        l.flat = true;
        l.normal = s.triangle_normal(int(t), 0, 0);
      }
      // Degenerate triangles get a zero selection probability through their power.
      lights.push_back(l);
    }
  }
  check_light_power(std::span(lights).subspan(std::size_t(s.first_light)), d.loc);
}

// The shapes outside any object instance, with their area lights; returns their ids.
std::vector<int> add_top_level_shapes(const SceneDesc& desc, int default_material,
                                      const std::vector<int>& subsurface_medium, RenderScene& sc) {
  std::vector<int> top_level;
  for (const ShapeDesc& d : desc.shapes) {
    Shape s = make_scene_shape(d, default_material, subsurface_medium);
    const int id = int(sc.shapes.size());
    if (d.area_light) add_area_lights(s, d, id, sc.lights);
    if (sc.materials[s.material].is_interface()) sc.has_interfaces = true;
    sc.shapes.push_back(std::move(s));
    top_level.push_back(id);
  }
  return top_level;
}

// An instanced object's shapes, and their bounds in object space (for the instances'
// extent check).
struct ObjectShapes {
  std::vector<int> ids;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void grow(const Vec3& p) {
    lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
    hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
  }
  bool empty_bounds() const { return !(lo.x <= hi.x); }
};

ObjectShapes add_object_shapes(const ObjectDesc& o, int default_material, const std::vector<int>& subsurface_medium,
                               RenderScene& sc, Diagnostics& diag) {
  ObjectShapes object;
  for (const ShapeDesc& d : o.shapes) {
    if (d.area_light)
      diag.warn(d.loc, "area lights inside object instances are not supported (as in pbrt-v4); ignored");
    Shape s = make_scene_shape(d, default_material, subsurface_medium);
    if (s.type == Shape::Type::Sphere) {
      object.grow(s.center - Vec3(s.radius, s.radius, s.radius));
      object.grow(s.center + Vec3(s.radius, s.radius, s.radius));
    }
    for (const Vec3& p : s.positions) object.grow(p);
    if (sc.materials[s.material].is_interface()) sc.has_interfaces = true;
    object.ids.push_back(int(sc.shapes.size()));
    sc.shapes.push_back(std::move(s));
  }
  return object;
}

// The instances, checked against their object's extent; each shape learns its object.
std::vector<Instance> make_instances(const SceneDesc& desc, const std::vector<ObjectShapes>& objects, RenderScene& sc) {
  std::vector<Instance> instances;
  for (const InstanceDesc& i : desc.instances) {
    if (i.object >= 0 && std::size_t(i.object) < objects.size() && !objects[std::size_t(i.object)].empty_bounds())
      check_box_extent(objects[std::size_t(i.object)].lo, objects[std::size_t(i.object)].hi, i.object_to_world, i.loc,
                       "the instanced object");
    instances.push_back({i.object, i.object_to_world});
  }
  for (std::size_t o = 0; o < objects.size(); ++o)
    for (int id : objects[o].ids) sc.shapes[id].instance = int(o);
  return instances;
}

// The scene's geometry in Embree: the top-level shapes and the instanced objects.
void build_geometry(const std::vector<int>& top_level, const std::vector<ObjectShapes>& objects,
                    const std::vector<Instance>& instances, RenderScene& sc, const LoadMonitor* monitor) {
  std::vector<std::vector<int>> object_ids;
  for (const ObjectShapes& o : objects) object_ids.push_back(o.ids);
  sc.embree = std::make_unique<EmbreeScene>();
  // Alpha textures are float textures: their first channel.
  const AlphaTextureLookup alpha_lookup{
      [](const void* textures, int texture, Vec2 uv) {
        return evaluate_texture(*static_cast<const std::vector<Texture>*>(textures), texture, uv).r();
      },
      &sc.textures};
  sc.embree->build(sc.shapes, top_level, object_ids, instances, alpha_lookup, monitor);
  sc.embree->set_uv_needed(!sc.textures.empty());  // only textures read (u, v)
}

// An environment map light's map, scaled as the file asks; returns the emission scale.
float load_environment_map(const LightDesc& d, Light& l) {
  Image img;
  try {
    img = read_image(d.filename);
  } catch (const std::exception& ex) {
    throw SceneError(d.loc, ex.what());
  }
  const auto mapping = d.latlong ? EnvironmentMap::Mapping::LatLong : EnvironmentMap::Mapping::EqualArea;
  float scale = d.scale;
  try {
    if (d.illuminance >= 0) {
      // pbrt-v4: scaled so that a surface facing up (light-space +z) receives it.
      const EnvironmentMap unit(img.width, img.height, img.pixels, d.light_to_world, 1, mapping);
      if (unit.upper_hemisphere_illuminance() > 0) scale *= d.illuminance / unit.upper_hemisphere_illuminance();
    }
    l.environment = std::make_shared<EnvironmentMap>(img.width, img.height, std::move(img.pixels), d.light_to_world,
                                                     scale, mapping);
  } catch (const std::invalid_argument& ex) {
    throw SceneError(d.loc, fmt::format("infinite light \"{}\": {}", d.filename, ex.what()));
  }
  return scale;
}

void make_infinite_light(const LightDesc& d, Light& l) {
  l.type = Light::Type::Infinite;
  if (!d.filename.empty()) {
    l.emission = RGB(load_environment_map(d, l));
  } else if (d.illuminance >= 0 && d.spectrum.luminance() > 0) {
    // pbrt-v4: uniform radiance L gives the illuminance pi L on any surface.
    l.emission = d.spectrum * (d.scale * d.illuminance / (kPi * d.spectrum.luminance()));
  }
  if (!d.portal.empty()) {
    // pbrt-v4: Frame::FromXY(p03, p01), its z = p03 x p01, in world space.
    const Vec3 p0 = d.light_to_world.point(d.portal[0]);
    const Vec3 z = cross(d.light_to_world.point(d.portal[3]) - p0, d.light_to_world.point(d.portal[1]) - p0);
    if (!(length(z) > 0)) throw SceneError(d.loc, "infinite light \"portal\": the rectangle has no area");
    l.portal_normal = normalize(z);
  }
}

// A light that is not a shape's: point, spot, distant or infinite.
Light make_light(const LightDesc& d) {
  Light l;
  l.medium = d.medium;
  l.emission = d.spectrum * d.scale;
  if (d.filename.empty()) {
    l.spectrum_data = d.spectrum_data;
    l.spectrum_data_rgb = d.spectrum;
  }
  switch (d.type) {
    case LightDesc::Type::Point:
      l.type = Light::Type::Point;
      l.position = d.light_to_world.point(d.from);
      check_scene_point(l.position, d.loc, "the point light");
      break;
    case LightDesc::Type::Spot: {
      l.type = Light::Type::Spot;
      l.position = d.light_to_world.point(d.from);
      Vec3 axis = d.light_to_world.point(d.to) - l.position;
      if (length(axis) == 0) throw SceneError(d.loc, "spot light: 'from' and 'to' coincide");
      l.direction = normalize(axis);
      l.cos_falloff_end = std::cos(d.cone_angle * kPi / 180);
      l.cos_falloff_start = std::cos((d.cone_angle - d.cone_delta) * kPi / 180);
      break;
    }
    case LightDesc::Type::Distant: {
      l.type = Light::Type::Distant;
      // pbrt-v4: the illuminance on a surface facing the light is L's luminance.
      if (d.illuminance >= 0 && d.spectrum.luminance() > 0)
        l.emission = d.spectrum * (d.scale * d.illuminance / d.spectrum.luminance());
      Vec3 w = d.light_to_world.vector(d.from - d.to);
      if (length(w) == 0) throw SceneError(d.loc, "distant light: 'from' and 'to' coincide");
      l.direction = normalize(w);
      break;
    }
    case LightDesc::Type::Infinite:
      make_infinite_light(d, l);
      break;
  }
  // The parser bounds "L" x "scale"; "illuminance" normalises after it and may still overflow.
  if (d.illuminance >= 0 && !l.emission.is_finite())
    throw SceneError(d.loc, fmt::format("the light's emission is beyond the range of 32-bit floats (\"scale\" {:g}, "
                                        "\"illuminance\" {:g}): lower them",
                                        double(d.scale), double(d.illuminance)));
  check_light_power(std::span(&l, 1), d.loc);
  return l;
}

// A medium is enclosed when it appears only inside non-interface boundaries.
void mark_media_that_see_lights(RenderScene& sc) {
  sc.medium_sees_lights.assign(sc.media.size(), 0);
  auto open_medium = [&](int m) {
    if (m >= 0) sc.medium_sees_lights[m] = 1;
  };
  open_medium(sc.camera_medium);
  for (const Light& l : sc.lights) open_medium(l.medium);
  for (const Shape& s : sc.shapes) {
    if (!s.has_medium_interface) continue;
    open_medium(s.outside_medium);
    if (sc.materials[s.material].is_interface() || s.first_light >= 0) open_medium(s.inside_medium);
  }
}

// Subsurface objects (render_scene.h): the shapes sharing a subsurface material form
// one object (pbrt-v4's rule), and so do all shapes of the materials that name the
// same "sssgroup"; every other shape is an object of its own (a boundary a walk inside
// another object reflects from), except index-matched interfaces (-1: passed through).
// Shapes reached through an instance are told apart by the instance (object_tracer.h).
void group_subsurface_objects(RenderScene& sc) {
  std::map<std::string, int> object_of_key;
  sc.object_of_shape.resize(sc.shapes.size());
  for (std::size_t i = 0; i < sc.shapes.size(); ++i) {
    const Material& m = sc.materials[sc.shapes[i].material];
    std::string key = fmt::format("shape {}", i);
    if (m.type == Material::Type::Subsurface) {
      const std::string& group = sc.subsurface_params[m.subsurface].group;
      key = group.empty() ? fmt::format("material {}", sc.shapes[i].material) : "group " + group;
    }
    auto [it, added] = object_of_key.try_emplace(key, int(object_of_key.size()));
    sc.object_of_shape[i] = m.is_interface() ? -1 : it->second;  // walks pass through interfaces
  }
}

// A nanovdb medium's grids, read from its file (errors at the file name), and its box.
void load_nanovdb_grids(const MediumDesc& d, GridMedium& g) {
  try {
    g.vdb_density = NanoVdbGrid::load(d.filename, d.grid_name);
    g.vdb_temperature = NanoVdbGrid::load(d.filename, d.temperature_name, true);
  } catch (const std::runtime_error& e) {
    throw SceneError(d.filename_loc, fmt::format("nanovdb medium \"{}\": {}: {}", d.name, d.filename, e.what()));
  }
  g.p0 = g.vdb_density->world_min();
  g.p1 = g.vdb_density->world_max();
  if (g.vdb_temperature) {  // pbrt-v4's bounds: the union of the two grids'
    g.p0 = min(g.p0, g.vdb_temperature->world_min());
    g.p1 = max(g.p1, g.vdb_temperature->world_max());
  }
  g.vdb_le_scale = d.Lescale;
  for (int a = 0; a < 3; ++a)
    if (!(g.p1[a] > g.p0[a]))
      throw SceneError(d.filename_loc,
                       fmt::format("nanovdb medium \"{}\": {}: the grid's box has no volume", d.name, d.filename));
}

// A grid medium of the file, its majorants computed.
GridMedium make_grid_medium(const MediumDesc& d) {
  GridMedium g;
  g.kind = d.type == "rgbgrid"   ? GridMedium::Kind::RGBGrid
           : d.type == "cloud"   ? GridMedium::Kind::Cloud
           : d.type == "nanovdb" ? GridMedium::Kind::NanoVDB
                                 : GridMedium::Kind::Density;
  g.medium_from_world = d.medium_to_world.inverse();
  g.p0 = d.p0;
  g.p1 = d.p1;
  // Each grid shares the description's values (a grid exists once in memory).
  auto grid = [&d](auto& out, const std::shared_ptr<const FloatArray>& values) {
    if (values) out = std::decay_t<decltype(out)>(d.nx, d.ny, d.nz, values);
  };
  grid(g.density, d.density);
  grid(g.sigma_a_grid, d.sigma_a_grid);
  grid(g.sigma_s_grid, d.sigma_s_grid);
  grid(g.le_grid, d.Le_grid);
  // pbrt-v4 divides neither an rgbgrid's Le nor a temperature's blackbody by its photometric
  // value, as it does every other emission (media.cpp): they record kPbrtV4CieYIntegral times
  // their colour (cie_observer.h).
  g.le_grid_scale = d.Lescale * kPbrtV4CieYIntegral;
  g.blackbody_scale = kPbrtV4CieYIntegral;
  g.Le = d.type == "uniformgrid" ? d.Le : RGB(0);
  g.Le_data = d.Le_data;
  grid(g.temperature, d.temperature);
  g.temperature_offset = d.temperature_offset;
  g.temperature_scale = d.temperature_scale;
  if (!d.le_scale_grid)  // pbrt-v4's default: one sample (a tent over the box)
    g.le_scale = VoxelGrid<float>(1, 1, 1, make_shared_floats({1.0f}));
  else
    grid(g.le_scale, d.le_scale_grid);
  g.cloud_density = d.cloud_density;
  g.wispiness = d.wispiness;
  g.frequency = d.frequency;
  if (g.kind == GridMedium::Kind::NanoVDB) load_nanovdb_grids(d, g);
  g.build_majorants();
  return g;
}

}  // namespace

std::unique_ptr<RenderScene> assemble_scene(const SceneDesc& desc, Diagnostics& diag, const LoadMonitor* monitor) {
  auto sc = std::make_unique<RenderScene>();
  sc->film = desc.film;
  sc->settings = desc.settings;
  sc->camera_medium = desc.camera.medium;
  sc->camera = Camera(desc.camera.camera_to_world, desc.camera.fov, desc.camera.lens_radius, desc.camera.focal_distance,
                      desc.film.xres, desc.film.yres, desc.camera.screen_window ? &*desc.camera.screen_window : nullptr,
                      desc.camera.orthographic ? Camera::Projection::Orthographic : Camera::Projection::Perspective);
  check_scene_point(desc.camera.camera_to_world.point(Vec3(0, 0, 0)), desc.camera.loc, "the camera");

  for (const TextureDesc& t : desc.textures) sc->textures.push_back(make_texture(t));
  sc->spectra = desc.spectra;
  for (const MaterialDesc& m : desc.materials) sc->materials.push_back(make_material(m, diag));
  const int default_material = int(sc->materials.size());
  sc->materials.push_back(Material{});  // pbrt's default: diffuse, reflectance 0.5

  for (const MediumDesc& m : desc.media) {
    // Emission (Le) is not rendered: the parser has warned about it, once.
    const bool rgb_grid = m.type == "rgbgrid";  // its colours are in its grids
    sc->media.push_back(HomogeneousMedium::from_coefficients(rgb_grid ? RGB(1) : m.sigma_a,
                                                             rgb_grid ? RGB(1) : m.sigma_s, m.scale, m.g));
    sc->medium_spectra.push_back({m.sigma_a_data, m.sigma_s_data, m.scale});
    if (m.type == "homogeneous")
      sc->medium_emission.push_back({m.Le * m.Lescale, m.Le_data, m.Lescale});
    else
      sc->medium_emission.push_back({});
    sc->grid_of_medium.push_back(m.type == "homogeneous" ? -1 : int(sc->grid_media.size()));
    if (m.type != "homogeneous") sc->grid_media.push_back(make_grid_medium(m));
  }
  const std::vector<int> subsurface_medium = resolve_subsurface_materials(desc, *sc);
  note_default_boundaries(desc, has_delta_lights(desc), diag);

  const std::vector<int> top_level = add_top_level_shapes(desc, default_material, subsurface_medium, *sc);
  std::vector<ObjectShapes> objects;
  for (const ObjectDesc& o : desc.objects)
    objects.push_back(add_object_shapes(o, default_material, subsurface_medium, *sc, diag));
  sc->interface_shape.resize(sc->shapes.size());
  for (std::size_t i = 0; i < sc->shapes.size(); ++i)
    sc->interface_shape[i] = sc->materials[sc->shapes[i].material].is_interface();
  const std::vector<Instance> instances = make_instances(desc, objects, *sc);
  build_geometry(top_level, objects, instances, *sc, monitor);

  for (const LightDesc& d : desc.lights) {
    if (d.type == LightDesc::Type::Infinite) sc->infinite_lights.push_back(int(sc->lights.size()));
    sc->lights.push_back(make_light(d));
  }
  mark_media_that_see_lights(*sc);
  // Light selection (lights/light_selection.h): by each light's importance at the
  // shading point with few lights, by power with many.
  sc->light_selection = LightSelection(sc->lights, sc->embree->bounds_radius());
  group_subsurface_objects(*sc);
  return sc;
}

}  // namespace dermis
