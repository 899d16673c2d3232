// RGB textures: constants, image maps (bilinear lookup), scaled textures, the 2D
// checkerboard, mix and bilerp (pbrt-v4's).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

struct ImageData {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear, row-major, top row first
};

struct Texture {
  enum class Type { Constant, Image, Scale, Checkerboard, Mix, Bilerp };
  enum class Wrap { Repeat, Black, Clamp };
  Type type = Type::Constant;
  RGB value{1, 1, 1};
  std::shared_ptr<const ImageData> image;
  float scale = 1;
  bool invert = false;
  Wrap wrap = Wrap::Repeat;
  float uscale = 1, vscale = 1, udelta = 0, vdelta = 0;
  int base = -1;  // Scale: the texture scaled, or -1 for `value`
  RGB value2{0, 0, 0};       // Checkerboard: value = tex1, value2 = tex2
  int tex1 = -1, tex2 = -1;  // Checkerboard, Mix: the two textures, or -1 for the values
  float amount = 0.5f;       // Mix: the weight of tex2 ...
  int amount_texture = -1;   // ... or a float texture for it (its first channel)
  std::array<RGB, 4> corners{};  // Bilerp: v00, v01, v10, v11
};

// Evaluates texture `index` of `textures` at surface coordinates uv.
RGB evaluate_texture(const std::vector<Texture>& textures, int index, Vec2 uv);

}  // namespace dermis
