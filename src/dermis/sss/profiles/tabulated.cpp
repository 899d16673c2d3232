#include "dermis/sss/profiles/tabulated.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dermis/sss/profiles/gaussian.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis::sss {
namespace {

constexpr double kLogFloor = -700;  // ln of a zero value (exp(-700) ~ 1e-304)

// Uniform in logit(A) = ln(A / (1 - A)) over [0.002, 0.998]: the dipole's shape changes
// fastest near both ends (its sigma_tr goes like 1 - A as A -> 1).
std::vector<double> default_albedos() {
  constexpr int kNodes = 161;
  const double lo = std::log(0.002 / 0.998), hi = -lo;
  std::vector<double> a(kNodes);
  for (int i = 0; i < kNodes; ++i) a[i] = 1 / (1 + std::exp(-(lo + (hi - lo) * i / (kNodes - 1))));
  return a;
}

struct SourceSummary {
  double energy = 0;  // over [0, inf) (pieces up to 1e6 l)
  double median = 0;
};

// Energy of the source and its median radius: 16-point Gauss-Legendre on geometric
// pieces [0, 1e-6], [1e-6, 1.25e-6], ... up to 1e6 (l = 1), then bisection for the median.
SourceSummary summarise(const RadialFunction& f) {
  auto density = [&](double r) { return 2 * kPiD * r * f(r); };
  std::vector<double> edges{0.0}, cumulative{0.0};
  for (double a = 1e-6; a < 1e6; a *= 1.25) edges.push_back(a);
  for (std::size_t i = 1; i < edges.size(); ++i)
    cumulative.push_back(cumulative.back() + gauss_legendre_16(density, edges[i - 1], edges[i]));
  SourceSummary s;
  s.energy = cumulative.back();
  if (!(s.energy > 0) || !std::isfinite(s.energy))
    throw std::invalid_argument("profile table: a source profile has no finite positive energy");
  const double half = 0.5 * s.energy;
  std::size_t i = 1;
  while (cumulative[i] < half) ++i;
  double lo = edges[i - 1], hi = edges[i];
  const double base = cumulative[i - 1];
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (base + gauss_legendre_16(density, edges[i - 1], mid) < half ? lo : hi) = mid;
  }
  s.median = 0.5 * (lo + hi);
  return s;
}

}  // namespace

ProfileTable::ProfileTable(const std::function<double(double, double)>& f, ProfileTableOptions options)
    : ProfileTable(
          ProfileFamily([f](double albedo) { return RadialFunction([f, albedo](double r) { return f(albedo, r); }); }),
          std::move(options)) {}

ProfileTable::ProfileTable(const ProfileFamily& family, ProfileTableOptions options) {
  albedos_ = options.albedos.empty() ? default_albedos() : options.albedos;
  if (albedos_.size() < 2) throw std::invalid_argument("profile table: at least two albedo nodes are needed");
  for (std::size_t i = 0; i < albedos_.size(); ++i) {
    if (!(albedos_[i] > 0 && albedos_[i] <= 1))
      throw std::invalid_argument("profile table: albedo nodes must lie in (0, 1] (got " + std::to_string(albedos_[i]) +
                                  ")");
    if (i > 0 && !(albedos_[i] > albedos_[i - 1]))
      throw std::invalid_argument("profile table: albedo nodes must be strictly increasing");
  }
  if (options.radial_nodes < 8) throw std::invalid_argument("profile table: at least 8 radial nodes are needed");
  if (!(options.x_min > 0 && options.x_max > options.x_min))
    throw std::invalid_argument("profile table: need 0 < x_min < x_max");

  n_ = options.radial_nodes;
  x_min_ = options.x_min;
  x_max_ = options.x_max;
  log_x_min_ = std::log(x_min_);
  log_step_ = std::log(x_max_ / x_min_) / (n_ - 1);
  x_.resize(n_ + 1);
  x_[0] = 0;
  for (int k = 1; k <= n_; ++k) x_[k] = std::exp(log_x_min_ + (k - 1) * log_step_);
  x_[n_] = x_max_;

  const int nodes = int(albedos_.size());
  log_scale_.resize(nodes);
  energy_.resize(nodes);
  source_energy_.resize(nodes);
  log_shape_.resize(std::size_t(nodes) * n_);
  cdf_.resize(std::size_t(nodes) * (n_ + 1));
  // The nodes are independent (each writes its own rows): built in parallel, the same
  // table whatever the thread count.
  tbb::parallel_for(0, nodes, [&](int j) {
    const RadialFunction f = family(albedos_[j]);
    const SourceSummary s = summarise(f);
    const double scale = s.median;
    log_scale_[j] = std::log(scale);
    source_energy_[j] = s.energy;
    // Cell energies in x = r / L: int 2 pi r R dr over [x_k L, x_{k+1} L] (16-point Gauss-Legendre).
    auto density = [&](double r) { return 2 * kPiD * r * f(r); };
    double* cdf = &cdf_[std::size_t(j) * (n_ + 1)];
    cdf[0] = 0;
    for (int k = 0; k < n_; ++k) cdf[k + 1] = cdf[k] + gauss_legendre_16(density, x_[k] * scale, x_[k + 1] * scale);
    energy_[j] = cdf[n_];
    if (!(energy_[j] > 0)) throw std::invalid_argument("profile table: a node has zero energy in the table range");
    for (int k = 0; k <= n_; ++k) cdf[k] /= energy_[j];
    for (int k = 1; k <= n_; ++k) {
      const double value = scale * scale * f(x_[k] * scale) / energy_[j];
      log_shape_[std::size_t(j) * n_ + (k - 1)] = value > 0 ? std::max(std::log(value), kLogFloor) : kLogFloor;
    }
  });
}

