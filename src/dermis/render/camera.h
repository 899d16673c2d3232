// pbrt-v4's perspective camera with a thin lens: raster (0,0) is the top-left
// corner; fov spans the shorter image axis.
#pragma once

#include <array>

#include "dermis/core/transform.h"
#include "dermis/geometry/ray.h"

namespace dermis {

class PerspectiveCamera {
 public:
  PerspectiveCamera() = default;
  PerspectiveCamera(const Transform& camera_to_world, float fov_degrees, float lens_radius, float focal_distance,
                    int xres, int yres, const std::array<float, 4>* screen_window = nullptr);
  // film: raster position in pixels; u_lens in [0,1)^2.
  Ray generate_ray(Vec2 film, Vec2 u_lens) const;

 private:
  Transform camera_to_world_;
  float tan_half_fov_ = 1, lens_radius_ = 0, focal_distance_ = 1e6f;
  int xres_ = 1, yres_ = 1;
  std::array<float, 4> window_{-1, 1, -1, 1};  // xmin xmax ymin ymax
};

}  // namespace dermis
