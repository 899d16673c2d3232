#include "dermis/geometry/embree_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "dermis/core/frame.h"

namespace dermis {

namespace {

void embree_error(void*, RTCError code, const char* str) {
  if (code == RTC_ERROR_CANCELLED) return;  // a build stopped by its progress callback: commit() throws Interrupted
  throw std::runtime_error(fmt::format("Embree error {}: {}", int(code), str ? str : ""));
}

// (u, v) at a hit: interpolated vertex uvs, pbrt's default triangle parameterisation, the
// sphere's (phi / 2 pi, 1 - theta / pi) from the direction `l` (unit, object space), or a
// curve's (u along the segment, v across it from Embree's -1..1 to pbrt-v4's 0..1).
Vec2 surface_uv(const Shape& s, unsigned prim, float b1, float b2, Vec3 l) {
  if (s.type == Shape::Type::Curve) return Vec2(b1, std::clamp(0.5f * (b2 + 1), 0.0f, 1.0f));
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

// Embree filter of flat curves. A flat curve is a band that turns to face each ray, so a
// ray leaving a point on it would find the band again, turned toward the new ray. A ray
// whose origin lies within the segment's reach (its widest radius, plus the chord error
// of the polyline measured against, plus the offset rays leave surfaces with) never hits
// that segment: rays leaving a flat curve pass through it. Then alpha, if the curve has it.
void flat_curve_filter(const RTCFilterFunctionNArguments* args) {
  const auto* g = static_cast<const EmbreeScene::AlphaGeometry*>(args->geometryUserPtr);
  const Shape& s = *g->shape;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned N = args->N;
    const std::size_t prim = RTCHitN_primID(args->hit, N, i);
    const Vec3* p = &s.positions[4 * prim];
    const float* r = &s.curve_radii[4 * prim];
    const Vec3 o(RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i), RTCRayN_org_z(args->ray, N, i));
    // The segment as a polyline of m chords. A cubic Bézier strays from a chord over 1/m of
    // its parameter by at most |B''|max / (8 m^2), and |B''| <= 6 max|p[k+2] - 2 p[k+1] + p[k]|
    // (Farin, Curves and Surfaces for CAGD, the derivative of a Bézier curve).
    constexpr int m = 8;
    const float second = std::max(length(p[2] - p[1] * 2 + p[0]), length(p[3] - p[2] * 2 + p[1]));
    const float reach =
        std::max({r[0], r[1], r[2], r[3]}) + 6 * second / (8 * m * m) + 2e-4f * std::max(1.0f, max_component(abs(o)));
    Vec3 a = p[0];
    bool near = false;
    for (int k = 1; k <= m && !near; ++k) {
      const float t = float(k) / m, u = 1 - t;
      const Vec3 b = p[0] * (u * u * u) + p[1] * (3 * t * u * u) + p[2] * (3 * t * t * u) + p[3] * (t * t * t);
      const Vec3 ab = b - a;
      const float along = std::clamp(dot(o - a, ab) / std::max(length_squared(ab), 1e-30f), 0.0f, 1.0f);
      near = length(o - (a + ab * along)) <= reach;
      a = b;
    }
    if (near) args->valid[i] = 0;
  }
  if (s.has_alpha()) alpha_filter(args);
}

// all_hits: the context Embree passes to the filter (our fields after its own).
// pass_through_hits: only the hits on those shapes are recorded and rejected; any other
// is accepted (an occlusion query then stops).
void collect_filter(const RTCFilterFunctionNArguments* args);

struct CollectingContext {
  RTCIntersectContext embree;
  EmbreeScene::RawHit* hits;
  int capacity, count = 0;
  bool overflow = false;
  const EmbreeScene* scene = nullptr;
  const std::vector<char>* pass_through = nullptr;