ProfileTable::Lookup ProfileTable::lookup(double albedo) const {
  if (!(albedo >= albedos_.front() && albedo <= albedos_.back()))
    throw std::invalid_argument("tabulated profile: albedo " + std::to_string(albedo) + " outside the table's range [" +
                                std::to_string(albedos_.front()) + ", " + std::to_string(albedos_.back()) + "]");
  int j = int(std::upper_bound(albedos_.begin(), albedos_.end(), albedo) - albedos_.begin()) - 1;
  j = std::clamp(j, 0, int(albedos_.size()) - 2);
  Lookup q;
  q.node = j;
  q.t = (albedo - albedos_[j]) / (albedos_[j + 1] - albedos_[j]);
  // The scale and the energy vary smoothly with A: cubic Lagrange interpolation through
  // nodes j-1 .. j+2 (fewer at the ends), so that a curved ln L(A) does not shift the
  // profile between nodes.
  const int first = std::max(0, j - 1), last = std::min(int(albedos_.size()) - 1, j + 2);
  double log_scale = 0, energy = 0;
  q.first = first;
  q.count = last - first + 1;
  for (int i = first; i <= last; ++i) {
    double w = 1;
    for (int m = first; m <= last; ++m)
      if (m != i) w *= (albedo - albedos_[m]) / (albedos_[i] - albedos_[m]);
    q.weight[i - first] = w;
    log_scale += w * log_scale_[i];
    energy += w * energy_[i];
  }
  q.scale = std::exp(log_scale);
  q.energy = energy;
  return q;
}

double ProfileTable::albedo_for_energy(double energy) const {
  if (!(energy > energy_.front())) return albedos_.front();
  if (!(energy < energy_.back())) return albedos_.back();
  // The node interval first (the node energies are the interpolant's values there), then
  // the Illinois variant of regula falsi inside it (a few lookups per inversion: it runs
  // at every entry point of a textured material).
  const int j = int(std::upper_bound(energy_.begin(), energy_.end(), energy) - energy_.begin()) - 1;
  double lo = albedos_[std::max(j, 0)], hi = albedos_[std::min(j + 1, int(albedos_.size()) - 1)];
  double f_lo = energy_[std::max(j, 0)] - energy, f_hi = energy_[std::min(j + 1, int(albedos_.size()) - 1)] - energy;
  const double tolerance = 1e-13 * (hi - lo);
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > tolerance; ++it) {
    double mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    const double f = lookup(mid).energy - energy;
    if (f == 0) return mid;
    if (f < 0) {
      lo = mid, f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = mid, f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
    if (std::abs(f) < 1e-14 * energy) return mid;
  }
  return 0.5 * (lo + hi);
}

int ProfileTable::cell_of(double x) const {
  if (x < x_[1]) return 0;
  int k = 1 + int((std::log(x) - log_x_min_) / log_step_);
  k = std::clamp(k, 1, n_ - 1);
  if (x < x_[k])
    --k;  // guard the rounding of the logarithm
  else if (k + 1 < n_ && x >= x_[k + 1])
    ++k;
  return k;
}

double ProfileTable::interpolate_log_shape(int node, int k, double w) const {
  const double* g = &log_shape_[std::size_t(node) * n_];
  return (1 - w) * g[k] + w * g[k + 1];
}

