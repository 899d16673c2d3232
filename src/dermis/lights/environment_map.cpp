#include "dermis/lights/environment_map.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dermis {

Vec3 equal_area_square_to_sphere(Vec2 uv) {
  const float u = 2 * uv.x - 1, v = 2 * uv.y - 1, au = std::abs(u), av = std::abs(v);
  const float d = 1 - (au + av);  // > 0 inside the central diamond (upper hemisphere)
  const float r = 1 - std::abs(d);
  // The diamond of radius r maps to the cap z >= 1 - r^2: areas 2 r^2 and 2 pi r^2.
  const float phi = (r == 0 ? 1 : (av - au) / r + 1) * (kPi / 4);
  const float z = std::copysign(1 - r * r, d);
  const float s = r * safe_sqrt(2 - r * r);  // sqrt(1 - z^2)
  return {std::copysign(std::cos(phi), u) * s, std::copysign(std::sin(phi), v) * s, z};
}

Vec2 equal_area_sphere_to_square(Vec3 w) {
  const float ax = std::abs(w.x), ay = std::abs(w.y), az = std::min(std::abs(w.z), 1.0f);
  const float r = safe_sqrt(1 - az);
  const float phi = std::atan2(ay, ax);         // [0, pi/2]
  float vp = r * phi * (2 / kPi), up = r - vp;  // on the diamond |u| + |v| = r
  if (w.z < 0) {                                // the corner triangles, folded out
    const float t = up;
    up = 1 - vp;
    vp = 1 - t;
  }
  const float u = std::copysign(up, w.x), v = std::copysign(vp, w.y);
  return {std::clamp((u + 1) / 2, 0.0f, 1 - 1e-7f), std::clamp((v + 1) / 2, 0.0f, 1 - 1e-7f)};
}

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<float> pixels, const Transform& light_to_world,
                               float scale, Mapping mapping)
    : width_(width),
      height_(height),
      mapping_(mapping),
      light_to_world_(light_to_world),
      world_to_light_(light_to_world.inverse()),
      scale_(scale) {
  if (width <= 0 || height <= 0 || pixels.size() != std::size_t(width) * height * 3)
    throw std::invalid_argument("environment map: bad image size");
  if (mapping == Mapping::EqualArea && width != height)
    throw std::invalid_argument(fmt::format(
        "the image is {}x{}; an equal-area environment map (pbrt-v4's) is square; for an equirectangular (lat-long) "
        "map give \"string mapping\" \"latlong\"",
        width, height));
  std::vector<float> weight(std::size_t(width) * height);
  double sum = 0, solid_angle = 0;
  Vec3 arrival(0, 0, 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Vec2 uv{(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)};
      const float da = solid_angle_density(uv);  // per unit uv area
      const float* p = &pixels[3 * (std::size_t(y) * width + x)];
      float lum = std::max(0.0f, RGB(p[0], p[1], p[2]).luminance() * scale);
      if (!std::isfinite(lum * da))  // the sampling table is in floats, as is the radiance
        throw std::invalid_argument(fmt::format(
            "pixel ({}, {}) of luminance {:.3g} times the scale {:.3g} (and the pixel's solid angle) is beyond the "
            "range of 32-bit floats; lower \"scale\" (or \"illuminance\")",
            x, y, double(RGB(p[0], p[1], p[2]).luminance()), double(scale)));
      weight[std::size_t(y) * width + x] = lum * da;
      sum += double(lum) * da;
      solid_angle += da;
      arrival += uv_to_direction(uv) * (lum * da);
    }
  }
  average_ = solid_angle > 0 ? float(sum / solid_angle) : 0.0f;
  mean_arrival_ = sum > 0 ? arrival / float(sum) : Vec3(0, 0, 0);
  distribution_ = Distribution2D(weight, std::size_t(width), std::size_t(height));
  texels_.resize(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = std::size_t(y) * width + x;
      Texel& t = texels_[i];
      std::copy_n(&pixels[3 * i], 3, t.rgb);
      t.pdf_uv = distribution_.pdf({(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)});
    }
}

float EnvironmentMap::upper_hemisphere_illuminance() const {
  // Midpoint rule on 4 x 4 points per pixel (the horizon cuts pixels), in light space.
  constexpr int k = 4;
  double e = 0;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const float* p = texels_[std::size_t(y) * width_ + x].rgb;
      const double lum = std::max(0.0f, RGB(p[0], p[1], p[2]).luminance() * scale_);
      if (lum == 0) continue;
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          const Vec2 uv{(float(x) + (i + 0.5f) / k) / float(width_), (float(y) + (j + 0.5f) / k) / float(height_)};
          const float z = normalize(world_to_light_.vector(uv_to_direction(uv))).z;
          if (z > 0) e += lum * z * solid_angle_density(uv) / (double(width_) * height_ * k * k);
        }
    }
  return float(e);
}

float EnvironmentMap::solid_angle_density(Vec2 uv) const {
  if (mapping_ == Mapping::EqualArea) return 4 * kPi;  // equal-area: 4 pi over the unit square
  return 2 * kPi * kPi * std::sin(uv.y * kPi);         // dω = 2 π² sin θ du dv
}

Vec2 EnvironmentMap::direction_to_uv(Vec3 w_world) const {
  Vec3 w = normalize(world_to_light_.vector(w_world));
  if (mapping_ == Mapping::EqualArea) return equal_area_sphere_to_square(w);
  float theta = std::acos(std::clamp(w.z, -1.0f, 1.0f));
  float phi = std::atan2(w.y, w.x);
  if (phi < 0) phi += 2 * kPi;
  return {std::min(phi * kInv2Pi, 1 - 1e-7f), std::min(theta * kInvPi, 1 - 1e-7f)};
}

Vec3 EnvironmentMap::uv_to_direction(Vec2 uv) const {
  if (mapping_ == Mapping::EqualArea) return normalize(light_to_world_.vector(equal_area_square_to_sphere(uv)));
  float theta = uv.y * kPi, phi = uv.x * 2 * kPi;
  Vec3 w{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
  return normalize(light_to_world_.vector(w));
}

const EnvironmentMap::Texel& EnvironmentMap::texel_at(Vec2 uv) const {
  int x = std::clamp(int(uv.x * float(width_)), 0, width_ - 1);
  int y = std::clamp(int(uv.y * float(height_)), 0, height_ - 1);
  return texels_[std::size_t(y) * width_ + x];
}

RGB EnvironmentMap::eval(Vec3 w) const { return radiance(texel_at(direction_to_uv(w))); }

RGB EnvironmentMap::eval(Vec3 w, float* pdf) const {
  const Vec2 uv = direction_to_uv(w);
  const Texel& t = texel_at(uv);
  const float da = solid_angle_density(uv);
  *pdf = da == 0 ? 0 : t.pdf_uv / da;
  return radiance(t);
}

Vec3 EnvironmentMap::sample(Vec2 u, float* pdf, RGB* L) const {
  float pdf_uv;
  Vec2 uv = distribution_.sample(u, &pdf_uv);
  const float da = solid_angle_density(uv);
  if (pdf_uv == 0 || da == 0) {
    *pdf = 0;
    return {0, 0, 1};
  }
  *pdf = pdf_uv / da;
  if (L) *L = radiance(texel_at(uv));
  return uv_to_direction(uv);
}

float EnvironmentMap::pdf(Vec3 w) const {
  Vec2 uv = direction_to_uv(w);
  const float da = solid_angle_density(uv);
  if (da == 0) return 0;
  return texel_at(uv).pdf_uv / da;
}

}  // namespace dermis
