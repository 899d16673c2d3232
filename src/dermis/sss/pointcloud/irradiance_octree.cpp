#include "dermis/sss/pointcloud/irradiance_octree.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/sss/pointcloud/local_disk_weight.h"

namespace dermis::sss::pointcloud {

IrradianceOctree::IrradianceOctree(std::span<const SurfacePoint> points, std::span<const RGB> irradiance,
                                   OctreeOptions options)
    : options_(options) {
  if (points.empty()) throw std::invalid_argument("IrradianceOctree: the point cloud is empty");
  if (points.size() != irradiance.size())
    throw std::invalid_argument("IrradianceOctree: " + std::to_string(points.size()) + " points but " +
                                std::to_string(irradiance.size()) + " irradiance values");
  if (points.size() >= (1ull << 31)) throw std::invalid_argument("IrradianceOctree: too many points (2^31 or more)");
  if (options.max_leaf_points < 1 || options.max_leaf_points > 65535 || options.max_depth < 0 || options.max_depth > 64)
    throw std::invalid_argument("IrradianceOctree: max_leaf_points must be in [1, 65535] and max_depth in [0, 64]");
  points_.resize(points.size());
  Vec3 lo = points[0].position, hi = lo;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    const RGB e = irradiance[i];
    if (!e.is_finite() || e[0] < 0 || e[1] < 0 || e[2] < 0)
      throw std::invalid_argument("IrradianceOctree: irradiance of point " + std::to_string(i) +
                                  " is negative or not finite");
    if (!(p.area >= 0) || !std::isfinite(p.area) || !std::isfinite(p.position.x) || !std::isfinite(p.position.y) ||
        !std::isfinite(p.position.z))
      throw std::invalid_argument("IrradianceOctree: point " + std::to_string(i) +
                                  " has a non-finite position or a negative area");
    points_[i] = {p.position, p.area, e * p.area};
    lo = min(lo, p.position);
    hi = max(hi, p.position);
  }
  const Vec3 extent = hi - lo;
  const float size = std::max(max_component(extent), 1e-30f) * 1.0001f;
  nodes_.reserve(2 * points.size() / std::size_t(options.max_leaf_points) + 16);
  nodes_.emplace_back();
  build(lo, size);
}

// Fills the nodes top-down from an explicit list of (node, point range, cube) tasks; a
// node's children are reserved contiguously before they are filled.
void IrradianceOctree::build(Vec3 cube_lo, float cube_size) {
  struct Task {
    uint32_t node, begin, end;
    Vec3 cube_lo;
    float cube_size;
    int depth;
  };
  std::vector<Task> stack{{0, 0, uint32_t(points_.size()), cube_lo, cube_size, 0}};
  std::vector<Point> scratch;
  while (!stack.empty()) {
    const Task t = stack.back();
    stack.pop_back();
    // Node statistics (Jensen & Buehler 2002, sec. 4.2): total area, total power (mean
    // irradiance x area) and a centroid weighted by each point's luminance x area.
    Node n{};
    n.lo = n.hi = points_[t.begin].position;
    Vec3d c_lum, c_area;
    double w_lum = 0, w_area = 0, area = 0;
    double power[3] = {0, 0, 0};
    for (uint32_t i = t.begin; i < t.end; ++i) {
      const Point& p = points_[i];
      n.lo = min(n.lo, p.position);
      n.hi = max(n.hi, p.position);
      area += p.area;
      for (int c = 0; c < 3; ++c) power[c] += p.power[c];
      const double l = p.power.luminance();
      c_lum += Vec3d(p.position) * l;
      w_lum += l;
      c_area += Vec3d(p.position) * double(p.area);
      w_area += p.area;
    }
    n.area = float(area);
    n.power = RGB(float(power[0]), float(power[1]), float(power[2]));
    if (w_lum > 0)
      n.centroid = Vec3(c_lum / w_lum);
    else if (w_area > 0)
      n.centroid = Vec3(c_area / w_area);
    else
      n.centroid = (n.lo + n.hi) * 0.5f;
    const uint32_t count = t.end - t.begin;
    const bool degenerate = n.lo == n.hi;
    if (count <= uint32_t(options_.max_leaf_points) || t.depth >= options_.max_depth || degenerate) {
      if (count > 65535) throw std::invalid_argument("IrradianceOctree: more than 65535 coincident points");
      n.first = t.begin;
      n.count = uint16_t(count);
      n.is_leaf = 1;
      nodes_[t.node] = n;
      continue;
    }
    // Partition into the octants of the cube (a counting sort, stable).
    const float half = t.cube_size * 0.5f;
    const Vec3 mid = t.cube_lo + Vec3(half, half, half);
    auto octant = [&](const Vec3& p) {
      return (p.x >= mid.x ? 1 : 0) | (p.y >= mid.y ? 2 : 0) | (p.z >= mid.z ? 4 : 0);
    };
    std::array<uint32_t, 9> start{};
    for (uint32_t i = t.begin; i < t.end; ++i) ++start[octant(points_[i].position) + 1];
    for (int o = 0; o < 8; ++o) start[o + 1] += start[o];
    scratch.assign(points_.begin() + t.begin, points_.begin() + t.end);
    std::array<uint32_t, 8> fill{};
    for (const Point& p : scratch) {
      const int o = octant(p.position);
      points_[t.begin + start[o] + fill[o]++] = p;
    }
    n.first = uint32_t(nodes_.size());
    n.is_leaf = 0;
    uint16_t children = 0;
    for (int o = 0; o < 8; ++o) {
      if (start[o + 1] == start[o]) continue;
      const Vec3 lo(o & 1 ? mid.x : t.cube_lo.x, o & 2 ? mid.y : t.cube_lo.y, o & 4 ? mid.z : t.cube_lo.z);
      stack.push_back({uint32_t(nodes_.size()), t.begin + start[o], t.begin + start[o + 1], lo, half, t.depth + 1});
      nodes_.emplace_back();
      ++children;
    }
    n.count = children;
    nodes_[t.node] = n;
  }
}

