#include "dermis/sss/pointcloud/local_disk.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/core/vec.h"
#include "dermis/sss/pointcloud/local_disk_weight.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss::pointcloud {

LocalDiskTable::LocalDiskTable(const RadialProfile& profile, int entries) : profile_(profile) {
  if (entries < 2) throw std::invalid_argument("LocalDiskTable: at least 2 entries, got " + std::to_string(entries));
  const double albedo = profile.albedo();
  if (!(albedo >= 0) || !std::isfinite(albedo))
    throw std::invalid_argument("LocalDiskTable: the profile's albedo is negative or not finite");
  zero_ = albedo == 0;
  if (zero_) return;
  const double median = profile.r_max(0.5);
  if (!(median > 0) || !std::isfinite(median))
    throw std::invalid_argument("LocalDiskTable: the profile's median radius is not positive");
  alpha_lo_ = 1e-4 * median;
  alpha_hi_ = 1e3 * median;
  log_lo_ = std::log(alpha_lo_);
  inv_step_ = double(entries - 1) / (std::log(alpha_hi_) - log_lo_);
  log_value_.resize(std::size_t(entries));
  for (int i = 0; i < entries; ++i) {
    const double alpha = std::exp(log_lo_ + double(i) / inv_step_);
    const double v = integrate_directly(alpha);
    if (!(v > 0)) throw std::invalid_argument("LocalDiskTable: the profile integrates to zero near r = 0");
    log_value_[std::size_t(i)] = std::log(v);
  }
}

double LocalDiskTable::integrate_directly(double alpha) const {
  if (zero_ || !(alpha > 0)) return 0.0;
  // Langlands & Mertens (seed 001): the local term's 1D integral 2 pi int_0^alpha w R r dr.
  auto f = [&](double r) { return local_weight(r, alpha) * profile_.eval(r) * r; };
  // Dyadic pieces [alpha 2^-(k+1), alpha 2^-k]: a profile singular or steep at r = 0 is
  // smooth on each piece. Each piece to 1e-10 of its own size, but never below 1e-16 of
  // the whole (a first pass of 16-point rules), so that an underflowing tail cannot
  // drive the adaptive rule to its depth limit.
  constexpr int kPieces = 60;
  double rough[kPieces];
  double rough_total = 0;
  double b = alpha;
  for (int k = 0; k < kPieces; ++k, b *= 0.5) rough_total += rough[k] = std::abs(gauss_legendre_16(f, 0.5 * b, b));
  double total = 0;
  b = alpha;
  for (int k = 0; k < kPieces; ++k, b *= 0.5)
    total += integrate(f, 0.5 * b, b, 1e-10 * std::max(rough[k], 1e-6 * rough_total) + 1e-300);
  total += gauss_legendre_16(f, 0.0, b);
  return 2 * kPiD * total;
}

double LocalDiskTable::local_albedo(double alpha) const {
  if (zero_ || !(alpha > 0)) return 0.0;
  if (alpha < alpha_lo_ || alpha > alpha_hi_) return integrate_directly(alpha);
  const double u = (std::log(alpha) - log_lo_) * inv_step_;
  const std::size_t i = std::min(std::size_t(u), log_value_.size() - 2);
  const double t = u - double(i);
  return std::exp(log_value_[i] * (1 - t) + log_value_[i + 1] * t);
}

double local_albedo_of(const RadialProfile& profile, double alpha) {
  if (!(alpha > 0) || !(profile.albedo() > 0)) return 0.0;
  // Langlands & Mertens (seed 001): the local term's 1D integral 2 pi int_0^alpha w R r dr.
  auto f = [&](double r) { return local_weight(r, alpha) * profile.eval(r) * r; };
  constexpr int kPieces = 40;
  double total = 0, b = alpha;
  for (int k = 0; k < kPieces; ++k, b *= 0.5) total += gauss_legendre_16(f, 0.5 * b, b);
  total += gauss_legendre_16(f, 0.0, b);
  return 2 * kPiD * total;
}

LocalDiskTableRGB::LocalDiskTableRGB(const ProfileRGB& profile, int entries)
    : channel{LocalDiskTable(profile[0], entries), LocalDiskTable(profile[1], entries),
              LocalDiskTable(profile[2], entries)} {}

}  // namespace dermis::sss::pointcloud
