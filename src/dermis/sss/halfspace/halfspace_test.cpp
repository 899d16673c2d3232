#include "dermis/sss/halfspace/halfspace.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "dermis/core/gauss_legendre.h"
#include "dermis/sss/halfspace/chandrasekhar.h"

namespace dermis::sss {
namespace {

HalfspaceConfig config(double albedo, Incidence incidence, uint64_t paths, uint64_t seed) {
  HalfspaceConfig c;
  c.albedo = albedo;
  c.incidence = incidence;
  c.paths = paths;
  c.seed = seed;
  return c;
}

// Index-matched isotropic half-space: total albedo against Chandrasekhar's H-function,
// 1 - H(1) sqrt(1 - alpha) (normal) and 1 - 2 sqrt(1 - alpha) int H mu (diffuse).
TEST(Halfspace, AlbedoMatchesChandrasekhar) {
  for (double alpha : {0.5, 0.9, 0.99}) {
    const HFunction h(alpha);
    for (Incidence incidence : {Incidence::Normal, Incidence::Diffuse}) {
      const HalfspaceResult r = simulate_halfspace(config(alpha, incidence, 100000, 42));
      const double reference =
          incidence == Incidence::Normal ? halfspace_albedo_collimated(h, 1.0) : halfspace_albedo_diffuse(h);
      EXPECT_LT(r.albedo_stderr, 1.5e-3);
      EXPECT_NEAR(r.albedo, reference, 4 * r.albedo_stderr)
          << "alpha=" << alpha << " incidence=" << int(incidence) << " stderr=" << r.albedo_stderr;
      EXPECT_EQ(r.truncated, 0u);
    }
  }
}

// A Lambertian entry (Chiang, Kutz & Burley 2016) sends the entering light along a
// cosine lobe whatever its incidence: behind a refracting boundary with exit at the
// first crossing, the albedo per entering light is then the index-matched half-space's
// under diffuse incidence, Chandrasekhar's, even under normal incidence.
TEST(Halfspace, LambertianEntryIsDiffuseIncidenceInside) {
  for (double alpha : {0.5, 0.9}) {
    const HFunction h(alpha);
    HalfspaceConfig c = config(alpha, Incidence::Normal, 100000, 43);
    c.eta = 1.4;
    c.exit_matched = true;
    c.entry_lambertian = true;
    const HalfspaceResult r = simulate_halfspace(c);
    EXPECT_NEAR(r.albedo_per_entering(), halfspace_albedo_diffuse(h), 4 * r.albedo_per_entering_stderr())
        << "alpha=" << alpha << " stderr=" << r.albedo_per_entering_stderr();
  }
}

// Without absorption nothing is lost: every path leaves or is explicitly truncated
// (the return time of a conservative walk has infinite mean, so a cap is needed).
TEST(Halfspace, ConservativeMediumLosesNothing) {
  HalfspaceConfig c = config(1.0, Incidence::Normal, 4000, 5);
  c.max_collisions = 20000;
  HalfspaceResult r = simulate_halfspace(c);
  EXPECT_NEAR(r.albedo + r.truncated_weight, 1.0, 1e-12);  // per path: weight 1 out or truncated
  EXPECT_NEAR(r.truncated_weight * double(c.paths), double(r.truncated), 1e-6);
  EXPECT_LT(r.truncated_weight, 0.05);
  EXPECT_NEAR(r.absorbed, 0.0, 0.0);

  // Dielectric boundary: Fresnel only redistributes; entry reflection is `specular`.
  c.eta = 1.4;
  r = simulate_halfspace(c);  // normal incidence: every path enters with weight 1 - F(1)
  EXPECT_NEAR(r.specular + r.albedo + r.truncated_weight, 1.0, 1e-12);
  c.incidence = Incidence::Diffuse;
  r = simulate_halfspace(c);
  EXPECT_NEAR(r.specular + r.albedo + r.truncated_weight, 1.0, 4 * (r.albedo_stderr + r.truncated_weight_stderr));
  EXPECT_GT(r.specular, 0.05);

  // Refracting entry, exit at the first crossing (the renderer's `diffuse` walk boundary):
  // nothing is reflected back inside, so nothing is lost either, and the walks are
  // shorter than with Fresnel at the exit.
  c.incidence = Incidence::Normal;
  c.exit_matched = true;
  HalfspaceResult em = simulate_halfspace(c);
  EXPECT_NEAR(em.specular + em.albedo + em.truncated_weight, 1.0, 1e-12);
  EXPECT_LT(em.mean_collisions, simulate_halfspace([&] {
                                  HalfspaceConfig d = c;
                                  d.exit_matched = false;
                                  return d;
                                }())
                                    .mean_collisions);
}

// Implicit capture plus Russian roulette conserves energy in expectation, with
// anisotropy and a dielectric boundary: specular + albedo + absorbed = 1.
TEST(Halfspace, EnergyBalanceWithAbsorption) {
  HalfspaceConfig c = config(0.9, Incidence::Diffuse, 20000, 9);
  c.g = 0.8;
  c.eta = 1.4;
  const HalfspaceResult r = simulate_halfspace(c);
  EXPECT_EQ(r.truncated, 0u);
  EXPECT_NEAR(r.specular + r.albedo + r.absorbed, 1.0, 4 * (r.albedo_stderr + r.absorbed_stderr));
}

// Energy in the annulus [lo, hi) from single scattering, normal incidence, sigma_t = 1,
// isotropic, no absorption: a collision at depth z (density e^{-z}) sends (1/2) dmu
// upward at cosine mu, attenuated by e^{-z/mu}, landing at r = z tan(theta).
double single_scattering_energy(double lo, double hi) {
  static const QuadratureRule outer = gauss_legendre(400, 0.0, 1.0), inner = gauss_legendre(48, 0.0, 1.0);
  double sum = 0;
  for (size_t i = 0; i < outer.nodes.size(); ++i) {
    const double z = -std::log(outer.nodes[i]);  // t = e^{-z}, dt = e^{-z} dz
    const double mu_lo = z / std::sqrt(z * z + hi * hi), mu_hi = z / std::sqrt(z * z + lo * lo);
    double s = 0;
    for (size_t j = 0; j < inner.nodes.size(); ++j) {
      const double mu = mu_lo + (mu_hi - mu_lo) * inner.nodes[j];
      s += inner.weights[j] * 0.5 * std::exp(-z / mu);
    }
    sum += outer.weights[i] * s * (mu_hi - mu_lo);
  }
  return sum;
}

// The radial profile R(r) as an area density, bin by bin, against single scattering
// computed by quadrature (max_collisions = 1 keeps exactly the once-scattered light).
TEST(Halfspace, SingleScatteringProfileMatchesQuadrature) {
  HalfspaceConfig c = config(1.0, Incidence::Normal, 200000, 3);
  c.max_collisions = 1;
  c.bins = RadialBins::linear(3.0, 24);
  const HalfspaceResult r = simulate_halfspace(c);
  double total = 0;
  for (int i = 0; i < c.bins.count(); ++i) {
    const double energy = single_scattering_energy(c.bins.lo(i), c.bins.hi(i));
    total += energy;
    EXPECT_NEAR(r.R[i], energy / c.bins.annulus_area(i), 4 * r.R_stderr[i] + 1e-9) << "bin " << i;
  }
  // The quadrature itself: all once-scattered light is (1 - ln 2) / 2.
  EXPECT_NEAR(total + single_scattering_energy(c.bins.r_max(), 1e6), (1 - std::log(2.0)) / 2, 1e-7);
  EXPECT_NEAR(r.albedo, (1 - std::log(2.0)) / 2, 4 * r.albedo_stderr);
}

// Sum of R * annulus area is the albedo minus what left beyond r_max.
TEST(Halfspace, ProfileIntegratesToAlbedo) {
  HalfspaceConfig c = config(0.95, Incidence::Angle, 20000, 8);
  c.incidence_angle = 0.6;
  c.eta = 1.33;
  c.bins = RadialBins::logarithmic(0.01, 4.0, 30);
  const HalfspaceResult r = simulate_halfspace(c);
  double sum = 0;
  for (int i = 0; i < c.bins.count(); ++i) sum += r.R[i] * c.bins.annulus_area(i);
  EXPECT_NEAR(sum, r.albedo - r.beyond_rmax, 1e-12);
  EXPECT_GT(r.beyond_rmax, 0.0);
  EXPECT_EQ(r.r_lo.front(), 0.0);
  EXPECT_EQ(r.r_hi.back(), 4.0);
}

void expect_identical(const HalfspaceResult& a, const HalfspaceResult& b) {
  EXPECT_EQ(a.albedo, b.albedo);
  EXPECT_EQ(a.albedo_stderr, b.albedo_stderr);
  EXPECT_EQ(a.absorbed, b.absorbed);
  EXPECT_EQ(a.mean_collisions, b.mean_collisions);
  EXPECT_EQ(a.R, b.R);
  EXPECT_EQ(a.R_stderr, b.R_stderr);
}

TEST(Halfspace, DeterministicWhateverTheThreadCount) {
  HalfspaceConfig c = config(0.9, Incidence::Diffuse, 30000, 77);
  c.eta = 1.4;
  HalfspaceResult one, two;
  tbb::task_arena(1).execute([&] { one = simulate_halfspace(c); });
  tbb::task_arena(2).execute([&] { two = simulate_halfspace(c); });
  expect_identical(one, two);
  c.seed = 78;
  const HalfspaceResult other = simulate_halfspace(c);
  EXPECT_NE(other.albedo, one.albedo);
}

// Lengths scale with the mean free path: sigma_t = 2 halves every path exactly, so
// with r_max halved the profile is exactly 4 times larger and the albedo unchanged.
TEST(Halfspace, ScalesWithMeanFreePath) {
  HalfspaceConfig c = config(0.8, Incidence::Normal, 5000, 4);
  c.bins = RadialBins::linear(4.0, 16);
  const HalfspaceResult unit = simulate_halfspace(c);
  c.sigma_t = 2;
  c.bins = RadialBins::linear(2.0, 16);
  const HalfspaceResult half = simulate_halfspace(c);
  EXPECT_EQ(unit.albedo, half.albedo);
  for (int i = 0; i < 16; ++i) EXPECT_DOUBLE_EQ(half.R[i], 4 * unit.R[i]);
}

TEST(Halfspace, RejectsBadConfigurations) {
  auto bad = [](auto change) {
    HalfspaceConfig c;
    change(c);
    EXPECT_THROW(simulate_halfspace(c), std::invalid_argument);
  };
  bad([](HalfspaceConfig& c) { c.albedo = 1.5; });
  bad([](HalfspaceConfig& c) { c.albedo = -0.1; });
  bad([](HalfspaceConfig& c) { c.sigma_t = 0; });
  bad([](HalfspaceConfig& c) { c.g = 1; });
  bad([](HalfspaceConfig& c) { c.eta = 0; });
  bad([](HalfspaceConfig& c) { c.paths = 0; });
  bad([](HalfspaceConfig& c) { c.incidence = Incidence::Angle, c.incidence_angle = kPiD / 2; });
}

TEST(Halfspace, ParsesIncidence) {
  Incidence inc;
  double angle;
  parse_incidence("diffuse", inc, angle);
  EXPECT_EQ(inc, Incidence::Diffuse);
  parse_incidence("angle:30", inc, angle);
  EXPECT_EQ(inc, Incidence::Angle);
  EXPECT_NEAR(angle, kPiD / 6, 1e-15);
  EXPECT_THROW(parse_incidence("angle:95", inc, angle), std::invalid_argument);
  EXPECT_THROW(parse_incidence("angle:x", inc, angle), std::invalid_argument);
  EXPECT_THROW(parse_incidence("sideways", inc, angle), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