double ProfileTable::eval(const Lookup& q, double r) const {
  const double x = r / q.scale;
  if (x > x_max_ || x < 0) return 0;
  // Position in ln x; linear extrapolation below x_1 (at most 3 decades).
  const double u = (std::log(std::max(x, x_min_ * 1e-3)) - log_x_min_) / log_step_;
  const int k = std::clamp(int(std::floor(u)), 0, n_ - 2);
  const double w = u - k;
  double g = 0;
  for (int i = 0; i < q.count; ++i) g += q.weight[i] * interpolate_log_shape(q.first + i, k, w);
  return q.energy * std::exp(g) / (q.scale * q.scale);
}

double ProfileTable::node_cdf(int node, double x) const {
  if (x <= 0) return 0;
  if (x >= x_max_) return 1;
  const double* cdf = &cdf_[std::size_t(node) * (n_ + 1)];
  const int k = cell_of(x);
  return cdf[k] + (cdf[k + 1] - cdf[k]) * (x - x_[k]) / (x_[k + 1] - x_[k]);
}

double ProfileTable::sample_radius(const Lookup& q, double xi) const {
  int node = q.node;
  if (xi < 1 - q.t) {
    xi /= (1 - q.t);
  } else {
    xi = (xi - (1 - q.t)) / q.t;
    node = q.node + 1;
  }
  xi *= node == q.node ? q.kept_lo : q.kept_hi;
  xi = std::clamp(xi, 0.0, 0x1.fffffffffffffp-1);
  const double* cdf = &cdf_[std::size_t(node) * (n_ + 1)];
  int k = int(std::upper_bound(cdf, cdf + n_ + 1, xi) - cdf) - 1;
  k = std::clamp(k, 0, n_ - 1);
  while (k + 1 < n_ && !(cdf[k + 1] > cdf[k])) ++k;  // skip empty cells
  const double within = (xi - cdf[k]) / (cdf[k + 1] - cdf[k]);
  const double x = x_[k] + std::clamp(within, 0.0, 1.0) * (x_[k + 1] - x_[k]);
  return x * q.scale;
}

double ProfileTable::pdf_radius(const Lookup& q, double r) const {
  const double x = r / q.scale;
  if (x < 0 || x > x_max_ || (q.x_cut > 0 && x > q.x_cut)) return 0;
  const int k = cell_of(x);
  const double* a = &cdf_[std::size_t(q.node) * (n_ + 1)];
  const double* b = a + (n_ + 1);
  const double mass = (1 - q.t) * (a[k + 1] - a[k]) / q.kept_lo + q.t * (b[k + 1] - b[k]) / q.kept_hi;
  return mass / ((x_[k + 1] - x_[k]) * q.scale);
}

double ProfileTable::r_max(const Lookup& q, double energy_fraction) const {
  GaussianProfile::check_fraction(energy_fraction);
  // The mixture's CDF is piecewise linear on the radial nodes (so are both nodes'): the
  // first node where it reaches the fraction, then the line through the cell before it.
  const double* a = &cdf_[std::size_t(q.node) * (n_ + 1)];
  const double* b = a + (n_ + 1);
  auto mixed = [&](int k) { return (1 - q.t) * a[k] + q.t * b[k]; };
  int lo = 0, hi = n_;  // mixed(hi) = 1 >= the fraction
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (mixed(mid) < energy_fraction ? lo : hi) = mid;
  }
  if (mixed(lo) >= energy_fraction) return 0;
  const double f0 = mixed(lo), f1 = mixed(hi);
  return (x_[lo] + (energy_fraction - f0) / (f1 - f0) * (x_[hi] - x_[lo])) * q.scale;
}

void ProfileTable::truncate(Lookup& q, double energy_fraction) const {
  q.x_cut = 0;
  q.kept_lo = q.kept_hi = 1;
  if (energy_fraction >= 1) return;
  const double x_cut = r_max(q, energy_fraction) / q.scale;
  q.x_cut = x_cut;
  q.kept_lo = node_cdf(q.node, x_cut);
  q.kept_hi = node_cdf(q.node + 1, x_cut);
}

TabulatedProfile::TabulatedProfile(std::shared_ptr<const ProfileTable> table, double albedo, double mean_free_path,
                                   double kept)
    : table_(std::move(table)), l_(mean_free_path) {
  if (!table_) throw std::invalid_argument("tabulated profile: no table");
  if (!(mean_free_path > 0) || !std::isfinite(mean_free_path))
    throw std::invalid_argument("tabulated profile: the mean free path must be positive (got " +
                                std::to_string(mean_free_path) + ")");
  lookup_ = table_->lookup(albedo);
  table_->truncate(lookup_, kept);
}

}  // namespace dermis::sss
