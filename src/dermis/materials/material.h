// Materials as the renderer holds them; bsdf_at() makes the BSDF at a hit.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "dermis/core/microfacet.h"
#include "dermis/core/rgb.h"
#include "dermis/core/rng.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/texture.h"

namespace dermis {

struct Material {
  enum class Type { Diffuse, Dielectric, Conductor, Interface, Subsurface, Coated, DiffuseTransmission, Mix };
  Type type = Type::Diffuse;
  RGB reflectance{0.5f, 0.5f, 0.5f};  // Diffuse, DiffuseTransmission; Coated: a diffuse base's
  int reflectance_texture = -1;
  RGB transmittance{0.25f, 0.25f, 0.25f};  // DiffuseTransmission
  int transmittance_texture = -1;
  float scale = 1;   // DiffuseTransmission: factor of both, pbrt-v4's "scale"
  CoatedLayer coat;  // Coated: the stack (its base reflectance from `reflectance` above)
  // Mix: the two materials (indices), the second chosen with probability `amount`.
  int mix[2] = {-1, -1};
  float amount = 0.5f;
  int amount_texture = -1;  // a float texture for amount, or -1
  float eta = 1.5f;
  // The conductor's eta and k as spectra (RenderScene::spectra; -1: the RGB below), for
  // spectral rendering (render/path/surface_vertex.cpp).
  int cond_eta_data = -1, cond_k_data = -1;
  // The same for the reflectance (Diffuse, DiffuseTransmission, a Coated diffuse base) and
  // the transmittance (DiffuseTransmission) given as spectra.
  int reflectance_data = -1, transmittance_data = -1;
  // Dielectric: its index as a spectrum (RenderScene::spectra; -1: `eta` at every wavelength):
  // dispersion, which keeps one wavelength of a spectral path (render/path/surface_vertex.cpp).
  int eta_data = -1;
  RGB cond_eta, cond_k;
  // Dielectric, Conductor: Trowbridge-Reitz alpha along the two tangent axes (after
  // pbrt-v4's remaproughness); 0 (below kSmoothAlpha): smooth.
  float alpha_x = 0, alpha_y = 0;
  // Textured parameters (float textures, -1: the constants): roughness along the two axes
  // (Dielectric, Conductor, Coated's interface; Coated's conductor base), mapped to alpha per
  // hit as pbrt-v4 does (remap: alpha = sqrt(roughness)); Coated's thickness and g, and its
  // albedo (a spectrum texture). Conductor and a Coated conductor base given a textured
  // `reflectance` take eta = 1 and k from it per hit.
  int roughness_texture[2] = {-1, -1};
  int base_roughness_texture[2] = {-1, -1};
  bool remap_roughness = true;
  int thickness_texture = -1, g_texture = -1, albedo_texture = -1;
  int subsurface = -1;  // Subsurface: index into RenderScene::subsurface

