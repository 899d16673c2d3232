#include "dermis/materials/texture.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/materials/noise.h"

namespace dermis {
namespace {

TEST(Textures, CheckerboardAlternatesBySquareAsPbrtV4) {
  std::vector<Texture> t(2);
  t[0].type = Texture::Type::Constant;
  t[0].value = RGB(0.25f);
  t[1].type = Texture::Type::Checkerboard;
  t[1].tex1 = 0;             // a texture
  t[1].value2 = RGB(0.75f);  // a value
  t[1].mapping.su = 2;
  // (s, t) = (2u, v): tex1 where floor(s) + floor(t) is even.
  EXPECT_EQ(evaluate_texture(t, 1, {0.1f, 0.1f}), RGB(0.25f));
  EXPECT_EQ(evaluate_texture(t, 1, {0.6f, 0.1f}), RGB(0.75f));
  EXPECT_EQ(evaluate_texture(t, 1, {0.6f, 1.1f}), RGB(0.25f));
  EXPECT_EQ(evaluate_texture(t, 1, {-0.1f, 0.1f}), RGB(0.75f));   // floor(-0.2) = -1: odd
  EXPECT_EQ(evaluate_texture(t, 1, {-0.1f, -0.1f}), RGB(0.25f));  // -1 + -1: even
}

TEST(Textures, ScaleOfAValueScalesTheValue) {
  std::vector<Texture> t(1);
  t[0].type = Texture::Type::Scale;
  t[0].value = RGB(0.5f, 0.25f, 1);
  t[0].scale = 2;
  EXPECT_EQ(evaluate_texture(t, 0, {0, 0}), RGB(1, 0.5f, 2));
}

TEST(Textures, MixAndBilerpAsPbrtV4) {
  std::vector<Texture> t(3);
  t[0].type = Texture::Type::Constant;  // a float texture: the amount
  t[0].value = RGB(0.25f);
  t[1].type = Texture::Type::Mix;
  t[1].value = RGB(1, 0, 0);
  t[1].value2 = RGB(0, 0, 1);
  t[1].amount_texture = 0;
  EXPECT_EQ(evaluate_texture(t, 1, {0.3f, 0.7f}), RGB(0.75f, 0, 0.25f));  // (1 - a) tex1 + a tex2
  t[2].type = Texture::Type::Bilerp;
  t[2].corners = {RGB(0), RGB(1), RGB(2), RGB(4)};  // v00, v01, v10, v11
  EXPECT_EQ(evaluate_texture(t, 2, {0, 0}), RGB(0));
  EXPECT_EQ(evaluate_texture(t, 2, {0, 1}), RGB(1));
  EXPECT_EQ(evaluate_texture(t, 2, {1, 0}), RGB(2));
  EXPECT_EQ(evaluate_texture(t, 2, {0.5f, 0.5f}), RGB(1.75f));
}

}  // namespace
}  // namespace dermis

