#include "dermis/materials/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dermis/materials/noise.h"

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

// tex1/value or tex2/value2 of a texture with two inputs.
RGB first(const std::vector<Texture>& textures, const Texture& t, const TextureContext& c) {
  return t.tex1 >= 0 ? evaluate_texture(textures, t.tex1, c) : t.value;
}
RGB second(const std::vector<Texture>& textures, const Texture& t, const TextureContext& c) {
  return t.tex2 >= 0 ? evaluate_texture(textures, t.tex2, c) : t.value2;
}

}  // namespace

Vec2 TextureMapping::st(const TextureContext& c) const {
  switch (kind) {
    case Kind::UV:
      return {su * c.uv.x + du, sv * c.uv.y + dv};
    case Kind::Spherical: {
      // PBR book (4th ed.) §10.2.1, spherical mapping: (theta / pi, phi / 2pi) of the direction to the point.
      const Vec3 q = texture_from_world.point(c.p);
      const float len = length(q);
      if (!(len > 0)) return {0, 0};
      const float theta = std::acos(std::clamp(q.z / len, -1.0f, 1.0f));
      float phi = std::atan2(q.y, q.x);
      if (phi < 0) phi += 2 * kPi;
      return {theta / kPi, phi / (2 * kPi)};
    }
    case Kind::Cylindrical: {
      // PBR book (4th ed.) §10.2.1, cylindrical mapping: ((pi + atan2(y, x)) / 2pi, z).
      const Vec3 q = texture_from_world.point(c.p);
      return {(kPi + std::atan2(q.y, q.x)) / (2 * kPi), q.z};
    }
    case Kind::Planar: {
      // PBR book (4th ed.) §10.2.1, planar mapping: (ds + p . vs, dt + p . vt).
      const Vec3 q = texture_from_world.point(c.p);
      return {du + dot(q, vs), dv + dot(q, vt)};
    }
    case Kind::Point3D:
      break;
  }
  return c.uv;
}

bool inside_polka_dot(Vec2 st) {
  // PBR book (3rd ed.) §10.5.3: the cell around the nearest integer point holds a dot when
  // noise at its centre is positive; the dot's centre is shifted by noise, within the cell.
  const float s_cell = std::floor(st.x + 0.5f), t_cell = std::floor(st.y + 0.5f);
  if (!(perlin_noise(s_cell + 0.5f, t_cell + 0.5f) > 0)) return false;
  constexpr float kRadius = 0.35f, kMaxShift = 0.5f - kRadius;
  const float s_center = s_cell + kMaxShift * perlin_noise(s_cell + 1.5f, t_cell + 2.8f);
  const float t_center = t_cell + kMaxShift * perlin_noise(s_cell + 4.5f, t_cell + 9.8f);
  const float ds = st.x - s_center, dt = st.y - t_center;
  return ds * ds + dt * dt < kRadius * kRadius;
}

RGB marble_color(float t) {
  // PBR book (3rd ed.) §10.6.4, MarbleTexture: a cubic Bezier spline through these colours
  // (overlapping windows of 4), scaled by 1.5.
  static constexpr float kColors[9][3] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                          {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                          {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
  constexpr int kSegments = 9 - 3;
  t = std::clamp(t, 0.0f, 1.0f);
  const int first = std::min(int(std::floor(t * kSegments)), kSegments - 1);
  const float x = t * kSegments - float(first);
  // Cubic Bernstein weights (1 - x)^3, 3x(1 - x)^2, 3x^2(1 - x), x^3.
  const float w[4] = {(1 - x) * (1 - x) * (1 - x), 3 * x * (1 - x) * (1 - x), 3 * x * x * (1 - x), x * x * x};
  RGB c(0);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) c[k] += w[i] * kColors[first + i][k];
  return c * 1.5f;
}

RGB evaluate_texture(const std::vector<Texture>& textures, int index, const TextureContext& c) {
  const Texture& t = textures[index];
  switch (t.type) {
    case Texture::Type::Constant:
      return t.value;
    case Texture::Type::Scale: {
      RGB base = t.base >= 0 ? evaluate_texture(textures, t.base, c) : t.value;
      return base * t.scale;
    }
    case Texture::Type::Mix: {
      // pbrt-v4: (1 - amount) tex1 + amount tex2.
      const float a = t.amount_texture >= 0 ? evaluate_texture(textures, t.amount_texture, c)[0] : t.amount;
      return first(textures, t, c) * (1 - a) + second(textures, t, c) * a;
    }
    case Texture::Type::DirectionMix: {
      // pbrt-v4: amount = |n . dir|; amount tex1 + (1 - amount) tex2.
      const float a = std::min(std::abs(dot(c.n, t.dir)), 1.0f);
      return first(textures, t, c) * a + second(textures, t, c) * (1 - a);
    }
    case Texture::Type::Bilerp: {
      // pbrt-v4: bilinear between v00, v01, v10, v11 at (s, t).
      const Vec2 st = t.mapping.st(c);
      const float s = st.x, tt = st.y;
      return t.corners[0] * ((1 - s) * (1 - tt)) + t.corners[1] * ((1 - s) * tt) + t.corners[2] * (s * (1 - tt)) +
             t.corners[3] * (s * tt);
    }
    case Texture::Type::Checkerboard: {
      // pbrt-v4: tex1 where floor(s) + floor(t) (3D: floor(x) + floor(y) + floor(z)) is even.
      int64_t cells = 0;
      if (t.mapping.kind == TextureMapping::Kind::Point3D) {
        const Vec3 p = t.mapping.point(c);
        cells = int64_t(std::floor(double(p.x))) + int64_t(std::floor(double(p.y))) + int64_t(std::floor(double(p.z)));
      } else {
        const Vec2 st = t.mapping.st(c);
        cells = int64_t(std::floor(double(st.x))) + int64_t(std::floor(double(st.y)));
      }
      const bool even = (cells & 1) == 0;
      return even ? first(textures, t, c) : second(textures, t, c);
    }
    case Texture::Type::Dots:
      return inside_polka_dot(t.mapping.st(c)) ? first(textures, t, c) : second(textures, t, c);
    case Texture::Type::FBm:
      return RGB(fbm(t.mapping.point(c), t.omega, t.octaves));
    case Texture::Type::Wrinkled:
      return RGB(turbulence(t.mapping.point(c), t.omega, t.octaves));
    case Texture::Type::Windy: {
      // PBR book (3rd ed.) §10.6.3: |fBm at 1/10 the frequency| (wind strength) times fBm (wave height).
      const Vec3 p = t.mapping.point(c);
      return RGB(std::abs(fbm(p * 0.1f, 0.5f, 3)) * fbm(p, 0.5f, 6));
    }
    case Texture::Type::Marble: {
      // PBR book (3rd ed.) §10.6.4: stripes along y, perturbed by fBm: t = 1/2 + sin(y + variation fBm(p)) / 2.
      const Vec3 p = t.mapping.point(c) * t.scale;
      const float m = p.y + t.variation * fbm(p, t.omega, t.octaves);
      return marble_color(0.5f + 0.5f * std::sin(m));
    }
    case Texture::Type::Image: {
      const ImageData& img = *t.image;
      // pbrt flips t: row 0 of the image is at t = 1.
      const Vec2 st = t.mapping.st(c);
      float s = st.x, tt = 1 - st.y;
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
