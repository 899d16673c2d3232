#include "dermis/lights/environment_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dermis {

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<float> pixels, const Transform& light_to_world,
                               float scale)
    : width_(width),
      height_(height),
      pixels_(std::move(pixels)),
      light_to_world_(light_to_world),
      world_to_light_(light_to_world.inverse()),
      scale_(scale) {
  if (width <= 0 || height <= 0 || pixels_.size() != std::size_t(width) * height * 3)
    throw std::invalid_argument("environment map: bad image size");
  std::vector<float> weight(std::size_t(width) * height);
  double sum = 0, solid_angle = 0;
  for (int y = 0; y < height; ++y) {
    float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(height));
    for (int x = 0; x < width; ++x) {
      const float* p = &pixels_[3 * (std::size_t(y) * width + x)];
      float lum = std::max(0.0f, RGB(p[0], p[1], p[2]).luminance() * scale);
      weight[std::size_t(y) * width + x] = lum * sin_theta;
      sum += double(lum) * sin_theta;
      solid_angle += sin_theta;
    }
  }
  average_ = solid_angle > 0 ? float(sum / solid_angle) : 0.0f;
  distribution_ = Distribution2D(weight, std::size_t(width), std::size_t(height));
}

Vec2 EnvironmentMap::direction_to_uv(Vec3 w_world) const {
  Vec3 w = normalize(world_to_light_.vector(w_world));
  float theta = std::acos(std::clamp(w.z, -1.0f, 1.0f));
  float phi = std::atan2(w.y, w.x);
  if (phi < 0) phi += 2 * kPi;
  return {std::min(phi * kInv2Pi, 1 - 1e-7f), std::min(theta * kInvPi, 1 - 1e-7f)};
}

Vec3 EnvironmentMap::uv_to_direction(Vec2 uv) const {
  float theta = uv.y * kPi, phi = uv.x * 2 * kPi;
  Vec3 w{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
  return normalize(light_to_world_.vector(w));
}

RGB EnvironmentMap::texel(Vec2 uv) const {
  int x = std::clamp(int(uv.x * float(width_)), 0, width_ - 1);
  int y = std::clamp(int(uv.y * float(height_)), 0, height_ - 1);
  const float* p = &pixels_[3 * (std::size_t(y) * width_ + x)];
  return RGB(p[0], p[1], p[2]) * scale_;
}

RGB EnvironmentMap::eval(Vec3 w) const { return texel(direction_to_uv(w)); }

Vec3 EnvironmentMap::sample(Vec2 u, float* pdf) const {
  float pdf_uv;
  Vec2 uv = distribution_.sample(u, &pdf_uv);
  float sin_theta = std::sin(uv.y * kPi);
  if (pdf_uv == 0 || sin_theta == 0) {
    *pdf = 0;
    return {0, 0, 1};
  }
  // dω = 2 π² sin θ du dv
  *pdf = pdf_uv / (2 * kPi * kPi * sin_theta);
  return uv_to_direction(uv);
}

float EnvironmentMap::pdf(Vec3 w) const {
  Vec2 uv = direction_to_uv(w);
  float sin_theta = std::sin(uv.y * kPi);
  if (sin_theta == 0) return 0;
  return distribution_.pdf(uv) / (2 * kPi * kPi * sin_theta);
}

}  // namespace dermis
