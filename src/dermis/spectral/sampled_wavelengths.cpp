#include "dermis/spectral/sampled_wavelengths.h"

#include <algorithm>
#include <cmath>

#include "dermis/spectral/cie_observer.h"
#include "dermis/spectral/sigmoid_polynomial.h"

namespace dermis {

namespace {

constexpr float kA = 0.0072f, kCentre = 538;  // the density's width and centre

// The density's normalization over [360, 830]: integral of 1 / cosh^2(a (l - c)) is
// tanh(a (l - c)) / a.
float visible_normalization() {
  static const float n =
      kA / (std::tanh(kA * (kSpectrumLambdaMax - kCentre)) - std::tanh(kA * (kSpectrumLambdaMin - kCentre)));
  return n;
}

// The inverse of the density's CDF, tanh(a (l - c)) = t0 + u (t1 - t0), and the density
// there from the same t: 1 / cosh^2 = 1 - tanh^2.
void sample_visible_wavelength(float u, float& lambda, float& pdf) {
  static const float t0 = std::tanh(kA * (kSpectrumLambdaMin - kCentre));
  static const float t1 = std::tanh(kA * (kSpectrumLambdaMax - kCentre));
  const float t = t0 + u * (t1 - t0);
  lambda = std::fmin(std::fmax(kCentre + std::atanh(t) / kA, kSpectrumLambdaMin), kSpectrumLambdaMax);
  pdf = visible_normalization() * (1 - t * t);
}

}  // namespace

float SampledWavelengths::visible_pdf(float lambda_nm) {
  if (lambda_nm < kSpectrumLambdaMin || lambda_nm > kSpectrumLambdaMax) return 0;
  const float c = std::cosh(kA * (lambda_nm - kCentre));
  return visible_normalization() / (c * c);
}

SampledWavelengths SampledWavelengths::sample_visible(float u) {
  SampledWavelengths w;
  for (int i = 0; i < kPathWavelengths; ++i)
    sample_visible_wavelength((u + float(i)) / kPathWavelengths, w.lambda[std::size_t(i)], w.pdf[std::size_t(i)]);
  return w;
}

bool SampledWavelengths::secondary_terminated() const {
  int kept = 0;
  for (float p : pdf) kept += p > 0;
  return kept == 1;
}

int SampledWavelengths::kept() const {
  for (int i = 0; i < kPathWavelengths; ++i)
    if (pdf[std::size_t(i)] > 0) return i;
  return 0;
}

void SampledWavelengths::terminate_secondary(float u) {
  if (secondary_terminated()) return;
  const int kept = std::min(int(u * kPathWavelengths), kPathWavelengths - 1);
  for (int i = 0; i < kPathWavelengths; ++i)
    if (i != kept) pdf[std::size_t(i)] = 0;
  // Chosen with probability 1 / n from its slice, where its density is n x visible_pdf: its
  // density is visible_pdf, and it alone now stands for all the path's samples.
  pdf[std::size_t(kept)] /= kPathWavelengths;
}

RGB SampledWavelengths::to_linear_srgb(RGB values) const {
  const CieTables& cie = cie_tables();
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < kPathWavelengths; ++i) {
    const float p = pdf[std::size_t(i)];
    if (p == 0) continue;
    const double v = values[i] / p;
    X += v * cie_table_at(cie.x, lambda[std::size_t(i)]);
    Y += v * cie_table_at(cie.y, lambda[std::size_t(i)]);
    Z += v * cie_table_at(cie.z, lambda[std::size_t(i)]);
  }
  // y_sum is the integral of y over nanometres (1 nm steps).
  const double k = 1.0 / (kPathWavelengths * cie.y_sum);
  const auto rgb = xyz_to_linear_srgb(X * k, Y * k, Z * k);
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

}  // namespace dermis