  CollectingContext(EmbreeScene::RawHit* h, int cap) : hits(h), capacity(cap) {
    rtcInitIntersectContext(&embree);
    embree.filter = collect_filter;
  }
  // After the query: the hits sorted by t, or -1 when they did not fit.
  int sorted_count() {
    if (overflow) return -1;
    std::sort(hits, hits + count, [](const EmbreeScene::RawHit& a, const EmbreeScene::RawHit& b) { return a.t < b.t; });
    return count;
  }
};
// Embree hands the filter its own context: ours must begin with it.
static_assert(std::is_standard_layout_v<CollectingContext> && offsetof(CollectingContext, embree) == 0);

void collect_filter(const RTCFilterFunctionNArguments* args) {
  auto* c = reinterpret_cast<CollectingContext*>(args->context);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (args->valid[i] != -1) continue;
    if (c->pass_through && !(*c->pass_through)[std::size_t(c->scene->shape_of(RTCHitN_geomID(args->hit, N, i),
                                                                              RTCHitN_instID(args->hit, N, i, 0)))])
      continue;          // accepted
    args->valid[i] = 0;  // rejected: the traversal goes on to the next candidate
    EmbreeScene::RawHit h;
    h.t = RTCRayN_tfar(args->ray, N, i);
    h.u = RTCHitN_u(args->hit, N, i);
    h.v = RTCHitN_v(args->hit, N, i);
    h.ng_x = RTCHitN_Ng_x(args->hit, N, i);
    h.ng_y = RTCHitN_Ng_y(args->hit, N, i);
    h.ng_z = RTCHitN_Ng_z(args->hit, N, i);
    h.geom = RTCHitN_geomID(args->hit, N, i);
    h.prim = RTCHitN_primID(args->hit, N, i);
    h.inst = RTCHitN_instID(args->hit, N, i, 0);
    bool seen = false;
    for (int k = 0; k < c->count && !seen; ++k) {
      const EmbreeScene::RawHit& o = c->hits[k];
      // The same primitive twice (referenced from two leaves); a sphere's two roots differ in t.
      seen = o.geom == h.geom && o.prim == h.prim && o.inst == h.inst && o.t == h.t;
    }
    if (seen) continue;
    if (c->count == c->capacity) {
      c->overflow = true;
      continue;
    }
    c->hits[c->count++] = h;
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
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);  // all_hits
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
    } else if (s.type == Shape::Type::Curve) {
      g = rtcNewGeometry(device_, s.curve_kind == Shape::CurveKind::Cylinder ? RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE
                                  : s.curve_kind == Shape::CurveKind::Ribbon
                                      ? RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE
                                      : RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                            4 * sizeof(float), s.positions.size()));
      for (std::size_t i = 0; i < s.positions.size(); ++i) {
        v[4 * i] = s.positions[i].x;
        v[4 * i + 1] = s.positions[i].y;
        v[4 * i + 2] = s.positions[i].z;
        v[4 * i + 3] = s.curve_radii[i];
      }
      if (s.curve_kind == Shape::CurveKind::Ribbon) {
        auto* n = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), s.normals.size()));
        for (std::size_t i = 0; i < s.normals.size(); ++i) {
          n[3 * i] = s.normals[i].x;
          n[3 * i + 1] = s.normals[i].y;
          n[3 * i + 2] = s.normals[i].z;
        }
      }
      const std::size_t segments = s.positions.size() / 4;
      auto* idx = static_cast<unsigned*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), segments));
      for (std::size_t k = 0; k < segments; ++k) idx[k] = unsigned(4 * k);
      // Flat curves are traced as ray-facing quads along the curve: 8 per segment rather
      // than Embree's default 4, for close views of bent hairs.
      if (s.curve_kind == Shape::CurveKind::Flat) rtcSetGeometryTessellationRate(g, 8);
    } else {
      g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
      v[0] = s.center.x;
      v[1] = s.center.y;
      v[2] = s.center.z;
      v[3] = s.radius;
    }
    const bool flat_curve = s.type == Shape::Type::Curve && s.curve_kind == Shape::CurveKind::Flat;
    if (s.has_alpha() || flat_curve) {
      alpha_geometries_.push_back(std::make_unique<AlphaGeometry>(AlphaGeometry{&s, alpha_lookup_}));
      rtcSetGeometryUserData(g, alpha_geometries_.back().get());
      rtcSetGeometryIntersectFilterFunction(g, flat_curve ? flat_curve_filter : alpha_filter);
      rtcSetGeometryOccludedFilterFunction(g, flat_curve ? flat_curve_filter : alpha_filter);
    }
    rtcCommitGeometry(g);
    unsigned gid = rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    if (geom_to_shape.size() <= gid) geom_to_shape.resize(gid + 1, -1);
    geom_to_shape[gid] = id;
  }
  return scene;
}

void EmbreeScene::commit(RTCScene scene, const LoadMonitor* monitor, const std::string& stage_name) {
  LoadStage stage(monitor, stage_name);
  if (monitor)
    rtcSetSceneProgressMonitorFunction(
        scene, [](void* p, double fraction) { return static_cast<LoadStage*>(p)->try_update(fraction); }, &stage);
  rtcCommitScene(scene);
  if (monitor) rtcSetSceneProgressMonitorFunction(scene, nullptr, nullptr);
  stage.finish();  // throws Interrupted when the build was stopped
}

