#include "dermis/core/distribution.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dermis {

namespace {

// The bin of x in [0, 1) among n, as pdf_continuous() computes it (float arithmetic);
// sample_continuous() keeps its results consistent with this.
std::size_t bin_of(float x, std::size_t n) { return std::min(n - 1, std::size_t(x * float(n))); }

}  // namespace

Distribution1D::Distribution1D(std::span<const float> f) : func_(f.begin(), f.end()) {
  const std::size_t n = func_.size();
  if (n == 0) throw std::invalid_argument("Distribution1D: the function has no values");
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(func_[i]))
      throw std::invalid_argument(fmt::format("Distribution1D: value {} of the function is {}", i, func_[i]));
  for (float& v : func_) v = std::abs(v);
  cdf_.assign(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) cdf_[i + 1] = cdf_[i] + double(func_[i]) / double(n);
  integral_ = cdf_[n];
  if (integral_ <= 0) {
    // No information: fall back to uniform.
    for (std::size_t i = 0; i <= n; ++i) cdf_[i] = double(i) / double(n);
  } else {
    for (std::size_t i = 1; i <= n; ++i) cdf_[i] /= integral_;
  }
  guide_.resize(n);
  std::size_t i = 0;
  for (std::size_t j = 0; j < n; ++j) {
    while (i + 1 < n && cdf_[i + 1] <= double(j) / double(n)) ++i;
    guide_[j] = uint32_t(i);
  }
}

std::size_t Distribution1D::find_bin(double u) const {
  const std::size_t n = func_.size();
  std::size_t i = guide_[std::min(n - 1, std::size_t(std::max(0.0, u) * double(n)))];
  // u * n may round up onto the next cutpoint: step back, then on to u's bin.
  while (i > 0 && cdf_[i] > u) --i;
  while (i + 1 < n && cdf_[i + 1] <= u) ++i;
  return i;
}

float Distribution1D::sample_continuous(float u, float* pdf, std::size_t* bin) const {
  std::size_t i = find_bin(u);
  // Skip zero-width bins that upper_bound may land on at their boundary.
  while (cdf_[i + 1] - cdf_[i] <= 0 && i + 1 < func_.size()) ++i;
  double du = u - cdf_[i];
  double width = cdf_[i + 1] - cdf_[i];
  if (width > 0) du /= width;
  if (pdf) *pdf = integral_ > 0 ? float(func_[i] / integral_) : 1.0f;
  if (bin) *bin = i;
  const std::size_t n = func_.size();
  float x = std::min(float((double(i) + std::clamp(du, 0.0, 1.0)) / double(n)), std::nextafter(1.0f, 0.0f));
  // Rounding to float can carry x onto the first value of the next bin (whose density
  // may differ, or be zero) or short of this one: keep x in bin i as pdf_continuous() sees it.
  while (x > 0 && bin_of(x, n) > i) x = std::nextafter(x, 0.0f);
  while (x < 1 && bin_of(x, n) < i) x = std::nextafter(x, 1.0f);
  return x;
}

std::size_t Distribution1D::sample_discrete(float u, float* pmf, float* u_remapped) const {
  std::size_t i = find_bin(u);
  while (cdf_[i + 1] - cdf_[i] <= 0 && i + 1 < func_.size()) ++i;
  double width = cdf_[i + 1] - cdf_[i];
  if (pmf) *pmf = float(width);
  if (u_remapped) *u_remapped = width > 0 ? float(std::clamp((u - cdf_[i]) / width, 0.0, 1.0 - 1e-7)) : 0.0f;
  return i;
}

float Distribution1D::pdf_continuous(float x) const {
  if (x < 0 || x >= 1 || func_.empty()) return 0;
  const std::size_t i = bin_of(x, func_.size());
  return integral_ > 0 ? float(func_[i] / integral_) : 1.0f;
}

float Distribution1D::pmf_discrete(std::size_t i) const { return float(cdf_[i + 1] - cdf_[i]); }

Distribution2D::Distribution2D(std::span<const float> f, std::size_t nu, std::size_t nv) {
  if (nu == 0 || nv == 0 || f.size() != nu * nv)
    throw std::invalid_argument(fmt::format("Distribution2D: {} values given for a {} x {} grid", f.size(), nu, nv));
  conditional_.reserve(nv);
  std::vector<float> marginal(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    conditional_.emplace_back(f.subspan(v * nu, nu));
    marginal[v] = float(conditional_.back().integral());
  }
  marginal_ = Distribution1D(marginal);
}

Vec2 Distribution2D::sample(Vec2 u, float* pdf) const {
  float pdf_v, pdf_u;
  std::size_t row;
  float v = marginal_.sample_continuous(u.y, &pdf_v, &row);
  float x = conditional_[row].sample_continuous(u.x, &pdf_u);
  *pdf = pdf_u * pdf_v;
  return {x, v};
}

float Distribution2D::pdf(Vec2 p) const {
  if (p.x < 0 || p.x >= 1 || p.y < 0 || p.y >= 1) return 0;
  const std::size_t row = bin_of(p.y, conditional_.size());
  return marginal_.pdf_continuous(p.y) * conditional_[row].pdf_continuous(p.x);
}

}  // namespace dermis
