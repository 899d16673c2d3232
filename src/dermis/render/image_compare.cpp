#include "dermis/render/image_compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dermis {

namespace {

void check_same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument(
        fmt::format("images differ in size: {}x{} versus {}x{}", a.width, a.height, b.width, b.height));
  if (a.pixel_count() == 0) throw std::invalid_argument("images are empty");
}

float abs_difference_luminance(const Image& a, const Image& b, std::size_t i) {
  RGB d;
  for (int c = 0; c < 3; ++c) d[c] = std::abs(a.pixels[3 * i + c] - b.pixels[3 * i + c]);
  return d.luminance();
}

}  // namespace

ImageComparison compare_images(const Image& a, const Image& b) {
  check_same_size(a, b);
  ImageComparison r;
  r.width = a.width;
  r.height = a.height;
  std::array<double, 3> sum_a{}, sum_b{}, sum_sq{}, sum_rel{};
  for (std::size_t i = 0; i < a.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double va = a.pixels[3 * i + c], vb = b.pixels[3 * i + c], d = va - vb;
      sum_a[c] += va;
      sum_b[c] += vb;
      sum_sq[c] += d * d;
      sum_rel[c] += d * d / (vb * vb + kRelativeMseEpsilon);
      r.max_abs_diff[c] = std::max(r.max_abs_diff[c], float(std::abs(d)));
    }
  }
  const double n = double(a.pixel_count());
  for (int c = 0; c < 3; ++c) {
    r.mean_a[c] = float(sum_a[c] / n);
    r.mean_b[c] = float(sum_b[c] / n);
    r.rmse[c] = float(std::sqrt(sum_sq[c] / n));
    r.relative_mse[c] = float(sum_rel[c] / n);
  }
  r.rmse_all = std::sqrt((sum_sq[0] + sum_sq[1] + sum_sq[2]) / (3 * n));
  r.relative_mse_all = (sum_rel[0] + sum_rel[1] + sum_rel[2]) / (3 * n);
  r.max_abs_diff_all = r.max_abs_diff.max();
  return r;
}

RGB false_colour(float t) {
  // Six control points in sRGB-encoded display values, chosen by eye after the
  // "inferno" map of van der Walt & Smith (matplotlib, 2015): perceived lightness rises
  // monotonically; interpolated piecewise-linearly in display space.
  static constexpr std::array<RGB, 6> kRamp = {RGB(0.00f, 0.00f, 0.02f), RGB(0.26f, 0.04f, 0.41f),
                                               RGB(0.58f, 0.15f, 0.40f), RGB(0.87f, 0.32f, 0.23f),
                                               RGB(0.99f, 0.65f, 0.04f), RGB(0.99f, 1.00f, 0.65f)};
  if (!(t > 0)) t = 0;  // also maps NaN to the bottom
  t = std::min(t, 1.0f);
  const float x = t * float(kRamp.size() - 1);
  const std::size_t k = std::min(kRamp.size() - 2, std::size_t(x));
  const float f = x - float(k);
  RGB display = kRamp[k] * (1 - f) + kRamp[k + 1] * f;
  return {srgb_to_linear(display[0]), srgb_to_linear(display[1]), srgb_to_linear(display[2])};
}

double difference_quantile(const Image& a, const Image& b, double q) {
  check_same_size(a, b);
  std::vector<float> lum(a.pixel_count());
  for (std::size_t i = 0; i < lum.size(); ++i) {
    lum[i] = abs_difference_luminance(a, b, i);
    if (!std::isfinite(lum[i])) lum[i] = std::numeric_limits<float>::max();  // NaN/inf rank at the top
  }
  // Nearest rank: the smallest value with at least a fraction q of the values at or below it.
  const std::size_t rank = std::size_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(lum.size())));
  const std::size_t k = rank == 0 ? 0 : rank - 1;
  std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(k), lum.end());
  return lum[k];
}

Image difference_image(const Image& a, const Image& b, double* scale_out) {
  double scale = difference_quantile(a, b, 0.99);
  if (scale <= 0) scale = difference_quantile(a, b, 1.0);
  if (scale_out) *scale_out = scale;
  Image out(a.width, a.height);
  for (std::size_t i = 0; i < a.pixel_count(); ++i) {
    const double d = abs_difference_luminance(a, b, i);
    const RGB colour = false_colour(scale > 0 ? float(d / scale) : 0.0f);
    for (int c = 0; c < 3; ++c) out.pixels[3 * i + c] = colour[c];
  }
  return out;
}

}  // namespace dermis
