// The subsurface-object mask against the geometry of a sphere seen from the camera.
#include "dermis/render/object_mask.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/render/scene_assembly.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

// Camera at the origin looking down +z (pbrt's camera space, y up), fov 40 degrees on a
// square film; a subsurface sphere of radius 1 at z = 5 on the axis, a diffuse one
// beside it, and a diffuse floor below both (not in the mask). A pixel centre is in the mask exactly when its ray's
// angle to the axis is below asin(1/5); tessellation moves the silhouette a little, so pixels within 3 % of that angle
// are not checked.
class ObjectMask : public testing::TestWithParam<const char*> {};

TEST_P(ObjectMask, IsTheSubsurfaceSphereSilhouette) {
  const int res = 48;
  const double fov = 40 * M_PI / 180;
  SceneDesc desc = parse_scene_string(std::string(R"(LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 48 "integer yresolution" 48
WorldBegin
AttributeBegin
  Material "subsurface" "rgb reflectance" [0.5 0.5 0.5] "rgb mfp" [1 1 1] "string method" ")") +
                                      GetParam() + R"("
  Translate 0 0 5
  Shape "sphere" "float radius" 1
AttributeEnd
AttributeBegin
  Material "diffuse"
  Shape "bilinearmesh" "point3 P" [-10 -2 -10  10 -2 -10  -10 -2 20  10 -2 20]
AttributeEnd
AttributeBegin
  Material "diffuse"
  Translate 1.7 0 5
  Shape "sphere" "float radius" 0.4
AttributeEnd
)");
  Diagnostics diag;
  auto scene = assemble_scene(desc, diag);
  const std::vector<uint8_t> mask = subsurface_object_mask(*scene);
  ASSERT_EQ(mask.size(), std::size_t(res * res));
  const double silhouette = std::asin(1.0 / 5);
  int inside = 0, checked = 0;
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      // Screen position in [-1, 1] times tan(fov / 2); pbrt's x grows to the left of +x
      // in raster space, which does not matter for a sphere on the axis.
      const double sx = (2 * (x + 0.5) / res - 1) * std::tan(fov / 2),
                   sy = (2 * (y + 0.5) / res - 1) * std::tan(fov / 2);
      const double angle = std::atan(std::sqrt(sx * sx + sy * sy));
      const bool in = mask[std::size_t(y) * res + x] != 0;
      if (std::abs(angle / silhouette - 1) < 0.03) continue;
      ++checked;
      EXPECT_EQ(in, angle < silhouette) << "pixel " << x << ", " << y;
      inside += in;
    }
  EXPECT_GT(checked, res * res * 9 / 10);
  EXPECT_GT(inside, 100);  // the sphere covers ~ pi (0.2 / tan 20deg)^2 / 4 of the film: ~0.24 * 2304
}

// Every method, the `volumetric` reference (assembled as a dielectric with a medium) too.
INSTANTIATE_TEST_SUITE_P(Methods, ObjectMask, testing::Values("randomwalk", "disk", "volumetric"));

}  // namespace
}  // namespace dermis