namespace dermis {
namespace {

TextureContext at(Vec3 p, Vec3 n = {0, 0, 1}, Vec2 uv = {0, 0}) {
  TextureContext c;
  c.p = p;
  c.n = n;
  c.uv = uv;
  return c;
}

// pbrt-v4's 2D mappings at hand-computed points (texture space = world moved by -(1, 0, 0)).
TEST(TextureMappings, SphericalCylindricalPlanarAtHandComputedPoints) {
  TextureMapping m;
  m.texture_from_world = Transform::translate({-1, 0, 0});
  m.kind = TextureMapping::Kind::Spherical;         // (theta / pi, phi / 2pi)
  EXPECT_NEAR(m.st(at({1, 0, 2})).x, 0, 1e-6f);     // +z: theta 0
  EXPECT_NEAR(m.st(at({2, 0, 0})).x, 0.5f, 1e-6f);  // +x: theta pi/2, phi 0
  EXPECT_NEAR(m.st(at({2, 0, 0})).y, 0, 1e-6f);
  EXPECT_NEAR(m.st(at({1, 3, 0})).y, 0.25f, 1e-6f);   // +y: phi pi/2
  EXPECT_NEAR(m.st(at({1, -3, 0})).y, 0.75f, 1e-6f);  // -y: phi 3pi/2
  EXPECT_NEAR(m.st(at({1, 0, -1})).x, 1, 1e-6f);      // -z: theta pi
  m.kind = TextureMapping::Kind::Cylindrical;         // ((pi + atan2(y, x)) / 2pi, z)
  EXPECT_NEAR(m.st(at({2, 0, 3})).x, 0.5f, 1e-6f);
  EXPECT_NEAR(m.st(at({2, 0, 3})).y, 3, 1e-6f);
  EXPECT_NEAR(m.st(at({1, 1, 0})).x, 0.75f, 1e-6f);
  m.kind = TextureMapping::Kind::Planar;  // (du + p . vs, dv + p . vt)
  m.vs = {1, 0, 0};
  m.vt = {0, 0, 1};
  m.du = 0.5f;
  m.dv = -1;
  EXPECT_NEAR(m.st(at({3, 7, 3})).x, 2.5f, 1e-6f);
  EXPECT_NEAR(m.st(at({3, 7, 3})).y, 2, 1e-6f);
  m.kind = TextureMapping::Kind::UV;  // (su u + du, sv v + dv)
  m.su = 2;
  m.sv = 3;
  EXPECT_NEAR(m.st(at({0, 0, 0}, {0, 0, 1}, {0.25f, 0.5f})).x, 1.0f, 1e-6f);
  EXPECT_NEAR(m.st(at({0, 0, 0}, {0, 0, 1}, {0.25f, 0.5f})).y, 0.5f, 1e-6f);
}

TEST(Textures, CheckerboardIn3DCountsTheCellsOfThePoint) {
  std::vector<Texture> t(1);
  t[0].type = Texture::Type::Checkerboard;
  t[0].mapping.kind = TextureMapping::Kind::Point3D;
  t[0].value = RGB(1);
  t[0].value2 = RGB(0);
  EXPECT_EQ(evaluate_texture(t, 0, at({0.5f, 0.5f, 0.5f})), RGB(1));
  EXPECT_EQ(evaluate_texture(t, 0, at({1.5f, 0.5f, 0.5f})), RGB(0));
  EXPECT_EQ(evaluate_texture(t, 0, at({1.5f, -0.5f, 0.5f})), RGB(1));
  EXPECT_EQ(evaluate_texture(t, 0, at({1.5f, -0.5f, -0.5f})), RGB(0));
}

// pbrt-v4: amount = |n . dir|, amount tex1 + (1 - amount) tex2.
TEST(Textures, DirectionMixWeighsByTheNormalsCosineToDir) {
  std::vector<Texture> t(2);
  t[0].type = Texture::Type::Constant;
  t[0].value = RGB(0.2f, 0.4f, 0.6f);
  t[1].type = Texture::Type::DirectionMix;
  t[1].tex1 = 0;
  t[1].value2 = RGB(1, 0, 0);
  t[1].dir = {0, 1, 0};
  EXPECT_EQ(evaluate_texture(t, 1, at({0, 0, 0}, {0, 1, 0})), RGB(0.2f, 0.4f, 0.6f));
  EXPECT_EQ(evaluate_texture(t, 1, at({0, 0, 0}, {0, -1, 0})), RGB(0.2f, 0.4f, 0.6f));  // |cos|
  EXPECT_EQ(evaluate_texture(t, 1, at({0, 0, 0}, {1, 0, 0})), RGB(1, 0, 0));
  const RGB half = evaluate_texture(t, 1, at({0, 0, 0}, {std::sqrt(3.0f) / 2, 0.5f, 0}));  // cos 60 deg
  EXPECT_NEAR(half[0], 0.5f * 0.2f + 0.5f, 1e-6f);
  EXPECT_NEAR(half[2], 0.5f * 0.6f, 1e-6f);
}

// The dots' definition, checked cell by cell against the noise (PBR book 3rd ed. §10.5.3):
// no dot where noise at the cell centre is <= 0; elsewhere the shifted centre is inside and
// points 0.36 away from it are not.
TEST(Textures, DotsLieWhereTheNoiseSaysWithRadius035) {
  int cells_with_dots = 0;
  for (int i = -20; i < 20; ++i)
    for (int j = -20; j < 20; ++j) {
      const float si = float(i), tj = float(j);
      const bool dot = perlin_noise(si + 0.5f, tj + 0.5f) > 0;
      const Vec2 centre(si + 0.15f * perlin_noise(si + 1.5f, tj + 2.8f),
                        tj + 0.15f * perlin_noise(si + 4.5f, tj + 9.8f));
      EXPECT_EQ(inside_polka_dot(centre), dot) << i << " " << j;
      EXPECT_FALSE(inside_polka_dot(centre + Vec2(0.36f, 0)));
      EXPECT_FALSE(inside_polka_dot(centre + Vec2(0, -0.36f)));
      EXPECT_EQ(inside_polka_dot(centre + Vec2(0.24f, 0.24f)), dot);  // 0.339 < 0.35
      cells_with_dots += dot;
    }
  EXPECT_GT(cells_with_dots, 400);  // about half of 1600
  EXPECT_LT(cells_with_dots, 1200);
  std::vector<Texture> t(1);
  t[0].type = Texture::Type::Dots;
  t[0].value = RGB(0.9f);
  t[0].value2 = RGB(0.1f);
  t[0].mapping.su = 1;
  int inside = 0, n = 0;
  for (float u = -5; u < 5; u += 0.05f)
    for (float v = -5; v < 5; v += 0.05f, ++n) {
      const RGB x = evaluate_texture(t, 0, Vec2(u, v));
      ASSERT_TRUE(x == RGB(0.9f) || x == RGB(0.1f));
      inside += x == RGB(0.9f);
    }
  // Area fraction: about half the cells hold a disc of area pi 0.35^2 = 0.385.
  EXPECT_GT(double(inside) / n, 0.1);
  EXPECT_LT(double(inside) / n, 0.3);
}

TEST(Textures, NoiseTexturesAreTheirSumsInTextureSpace) {
  std::vector<Texture> t(4);
  for (Texture& x : t) {
    x.mapping.kind = TextureMapping::Kind::Point3D;
    x.mapping.texture_from_world = Transform::translate({-10, 0, 0});
    x.octaves = 1;
    x.omega = 0.5f;
  }
  t[0].type = Texture::Type::FBm;
  t[1].type = Texture::Type::Wrinkled;
  t[2].type = Texture::Type::Windy;
  t[3].type = Texture::Type::Marble;
  t[3].variation = 0;
  // World (13, -4, 5) is the lattice point (3, -4, 5) of texture space.
  EXPECT_EQ(evaluate_texture(t, 0, at({13, -4, 5})), RGB(0));
  EXPECT_FLOAT_EQ(evaluate_texture(t, 1, at({13, -4, 5}))[0], 0.1f);  // 0 + 0.2 omega
  const Vec3 p(10.3f, 1.7f, -2.2f), q(0.3f, 1.7f, -2.2f);
  // (the texture-space point goes through a float matrix: equal to a few ulps)
  EXPECT_NEAR(evaluate_texture(t, 0, at(p))[1], perlin_noise(q), 1e-5f);
  EXPECT_NEAR(evaluate_texture(t, 2, at(p))[2], std::abs(fbm(q * 0.1f, 0.5f, 3)) * fbm(q, 0.5f, 6), 1e-5f);
  // Marble with no variation: t = 1/2 + sin(y) / 2; y = 0 is the middle of the spline (colour 3
  // of 9, times 1.5); sin(y) = -1 is its start (colour 0, times 1.5).
  EXPECT_NEAR(evaluate_texture(t, 3, at({10, 0, 0}))[0], 0.75f, 1e-6f);
  const RGB start = evaluate_texture(t, 3, at({10, -kPi / 2, 0}));
  EXPECT_NEAR(start[0], 0.87f, 1e-5f);
  EXPECT_NEAR(start[2], 0.9f, 1e-5f);
  EXPECT_NEAR(marble_color(1)[2], 0.9f, 1e-5f);
  EXPECT_NEAR(marble_color(7.0f / 12)[2], 1.5f * (0.125f * 0.5f + 0.375f * 0.58f + 0.375f * 0.6f + 0.125f * 0.6f),
              1e-5f);  // segment 3 at x = 1/2: Bernstein weights 1/8 3/8 3/8 1/8
}

}  // namespace
}  // namespace dermis