  // Interfaces only mark a change of medium; rays pass straight through them.
  bool is_interface() const { return type == Type::Interface; }
};

// The material a hit uses: a mix material (pbrt-v4's MixMaterial) chooses one of its two
// per hit, the second with probability amount (amount <= 0: the first, >= 1: the
// second), by a uniform number hashed from the hit point, wo and `sample_key` (the pixel
// sample and path vertex: Sampler::sample_hash), nested mixes in turn. An unbiased
// one-sample estimate of (1 - amount) f_1 + amount f_2 that adds no dimension; the pixel
// sample enters the hash so that the samples of a pixel-centre ray do not all choose alike.
inline int resolve_material(const std::vector<Material>& materials, const std::vector<Texture>& textures, int index,
                            const SurfaceHit& hit, Vec3 wo, uint64_t sample_key) {
  auto bits = [](Vec3 v) {
    return mix64((uint64_t(std::bit_cast<uint32_t>(v.x)) << 32 | std::bit_cast<uint32_t>(v.y)) ^
                 mix64(std::bit_cast<uint32_t>(v.z)));
  };
  for (uint64_t level = 0; level < 64 && materials[index].type == Material::Type::Mix; ++level) {
    const Material& m = materials[index];
    const float a = m.amount_texture >= 0 ? evaluate_texture(textures, m.amount_texture, hit.uv)[0] : m.amount;
    const float u = float(mix64(sample_key ^ bits(hit.p) ^ mix64(bits(wo) + level)) >> 40) * 0x1p-24f;
    index = a <= 0 ? m.mix[0] : a >= 1 ? m.mix[1] : (u < a ? m.mix[1] : m.mix[0]);
  }
  return index;
}

// pbrt-v4's conductor from a reflectance r: eta = 1, k = 2 sqrt(r) / sqrt(1 - r) (r below 1).
inline RGB conductor_k_from_reflectance(RGB r) {
  RGB k;
  for (int c = 0; c < 3; ++c) {
    const float rc = std::clamp(r[c], 0.0f, 0.9999f);
    k[c] = 2 * std::sqrt(rc) / std::sqrt(1 - rc);
  }
  return k;
}

// A float texture's value at the hit, or `constant` where there is none.
inline float textured_float(const std::vector<Texture>& textures, int texture, float constant, const SurfaceHit& hit) {
  return texture >= 0 ? evaluate_texture(textures, texture, texture_context(hit))[0] : constant;
}

// Roughness along the two axes as alpha: the constants, or the textures mapped per hit.
inline void textured_alpha(const std::vector<Texture>& textures, const int texture[2], bool remap,
                           const SurfaceHit& hit, float& alpha_x, float& alpha_y) {
  if (texture[0] >= 0)
    alpha_x = roughness_to_alpha(std::max(0.0f, textured_float(textures, texture[0], 0, hit)), remap);
  if (texture[1] >= 0)
    alpha_y = roughness_to_alpha(std::max(0.0f, textured_float(textures, texture[1], 0, hit)), remap);
}

inline BSDF bsdf_at(const Material& m, const std::vector<Texture>& textures, const SurfaceHit& hit) {
  BSDF b;
  b.n = hit.ns;  // the shading normal (geometry/shading_normal.h)
  switch (m.type) {
    case Material::Type::Coated:
      b.type = BSDF::Type::Coated;
      b.coat = m.coat;
      if (m.coat.base == CoatedLayer::Base::Diffuse) {
        RGB r = m.reflectance_texture >= 0 ? evaluate_texture(textures, m.reflectance_texture, texture_context(hit))
                                           : m.reflectance;
        for (int c = 0; c < 3; ++c) r[c] = std::clamp(r[c], 0.0f, 1.0f);
        b.coat.base_reflectance = r;
      } else if (m.reflectance_texture >= 0) {
        b.coat.conductor_eta = RGB(1);
        b.coat.conductor_k =
            conductor_k_from_reflectance(evaluate_texture(textures, m.reflectance_texture, texture_context(hit)));
      }
      textured_alpha(textures, m.roughness_texture, m.remap_roughness, hit, b.coat.interface_alpha_x,
                     b.coat.interface_alpha_y);
      textured_alpha(textures, m.base_roughness_texture, m.remap_roughness, hit, b.coat.base_alpha_x,
                     b.coat.base_alpha_y);
      // pbrt-v4 clamps a textured thickness to at least its float epsilon and g to (-1, 1).
      if (m.thickness_texture >= 0)
        b.coat.thickness = std::max(textured_float(textures, m.thickness_texture, 0, hit), 0x1p-24f);
      if (m.g_texture >= 0) b.coat.g = std::clamp(textured_float(textures, m.g_texture, 0, hit), -0.99f, 0.99f);
      if (m.albedo_texture >= 0) {
        b.coat.albedo = evaluate_texture(textures, m.albedo_texture, texture_context(hit));
        for (int c = 0; c < 3; ++c) b.coat.albedo[c] = std::clamp(b.coat.albedo[c], 0.0f, 1.0f);
      }
      break;
    case Material::Type::DiffuseTransmission: {
      b.type = BSDF::Type::DiffuseTransmission;
      RGB r = m.reflectance_texture >= 0 ? evaluate_texture(textures, m.reflectance_texture, hit.uv) : m.reflectance;
      RGB t =
          m.transmittance_texture >= 0 ? evaluate_texture(textures, m.transmittance_texture, hit.uv) : m.transmittance;
      for (int c = 0; c < 3; ++c) {  // pbrt-v4 clamps scale * R and scale * T to [0, 1]
        b.albedo[c] = std::clamp(m.scale * r[c], 0.0f, 1.0f);
        b.transmittance[c] = std::clamp(m.scale * t[c], 0.0f, 1.0f);
      }
      break;
    }
    case Material::Type::Mix:  // resolved by resolve_material(); only a cyclic mix gets here: black
      b.type = BSDF::Type::Diffuse;
      b.albedo = RGB(0);
      break;
    case Material::Type::Diffuse:
    case Material::Type::Interface:
    case Material::Type::Subsurface:  // handled by the integrator before any BSDF
      b.type = BSDF::Type::Diffuse;
      b.albedo = m.reflectance_texture >= 0 ? evaluate_texture(textures, m.reflectance_texture, texture_context(hit))
                                            : m.reflectance;
      for (int c = 0; c < 3; ++c) b.albedo[c] = std::clamp(b.albedo[c], 0.0f, 1.0f);
      break;
    case Material::Type::Dielectric:
      b.type = BSDF::Type::Dielectric;
      b.eta = m.eta;
      b.alpha_x = m.alpha_x;
      b.alpha_y = m.alpha_y;
      textured_alpha(textures, m.roughness_texture, m.remap_roughness, hit, b.alpha_x, b.alpha_y);
      break;
    case Material::Type::Conductor:
      b.type = BSDF::Type::Conductor;
      b.cond_eta = m.cond_eta;
      b.cond_k = m.cond_k;
      if (m.reflectance_texture >= 0) {  // only a conductor given a "reflectance" has one
        b.cond_eta = RGB(1);
        b.cond_k =
            conductor_k_from_reflectance(evaluate_texture(textures, m.reflectance_texture, texture_context(hit)));
      }
      b.alpha_x = m.alpha_x;
      b.alpha_y = m.alpha_y;
      textured_alpha(textures, m.roughness_texture, m.remap_roughness, hit, b.alpha_x, b.alpha_y);
      break;
  }
  return b;
}

}  // namespace dermis
