// Materials as the renderer holds them; bsdf_at() makes the BSDF at a hit.
#pragma once

#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/texture.h"

namespace dermis {

struct Material {
  enum class Type { Diffuse, Dielectric, Conductor, Interface, Subsurface };
  Type type = Type::Diffuse;
  RGB reflectance{0.5f, 0.5f, 0.5f};
  int reflectance_texture = -1;
  float eta = 1.5f;
  RGB cond_eta, cond_k;
  // Dielectric, Conductor: Trowbridge-Reitz alpha along the two tangent axes (after
  // pbrt-v4's remaproughness); 0 (below kSmoothAlpha): smooth.
  float alpha_x = 0, alpha_y = 0;
  int subsurface = -1;  // Subsurface: index into RenderScene::subsurface

  // Interfaces only mark a change of medium; rays pass straight through them.
  bool is_interface() const { return type == Type::Interface; }
};

inline BSDF bsdf_at(const Material& m, const std::vector<Texture>& textures, const SurfaceHit& hit) {
  BSDF b;
  b.n = hit.ng;
  switch (m.type) {
    case Material::Type::Diffuse:
    case Material::Type::Interface:
    case Material::Type::Subsurface:  // handled by the integrator before any BSDF
      b.type = BSDF::Type::Diffuse;
      b.albedo = m.reflectance_texture >= 0 ? evaluate_texture(textures, m.reflectance_texture, hit.uv) : m.reflectance;
      for (int c = 0; c < 3; ++c) b.albedo[c] = std::clamp(b.albedo[c], 0.0f, 1.0f);
      break;
    case Material::Type::Dielectric:
      b.type = BSDF::Type::Dielectric;
      b.eta = m.eta;
      b.alpha_x = m.alpha_x;
      b.alpha_y = m.alpha_y;
      break;
    case Material::Type::Conductor:
      b.type = BSDF::Type::Conductor;
      b.cond_eta = m.cond_eta;
      b.cond_k = m.cond_k;
      b.alpha_x = m.alpha_x;
      b.alpha_y = m.alpha_y;
      break;
  }
  return b;
}

}  // namespace dermis
