// A BSDF or a medium made from RGB parameters read at a spectral path's wavelengths: each
// RGB field becomes the values at those wavelengths of its spectrum (spectral/spectrum_at.h),
// reflectances as reflectances, a conductor's eta and k and a medium's coefficients as
// unbounded spectra, as pbrt-v4 reads them. The index of a dielectric is one number here:
// no dispersion.
#pragma once

#include "dermis/materials/bsdf.h"
#include "dermis/materials/medium.h"
#include "dermis/spectral/spectrum_at.h"

namespace dermis {

inline BSDF bsdf_at_wavelengths(BSDF b, const SampledWavelengths& w) {
  switch (b.type) {  // the fields each type reads
    case BSDF::Type::Diffuse:
      b.albedo = reflectance_at(b.albedo, w);
      break;
    case BSDF::Type::DiffuseTransmission:
      b.albedo = reflectance_at(b.albedo, w);
      b.transmittance = reflectance_at(b.transmittance, w);
      break;
    case BSDF::Type::Conductor:
      b.cond_eta = unbounded_at(b.cond_eta, w);
      b.cond_k = unbounded_at(b.cond_k, w);
      break;
    case BSDF::Type::Coated:
      if (b.coat.base == CoatedLayer::Base::Diffuse) {
        b.coat.base_reflectance = reflectance_at(b.coat.base_reflectance, w);
      } else {
        b.coat.conductor_eta = unbounded_at(b.coat.conductor_eta, w);
        b.coat.conductor_k = unbounded_at(b.coat.conductor_k, w);
      }
      if (!b.coat.albedo.is_black()) b.coat.albedo = reflectance_at(b.coat.albedo, w);
      break;
    case BSDF::Type::Dielectric:
    case BSDF::Type::SubsurfaceExit:
      break;
  }
  return b;
}

inline HomogeneousMedium medium_at_wavelengths(const HomogeneousMedium& m, const SampledWavelengths& w) {
  return HomogeneousMedium::from_coefficients(unbounded_at(m.sigma_a, w), unbounded_at(m.sigma_s, w), 1, m.g);
}

}  // namespace dermis
