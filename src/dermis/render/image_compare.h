// Comparing a rendered image against a reference: error statistics and a
// false-colour difference image.
#pragma once

#include "dermis/core/rgb.h"
#include "dermis/render/image.h"

namespace dermis {

// Regularizer of the relative MSE: keeps near-black reference pixels from dominating.
inline constexpr double kRelativeMseEpsilon = 1e-2;

// Statistics of A (the test image) against B (the reference). Per-channel values
// are in RGB order; `*_all` pools the three channels.
struct ImageComparison {
  int width = 0, height = 0;
  RGB mean_a, mean_b;
  // RMSE = sqrt(mean over pixels of (a - b)^2).
  RGB rmse;
  double rmse_all = 0;
  // relMSE = mean over pixels of (a - b)^2 / (b^2 + kRelativeMseEpsilon).
  RGB relative_mse;
  double relative_mse_all = 0;
  // max over pixels of |a - b|.
  RGB max_abs_diff;
  double max_abs_diff_all = 0;
};

// Throws std::invalid_argument if the sizes differ (message names both sizes).
ImageComparison compare_images(const Image& a, const Image& b);

// The false-colour ramp for t in [0, 1] (clamped): black through purple, red and
// orange to pale yellow, with luminance increasing monotonically; returned as linear RGB.
RGB false_colour(float t);

// The q-quantile (q in [0, 1], nearest rank) of the luminance of |a - b|.
double difference_quantile(const Image& a, const Image& b, double q);

// |a - b| luminance per pixel divided by its 99th percentile (or by the maximum when
// that percentile is zero), clamped to [0, 1] and mapped through false_colour.
// `scale` (optional) receives the luminance that maps to the top of the ramp.
Image difference_image(const Image& a, const Image& b, double* scale = nullptr);

}  // namespace dermis
