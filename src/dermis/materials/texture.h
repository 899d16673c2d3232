// RGB textures: constants, image maps (bilinear lookup) and scaled textures.
#pragma once

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
  enum class Type { Constant, Image, Scale };
  enum class Wrap { Repeat, Black, Clamp };
  Type type = Type::Constant;
  RGB value{1, 1, 1};
  std::shared_ptr<const ImageData> image;
  float scale = 1;
  bool invert = false;
  Wrap wrap = Wrap::Repeat;
  float uscale = 1, vscale = 1, udelta = 0, vdelta = 0;
  int base = -1;  // Scale: the texture scaled
};

// Evaluates texture `index` of `textures` at surface coordinates uv.
RGB evaluate_texture(const std::vector<Texture>& textures, int index, Vec2 uv);

}  // namespace dermis
