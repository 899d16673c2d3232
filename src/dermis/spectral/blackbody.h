// Blackbody emission: Planck's law, pbrt-v4's BlackbodySpectrum (normalised to 1 at its
// peak) and the colour a film records for it, as a grid medium's temperature emits.
#pragma once

#include "dermis/core/rgb.h"

namespace dermis {

// Planck's law (Planck 1901): spectral radiance per unit wavelength, lambda in nm, in SI units.
double planck(double lambda_nm, double kelvin);

// Planck's law over its value at its peak, Wien's displacement lambda_max = b / T (b =
// 2.8977721e-3 m K): pbrt-v4's BlackbodySpectrum.
float normalized_blackbody(float lambda_nm, float kelvin);

// The colour of normalized_blackbody(., T) as the film records a spectral radiance (CIE 1931
// observer over 360-830 nm, divided by the integral of y, to linear sRGB), read from a table
// of ln X, ln Y, ln Z over ln T (100 K to 1e5 K; 0 at 100 K and below, where pbrt-v4 emits
// nothing; the value at 1e5 K beyond).
RGB normalized_blackbody_rgb(float kelvin);

}  // namespace dermis
