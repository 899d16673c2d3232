// A tabulated spectrum read as the piecewise-linear function through its samples.
#pragma once

#include <cstddef>
#include <span>

namespace dermis {

// Beyond the tabulated wavelengths a spectrum is zero (pbrt-v4's sampled spectra and files)
// or keeps its end values (pbrt-v4's named spectra).
enum class SpectrumEnds { Zero, Extend };

// The piecewise-linear function through (lambda[i], value[i]) (lambda increasing), read at
// increasing x: each read continues the search from the last.
class PiecewiseLinear {
 public:
  PiecewiseLinear(std::span<const double> lambda, std::span<const double> value, SpectrumEnds ends)
      : lambda_(lambda), value_(value), ends_(ends) {}
  // x must not decrease from one call to the next.
  double at(double x) {
    if (lambda_.empty()) return 0;
    if (x < lambda_.front()) return ends_ == SpectrumEnds::Extend ? value_.front() : 0;
    if (x > lambda_.back()) return ends_ == SpectrumEnds::Extend ? value_.back() : 0;
    while (i_ + 1 < lambda_.size() && lambda_[i_ + 1] < x) ++i_;
    if (i_ + 1 == lambda_.size()) return value_[i_];
    const double t = (x - lambda_[i_]) / (lambda_[i_ + 1] - lambda_[i_]);
    return value_[i_] + t * (value_[i_ + 1] - value_[i_]);
  }

 private:
  std::span<const double> lambda_, value_;
  SpectrumEnds ends_;
  std::size_t i_ = 0;
};

}  // namespace dermis
