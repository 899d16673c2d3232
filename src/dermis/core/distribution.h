// Piecewise-constant 1D and 2D distributions (tables) for importance sampling:
// environment maps and tabulated profiles (pbrt-v4 A.4.2, A.5.6).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dermis/core/vec.h"

namespace dermis {

// A piecewise-constant density on [0, 1) over n equal bins, proportional to |f|.
class Distribution1D {
 public:
  Distribution1D() = default;
  // Throws std::invalid_argument if f is empty or has a non-finite value.
  explicit Distribution1D(std::span<const float> f);
  std::size_t size() const { return func_.size(); }
  // Integral of |f| over [0, 1).
  double integral() const { return integral_; }
  // Continuous sample in [0, 1); returns the density there and the bin (the point is
  // always in that bin as pdf_continuous() computes it, so the two densities agree).
  float sample_continuous(float u, float* pdf, std::size_t* bin = nullptr) const;
  // Discrete sample of a bin with probability f_i / sum f.
  std::size_t sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;
  float pdf_continuous(float x) const;
  float pmf_discrete(std::size_t i) const;

 private:
  // The bin u falls in: the largest i with cdf_[i] <= u (at most n - 1).
  std::size_t find_bin(double u) const;

  std::vector<float> func_;
  std::vector<double> cdf_;
  // Where to start looking for u in [j/n, (j+1)/n): the bin of j/n (the cutpoint method,
  // Chen & Asau 1974). A search then reads a line or two of cdf_, where a binary search
  // reads ten lines of a row of a large environment map, missing the cache on most.
  std::vector<uint32_t> guide_;
  double integral_ = 0;
};

// A piecewise-constant density on [0,1)^2 over an nu x nv grid (f given row-major, v rows).
class Distribution2D {
 public:
  Distribution2D() = default;
  // Throws std::invalid_argument unless f has nu * nv > 0 finite values.
  Distribution2D(std::span<const float> f, std::size_t nu, std::size_t nv);
  // Returns (u, v) in [0,1)^2 and the density with respect to area in [0,1)^2.
  Vec2 sample(Vec2 u, float* pdf) const;
  float pdf(Vec2 p) const;
  double integral() const { return marginal_.integral(); }

 private:
  std::vector<Distribution1D> conditional_;
  Distribution1D marginal_;
};

}  // namespace dermis
