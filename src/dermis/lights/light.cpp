#include "dermis/lights/light.h"

#include <cmath>
#include <limits>

#include "dermis/core/frame.h"
#include "dermis/core/warp.h"
#include "dermis/geometry/shape.h"

namespace dermis {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float smooth_step(float x, float a, float b) {
  if (a == b) return x < a ? 0.0f : 1.0f;
  float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

// pbrt-v4's portal (PortalImageInfiniteLight): light only from the portal's front side.
bool through_portal(const Light& l, Vec3 w) {
  const Vec3 n = l.portal_normal;
  return (n.x == 0 && n.y == 0 && n.z == 0) || dot(w, n) > 0;
}

}  // namespace

RGB area_light_radiance(const Light& l, Vec3 n, Vec3 w) {
  if (!l.two_sided && dot(n, w) <= 0) return RGB(0);
  return l.emission;
}

RGB infinite_light_radiance(const Light& l, Vec3 w) {
  if (!through_portal(l, w)) return RGB(0);
  return l.environment ? l.environment->eval(w) : l.emission;
}

RGB infinite_light_radiance(const Light& l, Vec3 w, Vec3 ref_n, float* pdf) {
  if (!l.environment) {
    *pdf = light_pdf(l, {}, w, {}, {}, ref_n);
    return through_portal(l, w) ? l.emission : RGB(0);
  }
  const RGB L = l.environment->eval(w, pdf);
  return through_portal(l, w) ? L : RGB(0);
}

bool light_sample(const Light& l, const std::vector<Shape>& shapes, Vec3 ref, Vec2 u, LightSample& s, Vec3 ref_n) {
  switch (l.type) {
    case Light::Type::Triangle: {
      Vec2 b = sample_uniform_triangle(u);
      float b0 = b.x, b1 = b.y, b2 = 1 - b0 - b1;
      Vec3 p = l.p0 * b0 + l.p1 * b1 + l.p2 * b2;
      Vec3 n = l.flat ? l.normal : shapes[l.shape].triangle_normal(l.prim, b1, b2);
      Vec3 d = p - ref;
      float dist2 = length_squared(d);
      if (dist2 == 0) return false;
      float dist = std::sqrt(dist2);
      s.wi = d / dist;
      float cos_l = std::abs(dot(n, s.wi));
      if (cos_l == 0) return false;
      s.pdf = dist2 / (cos_l * l.area);  // area density 1/A converted to solid angle
      s.distance = dist;
      s.p_light = p;
      s.n_light = n;
      s.L = area_light_radiance(l, n, -s.wi);
      s.delta = false;
      return !s.L.is_black();
    }
    case Light::Type::Sphere: {
      Vec3 dc = l.center - ref;
      float dc2 = length_squared(dc);
      float r2 = l.radius * l.radius;
      Vec3 p, n;
      if (dc2 > r2 * 1.0001f && !l.inward) {
        // Uniform in the cone of directions subtended by the sphere (pbrt-v3 14.2.2).
        float dcl = std::sqrt(dc2);
        float sin2_max = r2 / dc2;
        float cos_max = safe_sqrt(1 - sin2_max);
        Frame f(dc / dcl);
        Vec3 wl = sample_uniform_cone(u, cos_max);
        Vec3 w = f.to_world(wl);
        // First intersection of the ray ref + t w with the sphere.
        float b = dot(w, dc);
        float disc = b * b - (dc2 - r2);
        float t = b - safe_sqrt(disc);
        p = ref + w * t;
        n = normalize(p - l.center);
        s.wi = w;
        s.distance = t;
        s.pdf = uniform_cone_pdf(cos_max);
      } else {
        // Inside (or inward-facing): uniform by area, converted to solid angle.
        Vec3 ls = sample_uniform_sphere(u);
        p = l.center + ls * l.radius;
        n = l.inward ? -ls : ls;
        Vec3 d = p - ref;
        float dist2 = length_squared(d);
        if (dist2 == 0) return false;
        s.distance = std::sqrt(dist2);
        s.wi = d / s.distance;
        float cos_l = std::abs(dot(n, s.wi));
        if (cos_l == 0) return false;
        s.pdf = dist2 / (cos_l * 4 * kPi * r2);
      }
      s.p_light = p;
      s.n_light = n;
      s.L = area_light_radiance(l, n, -s.wi);
      s.delta = false;
      return !s.L.is_black();
    }
    case Light::Type::Point:
    case Light::Type::Spot: {
      Vec3 d = l.position - ref;
      float dist2 = length_squared(d);
      if (dist2 == 0) return false;
      s.distance = std::sqrt(dist2);
      s.wi = d / s.distance;
      s.pdf = 1;
      s.delta = true;
      s.p_light = l.position;
      RGB I = l.emission;
      if (l.type == Light::Type::Spot) {
        // pbrt-v4 SpotLight::I: smooth step between the cone's outer and inner cosines.
        I = I * smooth_step(dot(-s.wi, l.direction), l.cos_falloff_end, l.cos_falloff_start);
      }
      s.L = I / dist2;
      return !s.L.is_black();
    }
    case Light::Type::Distant:
      s.wi = l.direction;
      s.distance = kInf;
      s.pdf = 1;
      s.delta = true;
      s.L = l.emission;
      return true;
    case Light::Type::Infinite: {
      if (l.environment) {
        s.wi = l.environment->sample(u, &s.pdf, &s.L);
        if (s.pdf == 0) return false;
      } else if (ref_n.x != 0 || ref_n.y != 0 || ref_n.z != 0) {
        const Vec3 local = sample_cosine_hemisphere(u);
        s.wi = Frame(ref_n).to_world(local);
        s.pdf = cosine_hemisphere_pdf(local.z);
        if (s.pdf <= 0) return false;
        s.L = l.emission;
      } else {
        s.wi = sample_uniform_sphere(u);
        s.pdf = uniform_sphere_pdf();
        s.L = l.emission;
      }
      if (!through_portal(l, s.wi))
        s.L = RGB(0);  // sampled over the whole sphere: unbiased, the portal's side is not favoured
      s.distance = kInf;
      s.delta = false;
      return !s.L.is_black();
    }
  }
  return false;
}

float light_pdf(const Light& l, Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light, Vec3 ref_n) {
  switch (l.type) {
    case Light::Type::Triangle: {
      float dist2 = length_squared(p_light - ref);
      float cos_l = std::abs(dot(n_light, wi));
      return cos_l > 0 ? dist2 / (cos_l * l.area) : 0.0f;
    }
    case Light::Type::Sphere: {
      Vec3 dc = l.center - ref;
      float dc2 = length_squared(dc);
      float r2 = l.radius * l.radius;
      if (dc2 > r2 * 1.0001f && !l.inward) return uniform_cone_pdf(safe_sqrt(1 - r2 / dc2));
      float dist2 = length_squared(p_light - ref);
      float cos_l = std::abs(dot(n_light, wi));
      return cos_l > 0 ? dist2 / (cos_l * 4 * kPi * r2) : 0.0f;
    }
    case Light::Type::Infinite:
      if (l.environment) return l.environment->pdf(wi);
      if (ref_n.x != 0 || ref_n.y != 0 || ref_n.z != 0) return cosine_hemisphere_pdf(dot(wi, ref_n));
      return uniform_sphere_pdf();
    default:
      return 0;  // delta lights cannot be hit
  }
}

double light_power(const Light& l, double scene_radius) {
  const double r2 = std::max(scene_radius * scene_radius, 1e-6);
  // The channels' mean in double (their float sum may overflow).
  const double e = (double(l.emission[0]) + double(l.emission[1]) + double(l.emission[2])) / 3;
  switch (l.type) {
    case Light::Type::Triangle:
      return kPiD * double(l.area) * e * (l.two_sided ? 2 : 1);
    case Light::Type::Sphere:
      return 4 * kPiD * kPiD * double(l.radius) * double(l.radius) * e;
    case Light::Type::Point:
      return 4 * kPiD * e;
    case Light::Type::Spot:
      return 2 * kPiD * e * (1 - 0.5 * (double(l.cos_falloff_start) + double(l.cos_falloff_end)));
    case Light::Type::Distant:
      return kPiD * r2 * e;
    case Light::Type::Infinite:
      return 4 * kPiD * kPiD * r2 * (l.environment ? double(l.environment->average_luminance()) : e);
  }
  return 0;
}

}  // namespace dermis
