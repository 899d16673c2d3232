#include "dermis/render/path/lights_from_inside.h"

#include <cmath>

#include "dermis/core/warp.h"
#include "dermis/lights/light.h"

namespace dermis {

namespace {

bool delta_light(const Light& l) {
  return l.type == Light::Type::Point || l.type == Light::Type::Spot || l.type == Light::Type::Distant;
}

// The lights the walks sample: area lights and environment maps. Not delta lights (no
// direction that refracts toward them is drawn with a density) and not uniform skies (the
// walks that leave find them nearly without noise; their light samples, uniform over the
// sphere from inside, only added it).
bool sampled_from_inside(const Light& l) {
  return !delta_light(l) && !(l.type == Light::Type::Infinite && !l.environment);
}

// The density with which light_sample() draws w from y (medium point: no normal), as
// light_pdf() gives it at the point the ray y + t w meets the light; 0 where it misses.
float light_density_along(const RenderScene& sc, const Light& l, Vec3 y, Vec3 w) {
  switch (l.type) {
    case Light::Type::Infinite:
      return light_pdf(l, y, w, {}, {});
    case Light::Type::Sphere: {
      const Vec3 dc = l.center - y;
      const float dc2 = length_squared(dc), r2 = l.radius * l.radius;
      if (dc2 > r2 * 1.0001f) {  // outside: uniform in the cone of the sphere (light.cpp)
        const float cos_max = safe_sqrt(1 - r2 / dc2);
        return dot(w, dc) >= cos_max * std::sqrt(dc2) ? uniform_cone_pdf(cos_max) : 0.0f;
      }
      // Inside: uniform by area; the ray meets the sphere once, ahead.
      const float b = dot(w, dc), t = b + safe_sqrt(b * b - (dc2 - r2));
      const Vec3 p = y + w * t;
      return light_pdf(l, y, w, p, normalize(p - l.center));
    }
    case Light::Type::Triangle: {
      // Moller & Trumbore 1997: the ray's barycentric coordinates in the triangle.
      const Vec3 e1 = l.p1 - l.p0, e2 = l.p2 - l.p0, q = cross(w, e2);
      const float det = dot(e1, q);
      if (det == 0) return 0;
      const Vec3 s = y - l.p0;
      const float b1 = dot(s, q) / det;
      const Vec3 r = cross(s, e1);
      const float b2 = dot(w, r) / det, t = dot(e2, r) / det;
      if (!(b1 >= 0 && b2 >= 0 && b1 + b2 <= 1 && t > 0)) return 0;
      const Vec3 n = l.flat ? l.normal : sc.shapes[std::size_t(l.shape)].triangle_normal(l.prim, b1, b2);
      return light_pdf(l, y, w, y + w * t, n);
    }
    default:
      return 0;
  }
}

}  // namespace

bool lights_offered_inside(const RenderScene& sc, int outside_medium) {
  if (outside_medium >= 0 || sc.has_interfaces || sc.lights.size() > kPointwiseLightLimit) return false;
  bool any = false;
  for (const Light& l : sc.lights) {
    if (l.type == Light::Type::Sphere && l.inward) return false;
    any = any || sampled_from_inside(l);
  }
  return any && sc.switches.refracted_light;
}

bool sample_light_from_inside(const RenderScene& sc, Vec3 y, float u1, float u2, Vec3& w, float& density) {
  float pmf = 0, u_reused = 0;
  const int li = sc.light_selection.sample(u1, y, Vec3(0, 0, 0), &pmf, &u_reused);
  if (li < 0 || pmf <= 0 || !sampled_from_inside(sc.lights[std::size_t(li)])) return false;
  LightSample ls;
  light_sample(sc.lights[std::size_t(li)], sc.shapes, y, {u_reused, u2}, ls);
  if (!(ls.pdf > 0)) return false;  // drawn whatever the light's radiance toward y
  w = ls.wi;
  density = light_density_from_inside(sc, y, w);
  return density > 0;
}

float light_density_from_inside(const RenderScene& sc, Vec3 y, Vec3 w) {
  float density = 0;
  for (std::size_t i = 0; i < sc.lights.size(); ++i) {
    const Light& l = sc.lights[i];
    if (!sampled_from_inside(l)) continue;
    const float p = light_density_along(sc, l, y, w);
    if (p > 0) density += sc.light_selection.pmf(int(i), y, Vec3(0, 0, 0)) * p;
  }
  return density;
}

std::optional<KeyLight> key_light(const RenderScene& sc) {
  Vec3 sum(0, 0, 0), arrival(0, 0, 0);
  double weight = 0, env_power = 0;
  for (const Light& l : sc.lights) {
    if (l.type == Light::Type::Infinite && l.environment) {
      const double power = l.environment->average_luminance();  // per steradian, the same 4 pi for all
      arrival += l.environment->mean_arrival() * float(power);
      env_power += power;
    }
    if (l.type != Light::Type::Triangle && l.type != Light::Type::Sphere) continue;
    const double power = light_power(l, 1);
    const Vec3 centre = l.type == Light::Type::Sphere ? l.center : (l.p0 + l.p1 + l.p2) / 3.0f;
    sum += centre * float(power);
    weight += power;
  }
  if (weight > 0) return KeyLight{sum / float(weight), false};
  if (env_power > 0 && length(arrival) >= kConcentratedArrival * float(env_power))
    return KeyLight{normalize(arrival), true};
  return std::nullopt;
}

bool key_light_direction(const std::optional<KeyLight>& key, Vec3 y, Vec3& toward) {
  if (!key) return false;
  if (key->at_infinity) {
    toward = key->at;
    return true;
  }
  const Vec3 d = key->at - y;
  if (!(length(d) > 0)) return false;
  toward = normalize(d);
  return true;
}

}  // namespace dermis
