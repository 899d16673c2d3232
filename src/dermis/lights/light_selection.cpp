#include "dermis/lights/light_selection.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dermis {

namespace {

constexpr float kPiF = 3.14159265358979f;

// Upper bound of cos(angle between unit axis a and any direction from the origin into
// a sphere at d, distance |d|, radius r): cos(max(0, theta - alpha)) with sin(alpha) =
// r / |d| (Conty Estevez & Kulla 2018, eq. 3, the cone of the bounds), times d2 = |d|^2,
// from a.d and |d| cos(alpha) = sqrt(d2 - r^2): cos(theta - alpha) |d|^2 =
// (a.d) |d| cos(alpha) + r |d| sin(theta), one square root (and no division) per bound.
inline float cos_bound_d2(float a_dot_d, float d2, float r, float dist_cos_alpha) {
  if (a_dot_d >= dist_cos_alpha) return d2;  // theta <= alpha
  return a_dot_d * dist_cos_alpha + r * std::sqrt(std::max(0.0f, d2 - a_dot_d * a_dot_d));
}
bool at_infinity(const Light& l) { return l.type == Light::Type::Infinite || l.type == Light::Type::Distant; }

}  // namespace

LightSelection::LightSelection(const std::vector<Light>& lights, float scene_radius, bool outweighed_sky_gives_way)
    : count_(lights.size()), outweighed_sky_gives_way_(outweighed_sky_gives_way) {
  if (lights.empty()) return;
  // The power distribution (lights at infinity and finite lights as two groups, each
  // with probability 1/2 when both exist: the power of a light at infinity grows with
  // the scene's radius, which a large floor inflates).
  // Powers in double, each divided by its group's sum (or, with one group, by the sum of
  // all), so that the table is finite in float whatever the scene's radius: a distant
  // light's power grows with its square (the ratios are what selection uses).
  std::vector<double> power(lights.size());
  double group_sum[2] = {0, 0};
  for (std::size_t i = 0; i < lights.size(); ++i) {
    // Finite in double for any float emission and extent; NaN (an emission set by hand
    // through the library, which the parser refuses) gets probability zero, as before.
    const double p = light_power(lights[i], scene_radius);
    power[i] = p > 0 ? p : 0.0;
    group_sum[at_infinity(lights[i])] += power[i];
  }
  const bool both_groups = group_sum[0] > 0 && group_sum[1] > 0;
  std::vector<float> normalised(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const double sum = both_groups ? group_sum[at_infinity(lights[i])] : group_sum[0] + group_sum[1];
    normalised[i] = sum > 0 ? float(power[i] / sum) : 0.0f;
  }
  power_ = Distribution1D(normalised);

  pointwise_ = lights.size() <= kPointwiseLightLimit;
  gives_way_leaves_none_ = false;
  if (!pointwise_) return;
  split_ = both_groups;
  group_.assign(lights.size(), 0);
  if (split_)
    for (std::size_t i = 0; i < lights.size(); ++i) group_[i] = at_infinity(lights[i]) ? 1 : 0;
  bounds_.resize(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    Bounds& b = bounds_[i];
    b.type = l.type;
    b.emission = float(std::max(0.0, (double(l.emission[0]) + double(l.emission[1]) + double(l.emission[2])) / 3));
    switch (l.type) {
      case Light::Type::Triangle: {
        b.center = (l.p0 + l.p1 + l.p2) / 3.0f;
        b.radius = std::sqrt(std::max(
            {length_squared(l.p0 - b.center), length_squared(l.p1 - b.center), length_squared(l.p2 - b.center)}));
        const Vec3 c = cross(l.p1 - l.p0, l.p2 - l.p0);
        const float len = length(c);
        b.normal = len > 0 ? c / len : Vec3(0, 0, 1);
        b.area = l.area;
        break;
      }
      case Light::Type::Sphere:
        b.center = l.center;
        b.radius = l.radius;
        b.area = kPiF * l.radius * l.radius;
        break;
      case Light::Type::Point:
        b.center = l.position;
        break;
      case Light::Type::Spot:
        b.center = l.position;
        b.normal = l.direction;
        b.cos_falloff_end = l.cos_falloff_end;
        break;
      case Light::Type::Distant:
        b.normal = l.direction;
        break;
      case Light::Type::Infinite:
        b.emission = l.environment ? l.environment->average_luminance() : b.emission;
        b.uniform_sky = !l.environment;
        break;
    }
  }
  // Importances are only compared with each other: emissions relative to the brightest
  // light's, so that the products in importance() stay finite for a light near the range
  // of floats (a sky of L = 3e38 made pi L infinite, and every probability NaN).
  float brightest = 0;
  for (const Bounds& b : bounds_) brightest = std::max(brightest, b.emission);
  if (brightest > 0)
    for (Bounds& b : bounds_) b.emission /= brightest;
  gives_way_leaves_none_ = true;
  for (const Bounds& b : bounds_)
    if (!b.uniform_sky) gives_way_leaves_none_ = false;
  infinite_all_uniform_ = split_;
  for (std::size_t i = 0; i < lights.size(); ++i)
    if (group_[i]) {
      if (!bounds_[i].uniform_sky) infinite_all_uniform_ = false;
      uniform_sky_importance_ += importance(i, Vec3(0, 0, 0), Vec3(0, 0, 1));  // the same at every surface point
    }
}

