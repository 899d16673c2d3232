// The spectra of RGB colours (Jakob & Hanika 2019, eq. 3): s(lambda) = S(c0 t^2 + c1 t + c2),
// t the wavelength mapped to [0, 1] over 360-830 nm, S a sigmoid.
#pragma once

#include <cmath>

namespace dermis {

// The range the spectra are defined on (the CIE 1931 observer's).
inline constexpr float kSpectrumLambdaMin = 360, kSpectrumLambdaMax = 830;

struct SigmoidPolynomial {
  float c0 = 0, c1 = 0, c2 = 0;  // in t = (lambda - 360) / 470

  // Eq. (3): S(x) = 1/2 + x / (2 sqrt(1 + x^2)), 0 and 1 at -inf and +inf.
  static float sigmoid(float x) {
    if (std::isinf(x)) return x > 0 ? 1.0f : 0.0f;
    return 0.5f + x / (2 * std::sqrt(1 + x * x));
  }
  float operator()(float lambda_nm) const {
    const float t = (lambda_nm - kSpectrumLambdaMin) / (kSpectrumLambdaMax - kSpectrumLambdaMin);
    return sigmoid((c0 * t + c1) * t + c2);
  }
  // The constant spectrum v in [0, 1]: S^-1(v) = (v - 1/2) / sqrt(v (1 - v)).
  static SigmoidPolynomial constant(float v) {
    SigmoidPolynomial p;
    p.c2 = v <= 0 ? -INFINITY : v >= 1 ? INFINITY : (v - 0.5f) / std::sqrt(v * (1 - v));
    return p;
  }
};

}  // namespace dermis
