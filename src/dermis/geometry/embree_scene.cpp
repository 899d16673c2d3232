#include "dermis/geometry/embree_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dermis {

namespace {

void embree_error(void*, RTCError code, const char* str) {
  throw std::runtime_error(fmt::format("Embree error {}: {}", int(code), str ? str : ""));
}

// (u, v) at a hit: interpolated vertex uvs, pbrt's default triangle parameterisation, or
// the sphere's (phi / 2 pi, 1 - theta / pi) from the direction `l` (unit, object space).
Vec2 surface_uv(const Shape& s, unsigned prim, float b1, float b2, Vec3 l) {
  if (s.type == Shape::Type::Mesh) {
    if (s.uvs.empty()) return Vec2(b1 + b2, b2);  // pbrt: (0,0), (1,0), (1,1) at the three vertices
    const uint32_t* tri = &s.indices[3 * std::size_t(prim)];
    return s.uvs[tri[0]] * (1 - b1 - b2) + s.uvs[tri[1]] * b1 + s.uvs[tri[2]] * b2;
  }
  const float theta = std::acos(std::clamp(l.z, -1.0f, 1.0f));
  float phi = std::atan2(l.y, l.x);
  if (phi < 0) phi += 2 * kPi;
  return Vec2(phi * kInv2Pi, 1 - theta * kInvPi);  // pbrt-v4: v = 0 at z = -r, 1 at z = +r
}

// Embree intersection and occlusion filter of the geometries with alpha: rejects the
// hits alpha_cuts_hit cuts away.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const EmbreeScene::AlphaGeometry*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    RTCHitN* hit = args->hit;
    RTCRayN* ray = args->ray;
    const unsigned N = args->N;
    float alpha = g->shape->alpha;
    const unsigned prim = RTCHitN_primID(hit, N, i);
    if (g->shape->alpha_texture >= 0) {
      const Vec3 ng(RTCHitN_Ng_x(hit, N, i), RTCHitN_Ng_y(hit, N, i), RTCHitN_Ng_z(hit, N, i));
      const float l = length(ng);
      const Vec2 uv = surface_uv(*g->shape, prim, RTCHitN_u(hit, N, i), RTCHitN_v(hit, N, i), l > 0 ? ng / l : ng);
      alpha = g->lookup.evaluate(g->lookup.context, g->shape->alpha_texture, uv);
    }
    if (alpha >= 1) continue;
    const Vec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
    const Vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    const float hash = alpha <= 0 ? 0 : alpha_hash(o, d, RTCRayN_tfar(ray, N, i), RTCHitN_geomID(hit, N, i), prim);
    if (alpha_cuts_hit(alpha, hash)) args->valid[i] = 0;
  }
}

}  // namespace

EmbreeScene::EmbreeScene() {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("could not create the Embree device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
}

EmbreeScene::~EmbreeScene() {
  for (RTCScene s : object_scenes_) rtcReleaseScene(s);
  if (scene_) rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

RTCScene EmbreeScene::make_scene(const std::vector<int>& shape_ids, std::vector<int>& geom_to_shape) {
  RTCScene scene = rtcNewScene(device_);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  for (int id : shape_ids) {
    const Shape& s = (*shapes_)[id];
    RTCGeometry g;
    if (s.type == Shape::Type::Mesh) {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), s.positions.size()));
      for (std::size_t i = 0; i < s.positions.size(); ++i) {
        v[3 * i] = s.positions[i].x;
        v[3 * i + 1] = s.positions[i].y;
        v[3 * i + 2] = s.positions[i].z;
      }
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), s.indices.size() / 3));
      for (std::size_t i = 0; i < s.indices.size(); ++i) idx[i] = s.indices[i];
    } else {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      v[0] = s.center.x;
      v[1] = s.center.y;
      v[2] = s.center.z;
      v[3] = s.radius;
    }
    if (s.has_alpha()) {
      alpha_geometries_.push_back(std::make_unique<AlphaGeometry>(AlphaGeometry{&s, alpha_lookup_}));
      rtcSetGeometryUserData(g, alpha_geometries_.back().get());
      rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
      rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
    }
    rtcCommitGeometry(g);
    unsigned gid = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    if (geom_to_shape.size() <= gid) geom_to_shape.resize(gid + 1, -1);
    geom_to_shape[gid] = id;
  }
  rtcCommitScene(scene);
  return scene;
}

