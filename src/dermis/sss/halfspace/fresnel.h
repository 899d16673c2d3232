// Exact Fresnel reflectance of a smooth dielectric interface for unpolarised light
// (Born & Wolf, Principles of Optics, 7th ed. 1999, section 1.5.2, the Fresnel formulae),
// and refraction through the plane z = 0 of the half-space.
#pragma once

#include "dermis/core/vec.h"

namespace dermis::sss {

// Reflectance for light arriving with cosine cos_i (in [0, 1], measured from the
// normal on the incident side) at an interface with relative index
// eta = n_transmitted / n_incident. Returns 1 under total internal reflection.
double fresnel_dielectric(double cos_i, double eta);

// Cosine-weighted hemispherical average 2 int_0^1 F(mu, eta) mu dmu: the fraction of
// diffuse (Lambertian) light reflected by the interface. Split at the critical
// angle and integrated by Gauss-Legendre with a substitution that removes the
// square-root singularity there.
double fresnel_diffuse_reflectance(double eta);

// Refraction through the plane z = 0 (normal +z) by Snell's law: `d` is a unit
// propagation direction, eta = n_transmitted / n_incident. The tangential part is
// divided by eta and z keeps its sign. Returns false under total internal reflection.
bool refract_through_plane(const Vec3d& d, double eta, Vec3d& transmitted);

}  // namespace dermis::sss
