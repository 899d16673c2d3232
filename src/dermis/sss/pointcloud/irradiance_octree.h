// The hierarchical irradiance integration of Jensen & Buehler 2002 ("A Rapid
// Hierarchical Rendering Technique for Translucent Materials", sec. 4; METHODS 3):
// an octree over the points of the cloud, each node holding its total area, its
// area-weighted mean irradiance and an irradiance-weighted centroid, evaluated as one
// point when it subtends a small enough solid angle.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"
#include "dermis/sss/pointcloud/point_distribution.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis::sss::pointcloud {

struct OctreeOptions {
  int max_leaf_points = 8;
  int max_depth = 32;
};

class IrradianceOctree {
 public:
  // points[i] carries irradiance[i] (RGB, the light transmitted into the surface).
  // Throws std::invalid_argument on sizes that differ, an empty cloud, a negative or
  // non-finite irradiance or area.
  IrradianceOctree(std::span<const SurfacePoint> points, std::span<const RGB> irradiance, OctreeOptions options = {});

  // M(x) = sum_p R(|x - p|) E_p A_p (Jensen & Buehler 2002, eq. 10), each channel with its
  // profile; a node is used whole when x lies outside its bounds and
  // A_node / |x - p_node|^2 < epsilon (their eq. 11's solid-angle test).
  RGB query(Vec3 x, const ProfileRGB& profile, double epsilon) const;

  // As query, with every term weighted by wbar(r) = 1 - (1 - (r/alpha)^2)^2 for r < alpha
  // (1 beyond): the global part of Langlands & Mertens' split (see local_disk.h).
  // alpha <= 0 gives query().
  RGB query_outside_disk(Vec3 x, const ProfileRGB& profile, double epsilon, double alpha) const;

  // The same sum over every point, with no hierarchy (the reference).
  RGB brute_force(Vec3 x, const ProfileRGB& profile) const;

  std::size_t point_count() const { return points_.size(); }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t memory_bytes() const;
  double total_area() const { return nodes_[0].area; }

 private:
  struct Point {
    Vec3 position;
    float area;
    RGB power;  // E_p A_p
  };
  struct Node {
    Vec3 lo, hi;     // tight bounds of the node's points
    Vec3 centroid;   // weighted by luminance(E_p) A_p (by A_p where that is zero)
    float area;      // sum of A_p
    RGB power;       // sum of E_p A_p = mean irradiance x area
    uint32_t first;  // leaf: first point; inner: first child
    uint16_t count;  // leaf: point count; inner: child count
    uint16_t is_leaf;
  };
  void build(Vec3 cube_lo, float cube_size);

  OctreeOptions options_;
  std::vector<Point> points_;  // reordered so that every node's points are contiguous
  std::vector<Node> nodes_;    // node 0 is the root; children of a node are contiguous
};

}  // namespace dermis::sss::pointcloud