bool LightSelection::may_meet_finite_emitter(Vec3 o, Vec3 d) const {
  if (!pointwise_) return count_ > 0;
  for (const Bounds& b : bounds_) {
    if (b.type != Light::Type::Triangle && b.type != Light::Type::Sphere) continue;
    // The ray meets the sphere (c, r) where the distance from c to the line is at most r,
    // ahead of o or with o inside.
    const Vec3 oc = b.center - o;
    const float along = dot(oc, d);
    const float r = b.radius * 1.001f + 1e-5f * (std::abs(b.center.x) + std::abs(b.center.y) + std::abs(b.center.z));
    const float d2 = length_squared(oc);
    if (d2 <= r * r) return true;
    if (along <= 0) continue;
    if (d2 - along * along <= r * r) return true;
  }
  return false;
}

float LightSelection::importance(std::size_t i, Vec3 p, Vec3 n) const {
  const Bounds& b = bounds_[i];
  const bool surface = n.x != 0 || n.y != 0 || n.z != 0;
  switch (b.type) {
    case Light::Type::Infinite:
      // Irradiance of a uniform sky of the map's mean radiance (fluence in a medium).
      return b.emission * (surface ? kPiF : 4 * kPiF);
    case Light::Type::Distant: {
      const float c = surface ? dot(n, b.normal) : 1.0f;  // exact: one direction
      return c > 0 ? b.emission * c : 0.0f;
    }
    case Light::Type::Point:
    case Light::Type::Spot: {
      const Vec3 d = b.center - p;
      const float d2 = length_squared(d);
      if (d2 <= 0) return 0;
      const float inv_d = 1 / std::sqrt(d2);
      const float c = surface ? dot(n, d) * inv_d : 1.0f;
      if (c <= 0) return 0;
      // Outside the spot's outer cone nothing is emitted toward p (exact).
      if (b.type == Light::Type::Spot && dot(d, b.normal) * -inv_d < b.cos_falloff_end) return 0;
      return b.emission * c / d2;
    }
    case Light::Type::Triangle:
    case Light::Type::Sphere: {
      const Vec3 d = b.center - p;
      const float d2 = length_squared(d);
      const float r2 = b.radius * b.radius;
      if (d2 <= r2 * 1.0001f) return b.emission * b.area / std::max(r2, 1e-12f);  // inside the bounds
      // The cosine bounds times d2: one square root shared (|d| cos(alpha)), one per bound.
      const float dist_cos_alpha = std::sqrt(d2 - r2);
      float c_s = 1, c_l = 1;
      const float inv_d2 = 1 / d2;
      if (surface) {
        c_s = cos_bound_d2(dot(n, d), d2, b.radius, dist_cos_alpha) * inv_d2;
        if (c_s <= 0) return 0;  // the whole bounding sphere is below the tangent plane
      }
      // Emitter cosine over the bounds, either side of the triangle (conservative for
      // one-sided lights).
      if (b.type == Light::Type::Triangle)
        c_l = cos_bound_d2(std::abs(dot(b.normal, d)), d2, b.radius, dist_cos_alpha) * inv_d2;
      return b.emission * b.area * std::max(c_l, 1e-4f) * c_s * inv_d2;
    }
  }
  return 0;
}

