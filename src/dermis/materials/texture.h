// RGB textures as pbrt-v4 defines them: constants, image maps (bilinear lookup), scale,
// mix, directionmix, bilerp, the 2D checkerboard, dots, and the noise textures fbm,
// wrinkled, windy and marble; with pbrt-v4's 2D mappings (uv, spherical, cylindrical,
// planar) and its 3D mapping (the point in the texture's space).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/transform.h"
#include "dermis/core/vec.h"
#include "dermis/geometry/ray.h"

namespace dermis {

struct ImageData {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear, row-major, top row first
};

// Where a texture is looked up: the world-space point, the geometric normal and the
// surface's (u, v).
struct TextureContext {
  Vec3 p{0, 0, 0};
  Vec3 n{0, 0, 1};
  Vec2 uv{0, 0};
};

// pbrt-v4's texture mappings. 2D: uv (s = su u + du, t = sv v + dv), spherical,
// cylindrical, planar; 3D: the point in texture space (Point3D).
struct TextureMapping {
  enum class Kind { UV, Spherical, Cylindrical, Planar, Point3D };
  Kind kind = Kind::UV;
  float su = 1, sv = 1, du = 0, dv = 0;  // uv; du, dv also offset planar
  Transform texture_from_world;          // all but uv: the inverse of the CTM at the Texture directive
  Vec3 vs{1, 0, 0}, vt{0, 1, 0};         // planar: the two axes

  Vec2 st(const TextureContext& c) const;                                              // 2D mappings
  Vec3 point(const TextureContext& c) const { return texture_from_world.point(c.p); }  // 3D
};

struct Texture {
  enum class Type {
    Constant,
    Image,
    Scale,
    Checkerboard,
    Mix,
    DirectionMix,
    Bilerp,
    Dots,
    FBm,
    Wrinkled,
    Windy,
    Marble
  };
  enum class Wrap { Repeat, Black, Clamp };
  Type type = Type::Constant;
  RGB value{1, 1, 1};
  std::shared_ptr<const ImageData> image;
  float scale = 1;  // Image, Scale: the factor; Marble: the frequency
  bool invert = false;
  Wrap wrap = Wrap::Repeat;
  TextureMapping mapping;
  int base = -1;  // Scale: the texture scaled, or -1 for `value`
  // Checkerboard, Mix, DirectionMix: tex1 (`value` or texture tex1) and tex2 (`value2` or
  // tex2); Dots: inside (value / tex1) and outside (value2 / tex2).
  RGB value2{0, 0, 0};
  int tex1 = -1, tex2 = -1;
  float amount = 0.5f;           // Mix: the weight of tex2 ...
  int amount_texture = -1;       // ... or a float texture for it (its first channel)
  Vec3 dir{0, 1, 0};             // DirectionMix: unit, world space
  std::array<RGB, 4> corners{};  // Bilerp: v00, v01, v10, v11
  int octaves = 8;               // FBm, Wrinkled, Marble
  float omega = 0.5f;            // FBm, Wrinkled, Marble: pbrt-v4's "roughness"
  float variation = 0.2f;        // Marble
};

// Evaluates texture `index` of `textures` at `c`. Float textures hold their value in all
// three channels. No allocation.
RGB evaluate_texture(const std::vector<Texture>& textures, int index, const TextureContext& c);
inline RGB evaluate_texture(const std::vector<Texture>& textures, int index, Vec2 uv) {
  TextureContext c;
  c.uv = uv;
  return evaluate_texture(textures, index, c);
}

inline TextureContext texture_context(const SurfaceHit& hit) { return {hit.p, hit.ng, hit.uv}; }

// pbrt-v4's polka dots at (s, t): one dot of radius 0.35 in about half of the unit cells
// centred on integers, shifted by up to 0.15 by noise.
bool inside_polka_dot(Vec2 st);

// pbrt-v4's marble colour for the noise-perturbed stripe parameter t in [0, 1].
RGB marble_color(float t);

}  // namespace dermis
