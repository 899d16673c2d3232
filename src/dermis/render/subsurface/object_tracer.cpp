#include "dermis/render/subsurface/object_tracer.h"

#include <limits>

#include "dermis/geometry/embree_scene.h"

namespace dermis {

namespace {

// Moves past a hit along the ray's direction (not along the normal: the next query
// must continue on the same line), as far as a ray leaving the surface keeps from it.
inline float skip_distance(Vec3 p) { return surface_offset(p); }

}  // namespace

void ObjectTracer::collect_hits(Vec3 o, Vec3 d, float length, int max_hits, std::vector<SurfaceHit>& hits) const {
  // One traversal for all of the segment's hits; a hit closer to the one before it than
  // skip_distance is dropped, as the queries hit by hit below step past it.
  {
    constexpr int kCapacity = 64;
    EmbreeScene::RawHit raw[kCapacity];
    const Ray segment{o, d, length};
    counters_.count(segment);
    const int n = scene_.all_hits(segment, raw, kCapacity);
    if (n >= 0) {
      float next = 0;  // the nearest t the queries hit by hit would look from
      for (int i = 0; i < n; ++i) {
        if (raw[i].t < next) continue;
        SurfaceHit h;
        scene_.fill_hit(raw[i], segment, h);
        next = raw[i].t + skip_distance(h.p);
        if (!contains(h)) continue;
        hits.push_back(h);
        if (int(hits.size()) >= max_hits) return;
      }
      return;
    }
  }
  // More hits than the buffer holds: the nearest, query by query.
  float t0 = 0;
  for (int guard = 0; guard < 4 * max_hits + 16 && t0 < length; ++guard) {
    Ray r{o + d * t0, d, length - t0};
    SurfaceHit h;
    counters_.count(r);
    if (!scene_.intersect(r, h)) return;
    float t = t0 + h.t;
    if (contains(h)) {
      h.t = t;
      hits.push_back(h);
      if (int(hits.size()) >= max_hits) return;
    }
    t0 = t + skip_distance(h.p);
  }
}

bool ObjectTracer::first_hit(Ray ray, SurfaceHit& hit) const { return first_where(ray, hit, false); }

bool ObjectTracer::first_boundary(Ray ray, SurfaceHit& hit) const { return first_where(ray, hit, true); }

bool ObjectTracer::first_where(Ray ray, SurfaceHit& hit, bool other_objects) const {
  for (int guard = 0; guard < 64; ++guard) {
    counters_.count(ray);
    if (!scene_.intersect(ray, hit)) return false;
    if (contains(hit) || (other_objects && object_of_shape_[hit.shape] >= 0)) return true;
    float skip = hit.t + skip_distance(hit.p);
    ray.o = ray.o + ray.d * skip;
    if (ray.tmax != std::numeric_limits<float>::infinity()) ray.tmax -= skip;
  }
  return false;
}

}  // namespace dermis
