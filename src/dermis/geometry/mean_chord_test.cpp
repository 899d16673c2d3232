#include "dermis/geometry/mean_chord.h"

#include <gtest/gtest.h>

namespace dermis {
namespace {

// A closed cube of side a at `offset`, its faces wound outward (or inward).
Shape cube(float a, Vec3 offset, bool inward = false) {
  Shape s;
  for (int k = 0; k < 8; ++k)
    s.positions.push_back(offset + Vec3(k & 1 ? a : 0.0f, k & 2 ? a : 0.0f, k & 4 ? a : 0.0f));
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    const uint32_t tris[2][3] = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
    for (const auto& t : tris) {
      s.indices.push_back(t[0]);
      s.indices.push_back(inward ? t[2] : t[1]);
      s.indices.push_back(inward ? t[1] : t[2]);
    }
  }
  return s;
}

TEST(MeanChord, IsCauchysFourVolumesOverTheAreaForASphereAndACube) {
  Shape sphere;
  sphere.type = Shape::Type::Sphere;
  sphere.center = Vec3(3, -2, 7);
  sphere.radius = 1.5f;
  EXPECT_NEAR(mean_chord_length({&sphere}), 2.0 * 3.0 / 3.0, 1e-6);  // 2D/3
  const Shape c = cube(2, Vec3(0, 0, 0)), far = cube(2, Vec3(100, -50, 20)), in = cube(2, Vec3(5, 5, 5), true);
  EXPECT_NEAR(mean_chord_length({&c}), 4.0 / 3.0, 1e-6);  // 4 a^3 / 6 a^2 = 2a/3
  EXPECT_NEAR(mean_chord_length({&far}), 4.0 / 3.0, 1e-4) << "independent of where the cube lies";
  EXPECT_NEAR(mean_chord_length({&in}), 4.0 / 3.0, 1e-6) << "or of its winding";
  // Two shapes as one object: volumes and areas add.
  EXPECT_NEAR(mean_chord_length({&c, &sphere}), 4 * (8 + 4.5 * kPiD) / (24 + 9 * kPiD), 1e-5);
}

TEST(MeanChord, IsZeroWithoutAVolume) {
  Shape triangle;
  triangle.positions = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)};
  triangle.indices = {0, 1, 2};
  EXPECT_EQ(mean_chord_length({&triangle}), 0.0) << "an open surface";
  EXPECT_EQ(mean_chord_length({}), 0.0);
  Shape curve;
  curve.type = Shape::Type::Curve;
  curve.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)};
  EXPECT_EQ(mean_chord_length({&curve}), 0.0);
}

}  // namespace
}  // namespace dermis
