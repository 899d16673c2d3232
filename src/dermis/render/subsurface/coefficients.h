// A subsurface material's parameters as the methods need them: scattering
// coefficients per scene unit (the random walk, the volumetric reference), or the
// surface albedo and mean free path per channel (the diffusion profiles) — for the
// material as a whole, or at one surface point when its parameters are textured.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"
#include "dermis/materials/texture.h"
#include "dermis/render/process_group.h"
#include "dermis/scene/subsurface_params.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis::sss {
class AlbedoInversion;
}

namespace dermis {

// The medium's parameters at one point, as the user gave them (scale applied): either
// coefficients or (reflectance, mfp).
struct MediumAt {
  std::optional<RGB> sigma_a, sigma_s, reflectance, mfp;
  float scale = 1;  // the scale there (already applied above): the material's, times its texture
};

// The material's textures evaluated at `at` (textures: the scene's; reflectance clamped
// to [0, 1], lengths and coefficients kept positive). Without textures: the constants.
MediumAt medium_at(const SubsurfaceParams& params, const std::vector<Texture>* textures = nullptr,
                   const TextureContext& at = {});

// The medium at a spectral path's wavelengths (spectral/spectrum_at.h), read as pbrt-v4
// reads a subsurface material: the reflectance as a reflectance spectrum, the coefficients
// and the mean free path as unbounded spectra. Each channel is then one wavelength, and
// everything made from it per channel (the albedo inversion, the profiles, the walk's
// medium) is made per wavelength. A parameter the material gives as a spectrum (`params`'
// *_spectrum, not textured) is read as that spectrum, times the scale at the point.
MediumAt medium_at_wavelengths(const SubsurfaceParams& params, MediumAt at, const SampledWavelengths& w);

struct Coefficients {
  RGB sigma_a, sigma_s;
};

// The exact albedo inversion of the random walk for this material's boundary, eta and
// g (sss/walk/albedo_inversion.h): a half-space table built once per process (and
// cached on disk by the table itself; may take seconds the first time: call it while
// preparing a scene). Null when the material gives coefficients or asks for the fit.
// A textured roughness: the smooth boundary's table (see AlbedoInversions).
const sss::AlbedoInversion* albedo_inversion_for(const SubsurfaceParams& params);

// A material's exact albedo inversions: its one table, or, when its roughness is
// textured, one table per boundary alpha (k / 8)^2 (k = 0 .. 8; uniform in sqrt(alpha),
// where A_max of a rough `dielectric` boundary changes fastest near 0) between which the
// surface albedo A(single-scattering albedo) is interpolated linearly in sqrt(alpha) at
// the entry point and inverted (the error this makes is measured in docs/materials.md).
// Empty: coefficients, or the fit.
class AlbedoInversions {
 public:
  static constexpr int kAlphaNodes = 9;
  AlbedoInversions() = default;
  explicit AlbedoInversions(const SubsurfaceParams& params);  // makes or looks up the tables

  bool empty() const { return tables_.empty(); }
  // alpha(A) at the boundary alpha (ignored with one table).
  double single_scattering_albedo(double surface_albedo, float boundary_alpha) const;
  // The one table (null when interpolated in alpha, or empty).
  const sss::AlbedoInversion* single() const { return tables_.size() == 1 ? tables_[0] : nullptr; }

 private:
  std::vector<const sss::AlbedoInversion*> tables_;
};

// Makes the tables these materials need now (albedo_inversion_for then only looks them
// up), shared by the group: rank 0 reads each from the cache and broadcasts it, or
// the processes simulate its nodes in shares and gather them (the nodes are
// independent), and rank 0 writes the cache. Every process calls it.
void prepare_albedo_inversions(std::span<const SubsurfaceParams> params, ProcessGroup& group);

// Coefficients per scene unit: as given, or from (reflectance, mfp) through `table`
// (albedo_inversion_for) or, when null, van de Hulst's fit.
Coefficients coefficients_from(const MediumAt& medium, const sss::AlbedoInversion* table);
// The same through a material's inversions at the boundary alpha of the entry point
// (empty: van de Hulst's fit).
Coefficients coefficients_from(const MediumAt& medium, const AlbedoInversions& inversions, float boundary_alpha);
inline Coefficients resolve_coefficients(const SubsurfaceParams& params) {
  return coefficients_from(medium_at(params), albedo_inversion_for(params));
}

struct AlbedoAndMfp {
  RGB albedo, mfp;
};

// Surface albedo A and mean free path l per channel: as given, or from coefficients
// by l = 1/sigma_t' and A = 1 - H(1) sqrt(1 - alpha') (Chandrasekhar 1950, METHODS.md
// sec. 6), alpha' the similarity-reduced single-scattering albedo: the searchlight,
// index-matched configuration the Christensen-Burley fit was made for.
AlbedoAndMfp albedo_and_mfp(const MediumAt& medium, float g);
inline AlbedoAndMfp albedo_and_mfp(const SubsurfaceParams& params) {
  return albedo_and_mfp(medium_at(params), params.g);
}

}  // namespace dermis
