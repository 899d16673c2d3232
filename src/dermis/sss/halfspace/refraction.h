// Refraction through the plane z = 0 of the half-space (its Fresnel reflectance is
// core/fresnel.h).
#pragma once

#include <cmath>

#include "dermis/core/vec.h"

namespace dermis::sss {

// Refraction through the plane z = 0 (normal +z) by Snell's law: `d` is a unit
// propagation direction, eta = n_transmitted / n_incident. The tangential part is
// divided by eta and z keeps its sign. Returns false under total internal reflection.
inline bool refract_through_plane(const Vec3d& d, double eta, Vec3d& transmitted) {
  const double sin2_t = (d.x * d.x + d.y * d.y) / (eta * eta);  // Snell's law
  if (sin2_t >= 1.0) return false;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  transmitted = {d.x / eta, d.y / eta, std::copysign(cos_t, d.z)};
  return true;
}

}  // namespace dermis::sss