namespace {

bool inside(Vec3 x, Vec3 lo, Vec3 hi) {
  return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z;
}

}  // namespace

RGB IrradianceOctree::query(Vec3 x, const ProfileRGB& profile, double epsilon) const {
  return query_outside_disk(x, profile, epsilon, 0.0);
}

RGB IrradianceOctree::query_outside_disk(Vec3 x, const ProfileRGB& profile, double epsilon, double alpha) const {
  if (!(epsilon >= 0)) throw std::invalid_argument("IrradianceOctree::query: epsilon must be >= 0");
  double sum[3] = {0, 0, 0};
  auto add = [&](double r, RGB power) {
    const double w = global_weight(r, alpha);
    if (w <= 0) return;
    for (int c = 0; c < 3; ++c)
      if (power[c] != 0) sum[c] += w * profile[c].eval(r) * double(power[c]);
  };
  // Depth-first with an explicit stack: at most 7 siblings wait per level.
  std::array<uint32_t, 8 * 66> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!inside(x, n.lo, n.hi)) {
      const double d2 = length_squared(Vec3d(x - n.centroid));
      // Jensen & Buehler 2002, sec. 4.3: use the node whole when dw = A / |x - p|^2 < eps.
      if (double(n.area) < epsilon * d2) {
        add(std::sqrt(d2), n.power);
        continue;
      }
    }
    if (n.is_leaf) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i)
        add(distance(Vec3d(x), Vec3d(points_[i].position)), points_[i].power);
    } else {
      for (uint32_t c = 0; c < n.count; ++c) stack[top++] = n.first + c;
    }
  }
  return RGB(float(sum[0]), float(sum[1]), float(sum[2]));
}

RGB IrradianceOctree::brute_force(Vec3 x, const ProfileRGB& profile) const {
  double sum[3] = {0, 0, 0};
  for (const Point& p : points_) {
    const double r = distance(Vec3d(x), Vec3d(p.position));
    for (int c = 0; c < 3; ++c) sum[c] += profile[c].eval(r) * double(p.power[c]);
  }
  return RGB(float(sum[0]), float(sum[1]), float(sum[2]));
}

std::size_t IrradianceOctree::memory_bytes() const {
  return sizeof(*this) + points_.capacity() * sizeof(Point) + nodes_.capacity() * sizeof(Node);
}

}  // namespace dermis::sss::pointcloud
