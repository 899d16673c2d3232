#include "dermis/materials/texture.h"

#include <cmath>
#include <cstdint>

namespace dermis {

namespace {

RGB texel(const ImageData& img, int x, int y, Texture::Wrap wrap) {
  if (wrap == Texture::Wrap::Repeat) {
    x = ((x % img.width) + img.width) % img.width;
    y = ((y % img.height) + img.height) % img.height;
  } else if (wrap == Texture::Wrap::Clamp) {
    x = std::clamp(x, 0, img.width - 1);
    y = std::clamp(y, 0, img.height - 1);
  } else if (x < 0 || y < 0 || x >= img.width || y >= img.height) {
    return RGB(0);
  }
  const float* p = &img.rgb[3 * (std::size_t(y) * img.width + x)];
  return {p[0], p[1], p[2]};
}

}  // namespace

RGB evaluate_texture(const std::vector<Texture>& textures, int index, Vec2 uv) {
  const Texture& t = textures[index];
  switch (t.type) {
    case Texture::Type::Constant:
      return t.value;
    case Texture::Type::Scale: {
      RGB base = t.base >= 0 ? evaluate_texture(textures, t.base, uv) : t.value;
      return base * t.scale;
    }
    case Texture::Type::Mix: {
      // pbrt-v4: (1 - amount) tex1 + amount tex2.
      const float a = t.amount_texture >= 0 ? evaluate_texture(textures, t.amount_texture, uv)[0] : t.amount;
      const RGB a1 = t.tex1 >= 0 ? evaluate_texture(textures, t.tex1, uv) : t.value;
      const RGB a2 = t.tex2 >= 0 ? evaluate_texture(textures, t.tex2, uv) : t.value2;
      return a1 * (1 - a) + a2 * a;
    }
    case Texture::Type::Bilerp: {
      // pbrt-v4: bilinear between v00, v01, v10, v11 at (s, t).
      const float s = uv.x * t.uscale + t.udelta, tt = uv.y * t.vscale + t.vdelta;
      return t.corners[0] * ((1 - s) * (1 - tt)) + t.corners[1] * ((1 - s) * tt) + t.corners[2] * (s * (1 - tt)) +
             t.corners[3] * (s * tt);
    }
    case Texture::Type::Checkerboard: {
      // pbrt-v4: (s, t) = (uscale u + udelta, vscale v + vdelta); tex1 where
      // floor(s) + floor(t) is even.
      const double s = double(uv.x) * t.uscale + t.udelta, tt = double(uv.y) * t.vscale + t.vdelta;
      const bool even = ((int64_t(std::floor(s)) + int64_t(std::floor(tt))) & 1) == 0;
      const int index = even ? t.tex1 : t.tex2;
      return index >= 0 ? evaluate_texture(textures, index, uv) : (even ? t.value : t.value2);
    }
    case Texture::Type::Image: {
      const ImageData& img = *t.image;
      // pbrt flips v: row 0 of the image is at v = 1.
      float s = uv.x * t.uscale + t.udelta, tt = 1 - (uv.y * t.vscale + t.vdelta);
      float x = s * float(img.width) - 0.5f, y = tt * float(img.height) - 0.5f;
      int x0 = int(std::floor(x)), y0 = int(std::floor(y));
      float fx = x - float(x0), fy = y - float(y0);
      RGB v = texel(img, x0, y0, t.wrap) * ((1 - fx) * (1 - fy)) + texel(img, x0 + 1, y0, t.wrap) * (fx * (1 - fy)) +
              texel(img, x0, y0 + 1, t.wrap) * ((1 - fx) * fy) + texel(img, x0 + 1, y0 + 1, t.wrap) * (fx * fy);
      v = v * t.scale;
      if (t.invert) v = RGB(1) - v;
      return v;
    }
  }
  return RGB(0);
}

}  // namespace dermis
