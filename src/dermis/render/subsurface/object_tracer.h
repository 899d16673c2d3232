// Ray queries restricted to one subsurface object, for exit sampling: every hit of a
// probe segment on the object, and the first boundary hit of a ray travelling inside
// it. An object is a set of shapes (render_scene.h: the shapes sharing a subsurface
// material) seen through one instance; the tracer needs only the Embree scene and
// the shape -> object map, so exit samplers are testable without a RenderScene.
#pragma once

#include <vector>

#include "dermis/geometry/embree_scene.h"
#include "dermis/geometry/ray.h"
#include "dermis/render/path_counters.h"

namespace dermis {

class ObjectTracer {
 public:
  // object_of_shape: -1 for shapes every ray passes through.
  // The object of `entry` (the hit where the path entered): the shapes s with
  // object_of_shape[s] == object_of_shape[entry.shape], hit through entry.instance.
  ObjectTracer(const EmbreeScene& scene, const std::vector<int>& object_of_shape, const SurfaceHit& entry,
               PathCounters& counters)
      : scene_(scene),
        object_of_shape_(object_of_shape),
        object_(object_of_shape[entry.shape]),
        instance_(entry.instance),
        counters_(counters) {}

  bool contains(const SurfaceHit& h) const { return h.instance == instance_ && object_of_shape_[h.shape] == object_; }
  int object() const { return object_; }

  // Appends to `hits` every intersection of the segment o + t d, t in (0, length), with
  // the object, in order, at most max_hits (hit.t measured from o).
  void collect_hits(Vec3 o, Vec3 d, float length, int max_hits, std::vector<SurfaceHit>& hits) const;

  // The first intersection of the ray with the object, skipping other shapes.
  bool first_hit(Ray ray, SurfaceHit& hit) const;

  // The first intersection with the object or with another object inside it (an
  // interior boundary: a stone in jade, teeth in a head); shapes whose object is -1
  // (index-matched interfaces) are passed through.
  bool first_boundary(Ray ray, SurfaceHit& hit) const;

 private:
  bool first_where(Ray ray, SurfaceHit& hit, bool other_objects) const;

  const EmbreeScene& scene_;
  const std::vector<int>& object_of_shape_;
  int object_, instance_;
  PathCounters& counters_;
};

}  // namespace dermis
