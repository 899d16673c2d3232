#include "dermis/materials/texture.h"

#include <gtest/gtest.h>

namespace dermis {
namespace {

TEST(Textures, CheckerboardAlternatesBySquareAsPbrtV4) {
  std::vector<Texture> t(2);
  t[0].type = Texture::Type::Constant;
  t[0].value = RGB(0.25f);
  t[1].type = Texture::Type::Checkerboard;
  t[1].tex1 = 0;           // a texture
  t[1].value2 = RGB(0.75f);  // a value
  t[1].uscale = 2;
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