void EmbreeScene::build(const std::vector<Shape>& shapes, const std::vector<int>& top_level,
                        const std::vector<std::vector<int>>& objects, const std::vector<Instance>& instances,
                        AlphaTextureLookup alpha, const LoadMonitor* monitor) {
  shapes_ = &shapes;
  alpha_lookup_ = alpha;
  for (const Shape& s : shapes)
    if (s.alpha_texture >= 0 && !alpha.evaluate)
      throw std::invalid_argument("EmbreeScene::build: a shape has an alpha texture but no texture lookup was given");
  instances_ = instances;
  object_geom_shape_.assign(objects.size(), {});
  for (std::size_t o = 0; o < objects.size(); ++o) {
    object_scenes_.push_back(make_scene(objects[o], object_geom_shape_[o]));
    commit(object_scenes_.back(), monitor, fmt::format("building the BVH (object {} of {})", o + 1, objects.size()));
  }

  top_geom_shape_.clear();
  scene_ = make_scene(top_level, top_geom_shape_);
  // The instances are attached, then the scene committed.
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
  commit(scene_, monitor, "building the BVH");

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

int EmbreeScene::all_hits(const Ray& ray, RawHit* hits, int capacity) const {
  // An occlusion query whose filter records and rejects every hit: the traversal visits
  // every node the segment crosses either way (no hit shortens it), and the occlusion
  // kernel does so without ordering the children by distance or keeping a nearest hit
  // (as Cycles' local intersection for its subsurface probes). The hits come unordered;
  // sorted_count sorts them.
  CollectingContext c(hits, capacity);
  RTCRay r;
  init_ray(r, ray);
  rtcOccluded1(scene_, &c.embree, &r);
  return c.sorted_count();
}

int EmbreeScene::pass_through_hits(const Ray& ray, const std::vector<char>& pass_through, RawHit* hits,
                                   int capacity) const {
  CollectingContext c(hits, capacity);
  c.scene = this;
  c.pass_through = &pass_through;
  RTCRay r;
  init_ray(r, ray);
  rtcOccluded1(scene_, &c.embree, &r);
  if (r.tfar < 0) return kBlocked;
  return c.sorted_count();
}

void EmbreeScene::fill_hit(const RawHit& raw, const Ray& ray, SurfaceHit& hit) const {
  RTCRayHit rh;
  init_ray(rh.ray, ray);
  rh.ray.tfar = raw.t;
  rh.hit.u = raw.u;
  rh.hit.v = raw.v;
  rh.hit.Ng_x = raw.ng_x;
  rh.hit.Ng_y = raw.ng_y;
  rh.hit.Ng_z = raw.ng_z;
  rh.hit.geomID = raw.geom;
  rh.hit.primID = raw.prim;
  rh.hit.instID[0] = raw.inst;
  fill_hit(rh, ray, hit);
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
  if (s.type == Shape::Type::Curve) {
    // Embree's Ng: the surface normal of round and normal-oriented curves; the curve's
    // tangent for flat ones, which face the ray: their normal is the ray's reverse made
    // perpendicular to the tangent (pbrt-v4's flat curve, dp/du x dp/dv with dp/dv across
    // the ray). Computed in world space; the point is on the ray.
    Vec3 n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    if (inst)
      n = s.curve_kind == Shape::CurveKind::Flat ? inst->object_to_world.vector(n) : inst->object_to_world.normal(n);
    if (s.curve_kind == Shape::CurveKind::Flat) {
      const Vec3 tangent = normalize(n);
      const Vec3 d = normalize(ray.d);
      n = tangent * dot(tangent, d) - d;
      if (!(length_squared(n) > 0)) {  // a ray along the curve
        Vec3 b;
        orthonormal_basis(tangent, n, b);
      }
    }
    if (s.curve_kind == Shape::CurveKind::Ribbon) {
      // pbrt-v4's ribbon normal is the given one (interpolated along the segment).
      const Vec3* nk = &s.normals[4 * std::size_t(rh.hit.primID)];
      Vec3 given = nk[0] * (1 - rh.hit.u) + nk[3] * rh.hit.u;
      if (inst) given = inst->object_to_world.normal(given);
      if (dot(n, given) < 0) n = -n;
    }
    ng = normalize(n);
    if (s.flip_normals && s.curve_kind != Shape::CurveKind::Flat) ng = -ng;  // a flat curve faces the ray
    hit.p = ray.o + ray.d * hit.t;
    hit.ng = ng;
    hit.ns = ng;
    hit.uv = surface_uv(s, rh.hit.primID, rh.hit.u, rh.hit.v, Vec3());
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
