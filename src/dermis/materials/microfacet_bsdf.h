// The rough lobes over the Trowbridge-Reitz distribution (materials/microfacet.h): the
// rough dielectric (Walter et al. 2007, "Microfacet Models for Refraction through Rough
// Surfaces") and the rough conductor (a Fresnel conductor on each microfacet). In the
// local shading frame, z along the macro normal; wo and wi point away from the surface.
// bsdf.cpp takes them there from world space.
//
// Sampling (the dielectric's in core/microfacet.h): a microfacet normal m from the
// normals visible from wo (Heitz 2018), then reflection about m, or for the dielectric
// refraction through it, chosen with the microfacet's Fresnel reflectance F(wo.m). A
// reflection that leaves below the surface (or a refraction that comes back up) is
// lost: the sampler returns nothing, and the pdf integrates to one minus the
// probability of that.
#pragma once

#include <optional>

#include "dermis/core/microfacet.h"
#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

// Rough dielectric. eta: index on the -z side over the index on the +z side (the BSDF's
// convention). Values are f(wo, wi) |cos wi| with transmitted radiance scaled by
// 1 / etap^2 (Veach 1997, sec. 5.2), as for the smooth dielectric.
float rough_dielectric_eval(const TrowbridgeReitz& d, float eta, Vec3 wo, Vec3 wi);
// Solid-angle density of rough_dielectric_sample choosing wi (lobe choice included).
float rough_dielectric_pdf(const TrowbridgeReitz& d, float eta, Vec3 wo, Vec3 wi);
// rough_dielectric_sample is in core/microfacet.h (the half-space simulator samples it too).

// Rough conductor with complex index eta + i k, reflecting on both sides like the
// smooth one (on the side of wo).
RGB rough_conductor_eval(const TrowbridgeReitz& d, RGB eta, RGB k, Vec3 wo, Vec3 wi);
float rough_conductor_pdf(const TrowbridgeReitz& d, Vec3 wo, Vec3 wi);
std::optional<MicrofacetSample> rough_conductor_sample(const TrowbridgeReitz& d, Vec3 wo, Vec2 u);

}  // namespace dermis