int LightSelection::sample(float u, Vec3 p, Vec3 n, float* pmf, float* u_remapped, int group, float* group_importance,
                           SkyRule sky) const {
  *pmf = 0;
  if (group_importance) *group_importance = 0;
  if (count_ == 0) return -1;
  if (!pointwise_) {
    const std::size_t i = power_.sample_discrete(u, pmf, u_remapped);
    return *pmf > 0 ? int(i) : -1;
  }
  std::array<float, kPointwiseLightLimit> w;
  const float sum = weights(p, n, group, w.data(), sky);
  if (group_importance) *group_importance = sum;
  if (!(sum > 0)) return -1;
  float target = u * sum;
  std::size_t chosen = count_;
  for (std::size_t i = 0; i < count_; ++i) {
    if (w[i] <= 0) continue;
    chosen = i;  // the last light with weight, should round-off carry target past the end
    if (target < w[i]) break;
    target -= w[i];
  }
  *pmf = w[chosen] / sum;
  if (u_remapped) *u_remapped = std::clamp(target / w[chosen], 0.0f, 0x1.fffffep-1f);
  return int(chosen);
}

float LightSelection::pmf(int light, Vec3 p, Vec3 n, SkyRule sky) const {
  if (light < 0 || std::size_t(light) >= count_) return 0;
  if (!pointwise_) return power_.pmf_discrete(std::size_t(light));
  std::array<float, kPointwiseLightLimit> w;
  const float sum = weights(p, n, group_of(std::size_t(light), n), w.data(), sky);
  return sum > 0 ? w[std::size_t(light)] / sum : 0.0f;
}

float LightSelection::weights(Vec3 p, Vec3 n, int group, float* w, SkyRule sky) const {
  float sum = 0, others = 0, skies = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    sum += w[i] = group_of(i, n) == group ? importance(i, p, n) : 0.0f;
    (bounds_[i].uniform_sky ? skies : others) += w[i];
  }
  if (!(skies > 0)) return sum;
  if (surface(n) && sky == SkyRule::GivesWay) {
    // Asked for by the caller (SkyRule::GivesWay): the uniform skies are never chosen.
    for (std::size_t i = 0; i < count_; ++i)
      if (bounds_[i].uniform_sky) w[i] = 0;
    return others;
  }
  if (!outweighed_sky_gives_way_) return sum;
  if (surface(n)) {
    // At a surface where the caller asks for the rule, the skies are a group of their own
    // (group 1, the finite lights group 0): they give way where the finite lights outweigh
    // them (the header's rule).
    if (sky != SkyRule::Outweighed || group != 1 || !infinite_all_uniform_) return sum;
    float finite = 0;
    for (std::size_t i = 0; i < count_; ++i)
      if (!group_[i]) finite += importance(i, p, n);
    if (!uniform_sky_outweighed(finite)) return sum;
    std::fill(w, w + count_, 0.0f);
    return 0;
  }
  // In a medium, where the other lights outweigh them (the header's rule).
  if (others > skies) {
    for (std::size_t i = 0; i < count_; ++i)
      if (bounds_[i].uniform_sky) w[i] = 0;
    sum = others;
  }
  return sum;
}

}  // namespace dermis
