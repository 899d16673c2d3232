// A lat-long (equirectangular) environment map, importance-sampled by a
// piecewise-constant 2D distribution over its pixels weighted by sin(theta)
// (pbrt-v3 sec. 14.2.4, with the mapping below).
//
// Mapping, in light space (z up): theta = acos(z), phi = atan2(y, x) in [0, 2 pi);
// image column u = phi / (2 pi), row v = theta / pi (row 0 is the +z pole).
#pragma once

#include <vector>

#include "dermis/core/distribution.h"
#include "dermis/core/rgb.h"
#include "dermis/core/transform.h"

namespace dermis {

class EnvironmentMap {
 public:
  // pixels: width*height RGB, row-major, top row first (linear radiance).
  EnvironmentMap(int width, int height, std::vector<float> pixels, const Transform& light_to_world, float scale);

  // Radiance arriving from world direction w (pointing toward the environment).
  RGB eval(Vec3 w) const;
  // Samples a world direction; pdf in solid angle.
  Vec3 sample(Vec2 u, float* pdf) const;
  float pdf(Vec3 w) const;
  // Mean radiance over the sphere of directions (for light selection).
  float average_luminance() const { return average_; }

  Vec2 direction_to_uv(Vec3 w_world) const;
  Vec3 uv_to_direction(Vec2 uv) const;

 private:
  RGB texel(Vec2 uv) const;
  int width_, height_;
  std::vector<float> pixels_;
  Transform light_to_world_, world_to_light_;
  float scale_;
  Distribution2D distribution_;
  float average_ = 0;
};

}  // namespace dermis
