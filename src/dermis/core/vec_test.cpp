#include "dermis/core/vec.h"

#include <gtest/gtest.h>

#include "dermis/core/frame.h"
#include "dermis/core/rng.h"
#include "dermis/core/transform.h"

namespace dermis {
namespace {

TEST(Vec3, CrossIsOrthogonalAndRightHanded) {
  Vec3 x{1, 0, 0}, y{0, 1, 0};
  EXPECT_EQ(cross(x, y), Vec3(0, 0, 1));
  Vec3 a{0.3f, -1.2f, 2.5f}, b{4.0f, 0.5f, -0.7f};
  EXPECT_NEAR(dot(cross(a, b), a), 0, 1e-5);
  EXPECT_NEAR(dot(cross(a, b), b), 0, 1e-5);
}

TEST(Frame, IsOrthonormalForManyNormals) {
  Rng rng(1, 2);
  for (int i = 0; i < 10000; ++i) {
    Vec3 n = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    if (i == 0) n = {0, 0, -1};
    if (i == 1) n = {0, 0, 1};
    Frame f(n);
    EXPECT_NEAR(length(f.s), 1, 1e-5);
    EXPECT_NEAR(length(f.t), 1, 1e-5);
    EXPECT_NEAR(dot(f.s, f.t), 0, 1e-5);
    EXPECT_NEAR(dot(f.s, f.n), 0, 1e-5);
    EXPECT_NEAR(dot(cross(f.s, f.t), f.n), 1, 1e-5);
    Vec3 v{0.2f, -0.4f, 0.7f};
    Vec3 back = f.to_world(f.to_local(v));
    EXPECT_NEAR(distance(back, v), 0, 1e-5);
  }
}

TEST(Transform, InverseRoundTrips) {
  Transform t = Transform::translate({1, 2, 3}) * Transform::rotate(33, {1, 1, 0}) * Transform::scale({2, 3, 0.5});
  Vec3d p{0.3, -0.7, 1.9};
  Vec3d q = t.inverse().point(t.point(p));
  EXPECT_NEAR(q.x, p.x, 1e-12);
  EXPECT_NEAR(q.y, p.y, 1e-12);
  EXPECT_NEAR(q.z, p.z, 1e-12);
  Mat4 prod = t.matrix() * t.inverse_matrix();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(prod.m[i][j], i == j ? 1 : 0, 1e-12);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
  Transform t = Transform::scale({1, 4, 1}) * Transform::rotate(20, {0, 0, 1});
  Vec3 tangent = normalize(Vec3(1, 1, 0)), n = normalize(Vec3(1, -1, 0));
  EXPECT_NEAR(dot(t.vector(tangent), t.normal(n)), 0, 1e-5);
}

TEST(Transform, LookAtMatchesPbrtConvention) {
  // pbrt: camera looks down +z in camera space.
  Transform cam_from_world = Transform::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  Vec3d forward = cam_from_world.vector(Vec3d(0, 0, -1));
  EXPECT_NEAR(forward.z, 1, 1e-12);
  Vec3d origin = cam_from_world.point(Vec3d(0, 0, 5));
  EXPECT_NEAR(length(origin), 0, 1e-12);
}

TEST(Rng, StreamsAreReproducibleAndDistinct) {
  Rng a(7, 100, 3), b(7, 100, 3), c(7, 100, 4);
  for (int i = 0; i < 10; ++i) {
    float x = a.uniform();
    EXPECT_EQ(x, b.uniform());
    EXPECT_GE(x, 0.0f);
    EXPECT_LT(x, 1.0f);
  }
  int same = 0;
  Rng d(7, 100, 3);
  for (int i = 0; i < 100; ++i) same += d.next_u32() == c.next_u32();
  EXPECT_LT(same, 3);
}

}  // namespace
}  // namespace dermis
