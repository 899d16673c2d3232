// A subsurface material's boundary roughness at a surface point (pbrt-v4's `roughness`,
// Trowbridge-Reitz alphas): its constants, or its "roughness" float texture evaluated at
// the point (isotropic; negative values taken as 0, alpha = sqrt(r) when remapped, as
// pbrt-v4 and the `dielectric` material do). What depends on the roughness beyond the
// microfacet BSDF at a hit (the exit lobe's transmittance, the walk's albedo inversion)
// is tabulated at alpha nodes on [0, 1] and interpolated in alpha at the point (an alpha
// above 1 takes the tables of alpha 1).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "dermis/core/microfacet.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/texture.h"
#include "dermis/scene/subsurface_params.h"

namespace dermis {

struct BoundaryAlphas {
  float x = 0, y = 0;  // 0 on both: smooth
  bool rough() const { return std::max(x, y) >= kSmoothAlpha; }
};

class BoundaryRoughness {
 public:
  BoundaryRoughness() = default;
  // matched: the boundary is index-matched (a `matched` walk): smooth whatever the
  // parameters say. textures: the scene's (must outlive this); null ignores a texture.
  BoundaryRoughness(const SubsurfaceParams& params, bool matched, const std::vector<Texture>* textures) {
    if (matched) return;
    remap_ = params.remap_roughness;
    if (params.roughness_texture >= 0 && textures) {
      texture_ = params.roughness_texture;
      textures_ = textures;
      return;
    }
    constant_ = {roughness_to_alpha(params.uroughness, remap_), roughness_to_alpha(params.vroughness, remap_)};
    if (!constant_.rough()) constant_ = {};
  }

  bool textured() const { return texture_ >= 0; }
  // The constant alphas (a textured boundary: zero).
  BoundaryAlphas constant() const { return constant_; }

  BoundaryAlphas at(const SurfaceHit& hit) const {
    if (texture_ < 0) return constant_;
    const float r = evaluate_texture(*textures_, texture_, texture_context(hit))[0];
    const float alpha = roughness_to_alpha(std::isfinite(r) ? r : 0.0f, remap_);
    return alpha >= kSmoothAlpha ? BoundaryAlphas{alpha, alpha} : BoundaryAlphas{};
  }

 private:
  BoundaryAlphas constant_;
  int texture_ = -1;
  bool remap_ = true;
  const std::vector<Texture>* textures_ = nullptr;
};

}  // namespace dermis
