#include "dermis/render/scene_extent.h"

#include <fmt/format.h>

#include <cmath>

namespace dermis {

void check_scene_point(const Vec3& p, const SourceLoc& loc, std::string_view what) {
  for (int a = 0; a < 3; ++a)
    if (!(std::abs(p[a]) <= kMaxSceneCoordinate))
      throw SceneError(loc, fmt::format("{} lies at ({:g}, {:g}, {:g}), beyond the ±{:g} the renderer can trace "
                                        "(Embree's limit; scale the scene down or move it nearer the origin)",
                                        what, p.x, p.y, p.z, kMaxSceneCoordinate));
}

void check_box_extent(const Vec3& lo, const Vec3& hi, const Transform& to_world, const SourceLoc& loc,
                      std::string_view what) {
  for (int corner = 0; corner < 8; ++corner)
    check_scene_point(
        to_world.point(Vec3((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z)), loc,
        what);
}

void check_shape_extent(const Shape& s, const Transform& to_world, const SourceLoc& loc) {
  if (s.type == Shape::Type::Sphere) {
    const float r = std::abs(s.radius);
    check_box_extent(s.center - Vec3(r, r, r), s.center + Vec3(r, r, r), to_world, loc, "the sphere");
    return;
  }
  for (const Vec3& p : s.positions) check_scene_point(to_world.point(p), loc, "a vertex of the shape");
}

}  // namespace dermis