void EmbreeScene::build(const std::vector<Shape>& shapes, const std::vector<int>& top_level,
                        const std::vector<std::vector<int>>& objects, const std::vector<Instance>& instances,
                        AlphaTextureLookup alpha) {
  shapes_ = &shapes;
  alpha_lookup_ = alpha;
  for (const Shape& s : shapes)
    if (s.alpha_texture >= 0 && !alpha.evaluate)
      throw std::invalid_argument("EmbreeScene::build: a shape has an alpha texture but no texture lookup was given");
  instances_ = instances;
  object_geom_shape_.assign(objects.size(), {});
  for (std::size_t o = 0; o < objects.size(); ++o)
    object_scenes_.push_back(make_scene(objects[o], object_geom_shape_[o]));

  top_geom_shape_.clear();
  scene_ = make_scene(top_level, top_geom_shape_);
  // make_scene committed the scene; instances are attached and the scene committed again.
  top_geom_instance_.assign(top_geom_shape_.size(), -1);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, object_scenes_[instances[k].object]);
    float xfm[12];  // 3x4 column-major
    const Mat4& m = instances[k].object_to_world.matrix();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) xfm[c * 3 + r] = float(m.m[r][c]);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(g);
    unsigned gid = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    if (top_geom_instance_.size() <= gid) {
      top_geom_instance_.resize(gid + 1, -1);
      top_geom_shape_.resize(gid + 1, -1);
    }
    top_geom_instance_[gid] = int(k);
  }
  rtcCommitScene(scene_);

  RTCBounds b;
  rtcGetSceneBounds(scene_, &b);
  if (b.lower_x > b.upper_x) {
    center_ = {0, 0, 0};
    radius_ = 0;
  } else {
    Vec3 lo{b.lower_x, b.lower_y, b.lower_z}, hi{b.upper_x, b.upper_y, b.upper_z};
    center_ = (lo + hi) * 0.5f;
    radius_ = length(hi - center_);
  }
}

static void init_ray(RTCRay& r, const Ray& ray) {
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = 0;
  r.tfar = ray.tmax;
  r.time = 0;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
}

bool EmbreeScene::intersect(const Ray& ray, SurfaceHit& hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  init_ray(rh.ray, ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  fill_hit(rh, ray, hit);
  return true;
}

bool EmbreeScene::occluded(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  init_ray(r, ray);
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0;
}

void EmbreeScene::fill_hit(const RTCRayHit& rh, const Ray& ray, SurfaceHit& hit) const {
  const Instance* inst = nullptr;
  int shape_id;
  hit.instance = -1;
  if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
    hit.instance = top_geom_instance_[rh.hit.instID[0]];
    inst = &instances_[hit.instance];
    shape_id = object_geom_shape_[inst->object][rh.hit.geomID];
  } else {
    shape_id = top_geom_shape_[rh.hit.geomID];
  }
  const Shape& s = (*shapes_)[shape_id];
  hit.t = rh.ray.tfar;
  hit.shape = shape_id;
  hit.prim = int(rh.hit.primID);
  Vec3 p, ng, ns;
  if (s.type == Shape::Type::Mesh && s.normals.empty() && s.uvs.empty()) {
    // Everything from Embree's own hit record: reading the shape's index and vertex arrays
    // missed the cache on most walk steps (three quarters of this function's time on a
    // 100k-triangle mesh). The point is on the ray (its error, a few ulps of |o| + t, is far
    // below offset_ray_origin's 1e-4 |p|); Embree's Ng is cross(p1 - p0, p2 - p0) in the
    // shape's own space, as Shape::triangle_normal (tested: EmbreeScene.*).
    ng = normalize(Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    if (s.flip_normals) ng = -ng;
    if (inst) ng = normalize(inst->object_to_world.normal(ng));
    hit.p = ray.o + ray.d * hit.t;
    hit.ng = ng;
    hit.ns = ng;
    hit.uv = Vec2(rh.hit.u + rh.hit.v, rh.hit.v);  // pbrt's default parameterisation, as below
    return;
  }
  if (s.type == Shape::Type::Mesh) {
    const uint32_t* tri = &s.indices[3 * rh.hit.primID];
    float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
    p = s.positions[tri[0]] * b0 + s.positions[tri[1]] * b1 + s.positions[tri[2]] * b2;
    ng = s.triangle_normal(hit.prim, b1, b2, &ns);
    hit.uv = surface_uv(s, rh.hit.primID, b1, b2, Vec3());
  } else {
    Vec3 o = inst ? inst->object_to_world.inverse().point(ray.o) : ray.o;
    Vec3 d = inst ? inst->object_to_world.inverse().vector(ray.d) : ray.d;
    Vec3 l = normalize(o + d * hit.t - s.center);
    // Re-project onto the sphere to remove the error of o + t d.
    p = s.center + l * s.radius;
    ng = s.flip_normals ? -l : l;
    ns = ng;
    hit.uv = uv_needed_ ? surface_uv(s, 0, 0, 0, l) : Vec2(0, 0);
  }
  if (inst) {
    p = inst->object_to_world.point(p);
    ng = normalize(inst->object_to_world.normal(ng));
    ns = normalize(inst->object_to_world.normal(ns));
  }
  hit.p = p;
  hit.ng = ng;
  hit.ns = ns;
}

}  // namespace dermis
