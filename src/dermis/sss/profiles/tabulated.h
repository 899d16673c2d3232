// Tabulated radial profiles (the Cycles page, 002_...; METHODS 1.5): a 2D table over
// (r / l, A) of any profile given at mean free path l = 1, scaled to any l by
// R(r; l) = R(r / l; 1) / l^2. The radial CDF is built by numerical integration of
// 2 pi r R(r) and inverted by table.
//
// Layout: each albedo node j stores the profile on a radial grid measured in units of
// that node's median radius L_j (the radius inside which half the energy lies), so that
// interpolating between nodes moves the profile's scale smoothly instead of blending two
// differently sized profiles. Values are stored as g = ln(L^2 R / M) (M: the node's
// energy in the table) on a log-spaced grid x = r / L in [x_min, x_max] (plus 0), and
// evaluation interpolates g linearly in ln x, and g, ln L and M with cubic Lagrange
// polynomials in A (through nodes j-1 .. j+2). Sampling at an A between nodes j and j+1 (weight t) picks node j with
// probability 1 - t, else j+1, then the node's piecewise-constant density in x
// (exact cell energies); pdf_radius is exactly that mixture density.
#pragma once

#include <cmath>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace dermis::sss {

// Given an albedo A, the radial profile r -> R(r) at l = 1 (area density).
using RadialFunction = std::function<double(double r)>;
using ProfileFamily = std::function<RadialFunction(double albedo)>;

struct ProfileTableOptions {
  // Albedo nodes, strictly increasing, in (0, 1]; empty: 161 nodes uniform in
  // logit(A) over [0.002, 0.998] (dense near 0 and 1).
  std::vector<double> albedos;
  int radial_nodes = 1024;  // log-spaced nodes x_1 .. x_n (plus x_0 = 0)
  double x_min = 1e-5;      // first radial node, in units of the node's median radius
  double x_max = 1000;      // last radial node (the truncation), in the same units
};

class ProfileTable {
 public:
  explicit ProfileTable(const ProfileFamily& family, ProfileTableOptions options = {});
  // Convenience: from a plain function (A, r) -> R at l = 1.
  explicit ProfileTable(const std::function<double(double albedo, double r)>& f, ProfileTableOptions options = {});

  // Where an albedo falls among the nodes; computed once per profile, used per sample.
  struct Lookup {
    int node = 0;       // node j; A lies in [A_j, A_{j+1}]
    double t = 0;       // interpolation weight of node j + 1
    double scale = 1;   // interpolated median radius L(A)
    double energy = 0;  // interpolated table energy M(A) (at l = 1)
    int first = 0;      // cubic Lagrange nodes first .. first + count - 1 and their weights
    int count = 0;
    double weight[4] = {0, 0, 0, 0};
    // Truncation (truncate()): sampling stops at x_cut, each node's density renormalised
    // by the fraction it keeps there. x_cut = 0: the table's whole range.
    double x_cut = 0, kept_lo = 1, kept_hi = 1;
  };
  Lookup lookup(double albedo) const;
  // Truncates sampling at the radius keeping `energy_fraction` of the sampled
  // distribution (like the analytic profiles' r_max), so that probe spheres are not
  // sized by the table's far tail.
  void truncate(Lookup& q, double energy_fraction) const;

  // All at l = 1.
  double eval(const Lookup& q, double r) const;
  double sample_radius(const Lookup& q, double xi) const;
  double pdf_radius(const Lookup& q, double r) const;
  double r_max(const Lookup& q) const { return (q.x_cut > 0 ? q.x_cut : x_max_) * q.scale; }
  // Radius inside which the sampled distribution keeps the given fraction.
  double r_max(const Lookup& q, double energy_fraction) const;

  // The albedo A whose interpolated table energy (lookup(A).energy) is `energy`, by
  // bisection (the energy rises with A): a surface albedo inverted to the family's
  // parameter. Clamped to the first or last node outside their energies (the node
  // energies must rise with A).
  double albedo_for_energy(double energy) const;

  const std::vector<double>& albedos() const { return albedos_; }
  // Energy the table keeps at node j, divided by the source's energy over [0, inf).
  double kept_fraction(int node) const { return energy_[node] / source_energy_[node]; }
  double median_radius(int node) const { return std::exp(log_scale_[node]); }

 private:
  friend bool write_profile_table(std::ostream& out, const std::string& key, const ProfileTable& table);
  friend std::shared_ptr<const ProfileTable> read_profile_table(std::istream& in, const std::string& key);
  ProfileTable() = default;  // read_profile_table fills it

  double node_cdf(int node, double x) const;  // CDF of node j's piecewise-constant density in x
  int cell_of(double x) const;                // radial cell k with x in [x_k, x_{k+1})
  double interpolate_log_shape(int node, int k, double w) const;

  std::vector<double> albedos_;
  int n_ = 0;  // radial nodes (cells: x_0 = 0 .. x_n)
  double x_min_ = 0, x_max_ = 0, log_x_min_ = 0, log_step_ = 0;
  std::vector<double> x_;              // n + 1 radial nodes, x_0 = 0
  std::vector<double> log_scale_;      // ln L_j
  std::vector<double> energy_;         // M_j: energy inside x_max L_j
  std::vector<double> source_energy_;  // the source's energy over [0, inf)
  std::vector<double> log_shape_;      // [j * n + (k - 1)] = ln(L_j^2 R_j(x_k L_j) / M_j), k = 1..n
  std::vector<double> cdf_;            // [j * (n + 1) + k] = normalised energy inside x_k
};

// One channel's tabulated profile: a shared table, an albedo and a mean free path l.
class TabulatedProfile {
 public:
  TabulatedProfile() = default;
  // Sampling keeps `kept` of the energy (0.999, as the Christensen-Burley profile).
  TabulatedProfile(std::shared_ptr<const ProfileTable> table, double albedo, double mean_free_path,
                   double kept = 0.999);

  double albedo() const { return lookup_.energy; }  // the table's energy at this A (the integral of eval)
  double eval(double r) const { return table_->eval(lookup_, r / l_) / (l_ * l_); }  // METHODS 1.3 scaling
  double sample_radius(double xi) const { return l_ * table_->sample_radius(lookup_, xi); }
  double pdf_radius(double r) const { return table_->pdf_radius(lookup_, r / l_) / l_; }
  double r_max() const { return l_ * table_->r_max(lookup_); }
  double r_max(double energy_fraction) const { return l_ * table_->r_max(lookup_, energy_fraction); }
  const ProfileTable& table() const { return *table_; }

 private:
  std::shared_ptr<const ProfileTable> table_;
  ProfileTable::Lookup lookup_;
  double l_ = 1;
};

}  // namespace dermis::sss
