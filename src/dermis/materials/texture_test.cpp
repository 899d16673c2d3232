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

}  // namespace
}  // namespace dermis
