// The `volumetric` reference with textured parameters (docs/materials.md): a path that
// enters the object takes the medium coefficients of its entry point, as the random
// walk does, and keeps them while inside; the volumetric path tracer then renders it
// as a homogeneous medium. (A medium that varies along the path would need delta or
// ratio tracking: not this.)
#pragma once

#include "dermis/geometry/ray.h"
#include "dermis/materials/medium.h"
#include "dermis/render/render_scene.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis {

// The entry in scene.volumetric_media of `medium` when its parameters are textured, else -1.
inline int textured_volumetric(const RenderScene& scene, int medium) {
  return medium >= 0 && medium < int(scene.textured_volumetric_of_medium.size())
             ? scene.textured_volumetric_of_medium[medium]
             : -1;
}

// The entry in scene.volumetric_media of `medium`, textured or not, else -1.
int volumetric_of_medium(const RenderScene& scene, int medium);

// The medium of volumetric entry `v` at the surface point `entry`: its textures there,
// (reflectance, mfp) turned into coefficients by the same dielectric table as the
// constants (a lookup; allocates nothing). At the wavelengths `w` when given: the
// parameters read at them (subsurface/coefficients.h medium_at_wavelengths) and inverted
// per wavelength, as the random walk does.
HomogeneousMedium volumetric_medium_at(const RenderScene& scene, int v, const SurfaceHit& entry,
                                       const SampledWavelengths* w = nullptr);
// The medium of volumetric entry `v`'s constant parameters at the wavelengths `w`.
HomogeneousMedium volumetric_medium_at_wavelengths(const RenderScene& scene, int v, const SampledWavelengths& w);

}  // namespace dermis
