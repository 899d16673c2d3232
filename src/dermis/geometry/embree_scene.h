// The Embree acceleration structure over the renderer's shapes: top-level
// shapes, and instanced objects (one Embree scene each, one level of instancing).
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>
#include <vector>

#include "dermis/core/load_monitor.h"
#include "dermis/core/transform.h"
#include "dermis/geometry/alpha_mask.h"
#include "dermis/geometry/ray.h"
#include "dermis/geometry/shape.h"

namespace dermis {

struct Instance {
  int object = -1;  // index into the object list given to build()
  Transform object_to_world;
};

class EmbreeScene {
 public:
  EmbreeScene();
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // shapes: every shape; top_level: indices of shapes placed in world space;
  // objects: for each object, the indices of its shapes (in object space).
  // Shapes with alpha (Shape::has_alpha) get an Embree filter that cuts their hits away
  // (geometry/alpha_mask.h) for every query, closest and any hit; `alpha` evaluates
  // their alpha textures. Shapes without alpha get no filter: they cost nothing more,
  // except flat curves, whose filter also drops a ray's hits on the band it left.
  // With a monitor: stage "building the BVH" (one per instanced object too), as Embree
  // reports it, and Interrupted once the cancel flag is set (Embree stops its build).
  void build(const std::vector<Shape>& shapes, const std::vector<int>& top_level,
             const std::vector<std::vector<int>>& objects, const std::vector<Instance>& instances,
             AlphaTextureLookup alpha = {}, const LoadMonitor* monitor = nullptr);

  // Whether hits need their (u, v): only a scene with textures reads them. Without, the
  // sphere's (acos, atan2 per hit: a measurable share of a medium render) is skipped and
  // hit.uv is (0, 0).
  void set_uv_needed(bool needed) { uv_needed_ = needed; }

  // Closest hit with t in (0, ray.tmax). Fills hit (world space) on success.
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // Any hit with t in (0, ray.tmax).
  bool occluded(const Ray& ray) const;

  // One hit as Embree reports it, before fill_hit turns it into a SurfaceHit.
  struct RawHit {
    float t, u, v, ng_x, ng_y, ng_z;
    unsigned geom, prim, inst;
  };
  // Every hit with t in (0, ray.tmax) in one traversal (a context filter records each
  // candidate and rejects it, so that the traversal goes on, as Cycles collects a probe's
  // hits), sorted by t, each primitive once (a spatial-split BVH may report one twice).
  // Returns the count, or -1 when there were more than `capacity`: the nearest ones are
  // then not known (hits come in traversal order), and the caller queries hit by hit.
  int all_hits(const Ray& ray, RawHit* hits, int capacity) const;
  void fill_hit(const RawHit& raw, const Ray& ray, SurfaceHit& hit) const;
  // The hits on shapes that `pass_through` marks (per shape: index-matched interfaces)
  // along the ray, sorted by t, in one occlusion query that stops at the first hit on any
  // other shape (its filter records and rejects the first kind, accepts the second).
  // Returns their count, kBlocked when another shape lies on the ray, or -1 when there
  // were more than `capacity` (the caller then queries hit by hit).
  static constexpr int kBlocked = -2;
  int pass_through_hits(const Ray& ray, const std::vector<char>& pass_through, RawHit* hits, int capacity) const;
  // The shape of an Embree hit (geometry, and instance or RTC_INVALID_GEOMETRY_ID).
  int shape_of(unsigned geom, unsigned inst) const {
    return inst != RTC_INVALID_GEOMETRY_ID ? object_geom_shape_[instances_[top_geom_instance_[inst]].object][geom]
                                           : top_geom_shape_[geom];
  }

  RTCScene handle() const { return scene_; }
  // World-space bounding sphere of all geometry.
  Vec3 bounds_center() const { return center_; }
  float bounds_radius() const { return radius_; }

  // What the filter of one geometry (alpha, flat curve) reads (Embree's geometry user pointer).
  struct AlphaGeometry {
    const Shape* shape;
    AlphaTextureLookup lookup;
  };

 private:
  RTCScene make_scene(const std::vector<int>& shape_ids, std::vector<int>& geom_to_shape);
  // rtcCommitScene with progress and cancellation (monitor may be null).
  void commit(RTCScene scene, const LoadMonitor* monitor, const std::string& stage_name);
  void fill_hit(const RTCRayHit& rh, const Ray& ray, SurfaceHit& hit) const;

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> object_scenes_;
  const std::vector<Shape>* shapes_ = nullptr;
  std::vector<int> top_geom_shape_;                  // top-level geomID -> shape index, or -1 for instances
  std::vector<int> top_geom_instance_;               // top-level geomID -> instance index, or -1
  std::vector<std::vector<int>> object_geom_shape_;  // per object: geomID -> shape index
  std::vector<Instance> instances_;
  std::vector<std::unique_ptr<AlphaGeometry>> alpha_geometries_;
  AlphaTextureLookup alpha_lookup_;
  bool uv_needed_ = true;
  Vec3 center_;
  float radius_ = 0;
};

}  // namespace dermis
