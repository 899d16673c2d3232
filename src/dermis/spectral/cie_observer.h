// The CIE 1931 2-degree observer and illuminant D65 at every nanometre of 360-830 nm
// (the observer by Sprague interpolation, D65 linearly, from the 5 nm tables of
// named_spectra_data.cpp), and CIE XYZ to
// linear sRGB: what turns a spectrum into the colour a film records.
#pragma once

#include <array>

namespace dermis {

struct CieTables {
  static constexpr int kLambdaMin = 360, kLambdaMax = 830;
  static constexpr int kSamples = kLambdaMax - kLambdaMin + 1;
  std::array<double, kSamples> x, y, z;  // colour matching functions at kLambdaMin + i nm
  std::array<double, kSamples> d65;      // illuminant D65, relative spectral power
  double y_sum = 0;                      // sum of y: the equal-energy spectrum's Y
  double d65_y = 0;                      // sum of d65 * y: D65's Y
};
const CieTables& cie_tables();

// pbrt-v4's CIE_Y_integral, the integral of y over 360-830 nm. pbrt-v4's film records a
// spectral radiance L as the integral of {x, y, z} L (its lights' spectra are divided by the
// integral of y times theirs, so that they record their colour); the few emissions it does not
// so divide (an rgbgrid's Le, a grid's blackbody by temperature) record CIE_Y_integral times
// what Dermis' film, which divides by the integral of y, would record.
inline constexpr float kPbrtV4CieYIntegral = 106.856895f;

// A table of CieTables read at a wavelength, linearly between its nanometres (0 outside).
float cie_table_at(const std::array<double, CieTables::kSamples>& table, float lambda_nm);

// CIE XYZ to linear sRGB (IEC 61966-2-1:1999, eq. F.7; D65 white), unclamped.
std::array<double, 3> xyz_to_linear_srgb(double X, double Y, double Z);

}  // namespace dermis
