// An image environment map, in pbrt-v4's equal-area octahedral mapping (Clarberg 2008,
// "Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD": a square image, every pixel
// the same solid angle 4 pi / N) or the lat-long (equirectangular) mapping; importance-
// sampled by a piecewise-constant 2D distribution over its pixels (pbrt-v3 sec. 14.2.4),
// weighted by each pixel's solid angle.
//
// Mappings, in light space (z up), image uv in [0, 1]^2 with (0, 0) the top-left pixel:
// - equal-area: (u', v') = (2u - 1, 2v - 1), r = 1 - |1 - |u'| - |v'||,
//   z = sign(1 - |u'| - |v'|) (1 - r^2), phi = pi/4 ((|v'| - |u'|) / r + 1) in the
//   quadrant of (u', v'): the centre is +z, the corners -z (Clarberg 2008, sec. 3).
// - lat-long: theta = acos(z), phi = atan2(y, x) in [0, 2 pi); column u = phi / (2 pi),
//   row v = theta / pi (row 0 is the +z pole).
#pragma once

#include <vector>

#include "dermis/core/distribution.h"
#include "dermis/core/rgb.h"
#include "dermis/core/transform.h"

namespace dermis {

class EnvironmentMap {
 public:
  enum class Mapping { EqualArea, LatLong };

  // pixels: width*height RGB, row-major, top row first (linear radiance). EqualArea
  // needs a square image (std::invalid_argument otherwise).
  EnvironmentMap(int width, int height, std::vector<float> pixels, const Transform& light_to_world, float scale,
                 Mapping mapping);

  // Radiance arriving from world direction w (pointing toward the environment).
  RGB eval(Vec3 w) const;
  // eval(w), and pdf(w) in `pdf`, from one look-up (a ray that escaped, weighed by MIS).
  RGB eval(Vec3 w, float* pdf) const;
  // Samples a world direction; pdf in solid angle; `L` (if given): the radiance from it, read
  // at the sampled point of the image (as pbrt-v4's ImageInfiniteLight::SampleLi), not looked
  // up again from the direction.
  Vec3 sample(Vec2 u, float* pdf, RGB* L = nullptr) const;
  float pdf(Vec3 w) const;
  // Mean radiance over the sphere of directions (for light selection).
  float average_luminance() const { return average_; }
  // The mean direction light arrives from: the integral of luminance x w over the sphere
  // over the integral of luminance (world space; its length, 0 to 1, says how concentrated
  // the light is: 0 for a uniform map, near 1 for a sun alone).
  Vec3 mean_arrival() const { return mean_arrival_; }
  // Illuminance at a surface facing light-space +z: the integral of luminance x cos
  // over the upper hemisphere (pbrt-v4's "illuminance" normalises it).
  // Computed when asked (16 points per pixel).
  float upper_hemisphere_illuminance() const;
  Mapping mapping() const { return mapping_; }

  Vec2 direction_to_uv(Vec3 w_world) const;
  Vec3 uv_to_direction(Vec2 uv) const;

 private:
  // A pixel's radiance (before the scale) and the density, per unit uv area, with which
  // sample() picks a point in it: together, so that a look-up of both (eval with the pdf)
  // reads one cache line of a map far larger than the caches.
  struct alignas(16) Texel {
    float rgb[3];
    float pdf_uv;
  };
  const Texel& texel_at(Vec2 uv) const;
  RGB radiance(const Texel& t) const { return RGB(t.rgb[0], t.rgb[1], t.rgb[2]) * scale_; }
  // Solid angle per unit uv area at uv (the Jacobian of the mapping).
  float solid_angle_density(Vec2 uv) const;
  int width_, height_;
  Mapping mapping_;
  std::vector<Texel> texels_;  // row-major, top row first
  Transform light_to_world_, world_to_light_;
  float scale_;
  Distribution2D distribution_;
  float average_ = 0;
  Vec3 mean_arrival_{0, 0, 0};
};

// Clarberg 2008: the equal-area map of the unit square onto the unit sphere and back.
Vec3 equal_area_square_to_sphere(Vec2 uv);
Vec2 equal_area_sphere_to_square(Vec3 w);

}  // namespace dermis
