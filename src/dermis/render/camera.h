// pbrt-v4's perspective and orthographic cameras with a thin lens: raster (0,0) is the
// top-left corner; the screen window spans [-1, 1] on the shorter image axis unless given.
// Perspective: fov spans the shorter axis. Orthographic: rays leave the screen window's
// points on the plane z = 0 of camera space along +z (the window in camera-space units).
#pragma once

#include <array>

#include "dermis/core/transform.h"
#include "dermis/geometry/ray.h"

namespace dermis {

class Camera {
 public:
  enum class Projection { Perspective, Orthographic };
  Camera() = default;
  Camera(const Transform& camera_to_world, float fov_degrees, float lens_radius, float focal_distance, int xres,
         int yres, const std::array<float, 4>* screen_window = nullptr,
         Projection projection = Projection::Perspective);
  // film: raster position in pixels; u_lens in [0,1)^2.
  Ray generate_ray(Vec2 film, Vec2 u_lens) const;
  // A thin lens (lens radius > 0): generate_ray reads u_lens; a pinhole ignores it.
  bool has_lens() const { return lens_radius_ > 0; }

 private:
  Transform camera_to_world_;
  Projection projection_ = Projection::Perspective;
  float tan_half_fov_ = 1, lens_radius_ = 0, focal_distance_ = 1e6f;
  int xres_ = 1, yres_ = 1;
  std::array<float, 4> window_{-1, 1, -1, 1};  // xmin xmax ymin ymax
  // Without a lens the world-space ray is linear in the raster position (x, y): origin
  // origin_ + x origin_dx_ + y origin_dy_, direction (before normalising) dir_ + x dir_dx_
  // + y dir_dy_; made once, in double, from the camera transform.
  Vec3 origin_, origin_dx_, origin_dy_, dir_, dir_dx_, dir_dy_;
};

}  // namespace dermis
