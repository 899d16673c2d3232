#include "dermis/sss/walk/albedo_inversion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dermis/source_hashes.h"
#include "dermis/sss/halfspace/chandrasekhar.h"
#include "dermis/sss/halfspace/halfspace.h"

namespace dermis::sss {
namespace {

std::string temp_cache_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dermis-albedo-test-" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

AlbedoTableConfig small_table(double eta, const std::string& cache_dir) {
  AlbedoTableConfig c;
  c.eta = eta;
  c.size = 24;
  c.paths_per_node = 20000;
  c.cache_dir = cache_dir;
  c.cache_min_seconds = 0;  // always write, so that the test exercises the cache
  return c;
}

// A -> alpha -> A and alpha -> A -> alpha on the interpolant.
TEST(AlbedoInversion, RoundTrips) {
  const AlbedoInversion inv(small_table(1.4, temp_cache_dir("roundtrip")));
  for (double a = 0.0; a <= 1.0; a += 0.05) EXPECT_NEAR(inv.surface_albedo(inv.single_scattering_albedo(a)), a, 1e-9);
  for (double alpha : {0.0, 0.3, 0.8, 0.97, 0.999, 1.0})
    EXPECT_NEAR(inv.single_scattering_albedo(inv.surface_albedo(alpha)), alpha, 1e-7) << alpha;
  EXPECT_EQ(inv.surface_albedo(1.0), 1.0);
  EXPECT_EQ(inv.surface_albedo(0.0), 0.0);
  for (size_t i = 1; i < inv.node_albedos().size(); ++i)
    EXPECT_LE(inv.node_albedos()[i], inv.node_albedos()[i - 1]);  // monotone in t
}

// Index-matched boundary: each table node against Chandrasekhar's exact diffuse
// albedo 1 - 2 sqrt(1 - alpha) int H mu, within 4 sigma (the monotone fit may only move
// a node toward its neighbours; the raw value is what is unbiased, so allow 4 sigma of both).
TEST(AlbedoInversion, IndexMatchedNodesMatchChandrasekhar) {
  const AlbedoInversion inv(small_table(1.0, temp_cache_dir("chandrasekhar")));
  const auto& alpha = inv.node_alphas();
  for (size_t i = 1; i + 1 < alpha.size(); i += 3) {
    const double reference = halfspace_albedo_diffuse(HFunction(alpha[i]));
    EXPECT_NEAR(inv.node_albedos()[i], reference, 4 * inv.node_stderrs()[i] + 1e-12) << "alpha=" << alpha[i];
  }
}

// Between the nodes, against a direct simulation (another seed) with a dielectric boundary.
TEST(AlbedoInversion, AgreesWithDirectSimulation) {
  const AlbedoInversion inv(small_table(1.4, temp_cache_dir("direct")));
  for (double alpha : {0.6, 0.9, 0.985}) {
    HalfspaceConfig c;
    c.albedo = alpha;
    c.eta = 1.4;
    c.incidence = Incidence::Diffuse;
    c.sampling = WalkSampling::Mis;
    c.paths = 40000;
    c.seed = 99;
    c.bins = RadialBins::linear(1.0, 1);
    const HalfspaceResult r = simulate_halfspace(c);
    // The table's own noise at alpha: the largest node stderr (nodes share one seed).
    double table_sigma = 0;
    for (double s : inv.node_stderrs()) table_sigma = std::max(table_sigma, s);
    const double sigma = std::hypot(r.albedo_per_entering_stderr(), table_sigma);
    EXPECT_NEAR(inv.surface_albedo(alpha), r.albedo_per_entering(), 4 * sigma) << "alpha=" << alpha;
    EXPECT_NEAR(inv.single_scattering_albedo(r.albedo_per_entering()), alpha, 0.02) << alpha;
  }
}

// The inversion (a node interval, then Newton on its cubic) against bisection on the
// interpolant itself, t* = sup{t : A(t) > a}: on a simulated table, and on a fitted one
// with flat parts (equal nodes, as the monotone fit leaves where the noise ran uphill),
// where the answer is the end of the flat part nearest alpha = 1.
TEST(AlbedoInversion, InvertsAsBisectionOfTheInterpolant) {
  auto bisection = [](const AlbedoInversion& inv, double a) {
    double lo = 0, hi = 1;  // in t = sqrt(1 - alpha)
    for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
      const double mid = 0.5 * (lo + hi);
      (inv.surface_albedo(1 - mid * mid) > a ? lo : hi) = mid;
    }
    const double t = 0.5 * (lo + hi);
    return 1 - t * t;
  };
  const AlbedoInversion simulated(small_table(1.4, temp_cache_dir("newton")));
  AlbedoTableConfig c;
  c.size = 6;
  c.use_cache = false;
  const std::vector<AlbedoNode> flat{{1.0, 0}, {0.7, 0}, {0.7, 0}, {0.4, 0}, {0.1, 0}, {0.1, 0}};
  const AlbedoInversion fitted(c, flat, /*fitted=*/true);
  // Where A(t) meets a flat part, its slope is 0 and the level a pins t down only to
  // about sqrt(1e-16) (A - a is quadratic there, for both methods): 1e-7 in alpha there,
  // 1e-12 where A falls steadily (the simulated table).
  for (const auto& [inv, tolerance] : {std::pair{&simulated, 1e-12}, std::pair{&fitted, 1e-7}}) {
    for (int i = 0; i <= 2000; ++i) {
      const double a = i / 2000.0;
      const double alpha = inv->single_scattering_albedo(a);
      EXPECT_NEAR(alpha, bisection(*inv, a), tolerance) << "A = " << a;
      if (a > inv->node_albedos().back() && a < inv->node_albedos().front()) {
        EXPECT_NEAR(inv->surface_albedo(alpha), a, 1e-12) << "A = " << a;
      }
    }
    for (double a : inv->node_albedos()) EXPECT_NEAR(inv->single_scattering_albedo(a), bisection(*inv, a), tolerance);
  }
  // On the flat part at 0.7 (t in [0.2, 0.4]): its end nearest alpha = 1, t = 0.2.
  EXPECT_NEAR(fitted.single_scattering_albedo(0.7), 1 - 0.2 * 0.2, 1e-7);
  EXPECT_EQ(fitted.single_scattering_albedo(0.05), 0.0);  // below A(alpha = 0) = 0.1
  EXPECT_EQ(fitted.single_scattering_albedo(1.0), 1.0);
}

// The cache file names what made the table: its parameters and the hash of the code's
// sources (cmake/source_hashes.cmake), so that a table made by other code is never read.
TEST(AlbedoInversion, TheCacheFileNamesTheTablesParametersAndCode) {
  AlbedoTableConfig c = small_table(1.3, temp_cache_dir("key"));
  c.g = 0.25, c.alpha_x = 0.2, c.alpha_y = 0.3, c.seed = 7;
  const AlbedoInversion inv(c);
  const std::string name = std::filesystem::path(inv.cache_path()).filename().string();
  for (const std::string& part : {std::string(source_hash::kAlbedoTable), std::string("eta1.3"), std::string("g0.25"),
                                  std::string("ax0.2"), std::string("ay0.3"), std::string("n24"), std::string("p20000"),
                                  std::string("s7"), std::string(walk_sampling_name(c.sampling))})
    EXPECT_NE(name.find(part), std::string::npos) << part << " in " << name;
  // Each parameter gives another file.
  AlbedoTableConfig other = c;
  other.exit_matched = true;
  EXPECT_NE(AlbedoInversion(other).cache_path(), inv.cache_path());
}

TEST(AlbedoInversion, CachesAndRebuildsCorruptCache) {
  const std::string dir = temp_cache_dir("cache");
  AlbedoTableConfig c = small_table(1.2, dir);
  c.size = 8;
  c.paths_per_node = 2000;
  const AlbedoInversion built(c);
  EXPECT_FALSE(built.from_cache());
  ASSERT_TRUE(std::filesystem::exists(built.cache_path()));
  const AlbedoInversion loaded(c);
  EXPECT_TRUE(loaded.from_cache());
  EXPECT_EQ(loaded.node_albedos(), built.node_albedos());
  EXPECT_EQ(loaded.single_scattering_albedo(0.5), built.single_scattering_albedo(0.5));
  // Another key (seed) is another file.
  c.seed = 2;
  EXPECT_FALSE(AlbedoInversion(c).from_cache());
  c.seed = 1;
  std::ofstream(built.cache_path()) << "garbage\n";
  const AlbedoInversion rebuilt(c);
  EXPECT_FALSE(rebuilt.from_cache());
  EXPECT_EQ(rebuilt.node_albedos(), built.node_albedos());  // deterministic
  std::filesystem::remove_all(dir);
}

TEST(AlbedoInversion, VanDeHulstFitEndsAndRejectsBadInput) {
  EXPECT_NEAR(van_de_hulst_single_scattering_albedo(1.0), 1.0, 1e-4);
  EXPECT_NEAR(van_de_hulst_single_scattering_albedo(0.0), 0.0, 1e-3);
  EXPECT_THROW(van_de_hulst_single_scattering_albedo(1.5), std::invalid_argument);
  AlbedoTableConfig c;
  c.size = 2;
  EXPECT_THROW(AlbedoInversion{c}, std::invalid_argument);
  c = AlbedoTableConfig{};
  c.eta = -1;
  EXPECT_THROW(AlbedoInversion{c}, std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
