#include "dermis/render/camera.h"

#include <cmath>

#include "dermis/core/warp.h"

namespace dermis {

Camera::Camera(const Transform& camera_to_world, float fov_degrees, float lens_radius, float focal_distance, int xres,
               int yres, const std::array<float, 4>* screen_window, Projection projection)
    : camera_to_world_(camera_to_world),
      projection_(projection),
      tan_half_fov_(std::tan(fov_degrees * kPi / 360.0f)),
      lens_radius_(lens_radius),
      focal_distance_(focal_distance),
      xres_(xres),
      yres_(yres) {
  if (screen_window) {
    window_ = *screen_window;
  } else {
    // pbrt-v4: the shorter axis spans [-1, 1].
    float aspect = float(xres) / float(yres);
    if (aspect > 1)
      window_ = {-aspect, aspect, -1, 1};
    else
      window_ = {-1, 1, -1 / aspect, 1 / aspect};
  }
  // The screen position (sx, sy) of raster (x, y), as in generate_ray: sx = w0 + x (w1 -
  // w0) / xres, sy = w3 - y (w3 - w2) / yres.
  const double sx_dx = (double(window_[1]) - window_[0]) / xres, sy_dy = -(double(window_[3]) - window_[2]) / yres;
  const Transform& m = camera_to_world_;
  if (projection_ == Projection::Orthographic) {
    origin_ = Vec3(m.point(Vec3d(window_[0], window_[3], 0)));
    origin_dx_ = Vec3(m.vector(Vec3d(sx_dx, 0, 0)));
    origin_dy_ = Vec3(m.vector(Vec3d(0, sy_dy, 0)));
    dir_ = Vec3(m.vector(Vec3d(0, 0, 1)));
  } else {
    const double t = tan_half_fov_;
    origin_ = Vec3(m.point(Vec3d(0, 0, 0)));
    dir_ = Vec3(m.vector(Vec3d(window_[0] * t, window_[3] * t, 1)));
    dir_dx_ = Vec3(m.vector(Vec3d(sx_dx * t, 0, 0)));
    dir_dy_ = Vec3(m.vector(Vec3d(0, sy_dy * t, 0)));
  }
}

Ray Camera::generate_ray(Vec2 film, Vec2 u_lens) const {
  if (lens_radius_ <= 0) {
    Ray r;
    r.o = origin_ + origin_dx_ * film.x + origin_dy_ * film.y;
    r.d = normalize(dir_ + dir_dx_ * film.x + dir_dy_ * film.y);
    return r;
  }
  float sx = window_[0] + film.x / float(xres_) * (window_[1] - window_[0]);
  float sy = window_[3] - film.y / float(yres_) * (window_[3] - window_[2]);
  const bool ortho = projection_ == Projection::Orthographic;
  Vec3 origin = ortho ? Vec3(sx, sy, 0) : Vec3(0, 0, 0);
  Vec3 dir = ortho ? Vec3(0, 0, 1) : Vec3(sx * tan_half_fov_, sy * tan_half_fov_, 1);
  // Thin lens: the ray through the lens point meets the pinhole ray on the plane of focus.
  const Vec2 lens = sample_uniform_disk_concentric(u_lens) * lens_radius_;
  const Vec3 focus = origin + dir * focal_distance_;
  origin = origin + Vec3(lens.x, lens.y, 0);
  dir = focus - origin;
  Ray r;
  r.o = camera_to_world_.point(origin);
  r.d = normalize(camera_to_world_.vector(dir));
  return r;
}

}  // namespace dermis
