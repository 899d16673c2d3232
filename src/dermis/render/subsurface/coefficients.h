// A subsurface material's parameters as the methods need them: scattering
// coefficients per scene unit (the random walk, the volumetric reference), or the
// surface albedo and mean free path per channel (the diffusion profiles).
#pragma once

#include "dermis/core/rgb.h"
#include "dermis/scene/subsurface_params.h"

namespace dermis {

struct Coefficients {
  RGB sigma_a, sigma_s;
};

// As given, or from (reflectance, mfp) through the random walk's exact albedo inversion:
// a half-space table for the boundary's eta and g (sss/walk/albedo_inversion.h), built
// once per process (and cached on disk by the table itself). May take seconds the first
// time: call it while preparing a scene, not while rendering.
Coefficients resolve_coefficients(const SubsurfaceParams& params);

struct AlbedoAndMfp {
  RGB albedo, mfp;
};

// Surface albedo A and mean free path l per channel: as given, or from coefficients
// by l = 1/sigma_t' and A = 1 - H(1) sqrt(1 - alpha') (Chandrasekhar 1950, METHODS.md
// sec. 6), alpha' the similarity-reduced single-scattering albedo: the searchlight,
// index-matched configuration the Christensen-Burley fit was made for.
AlbedoAndMfp albedo_and_mfp(const SubsurfaceParams& params);

}  // namespace dermis
