// The half-space simulator with the Dwivedi and MIS policies (walk_sampling.h).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "dermis/sss/halfspace/chandrasekhar.h"
#include "dermis/sss/halfspace/halfspace.h"

namespace dermis::sss {
namespace {

HalfspaceConfig guided_config(WalkSampling sampling, double albedo, Incidence incidence, uint64_t paths) {
  HalfspaceConfig c;
  c.sampling = sampling;
  c.albedo = albedo;
  c.incidence = incidence;
  c.paths = paths;
  c.seed = 17;
  c.bins = RadialBins::linear(8.0, 4);
  return c;
}

// Index-matched isotropic half-space: Chandrasekhar's albedo, both incidences,
// classical, Dwivedi and MIS (classical is also covered by halfspace_test.cpp).
TEST(GuidedHalfspace, AlbedoMatchesChandrasekhar) {
  for (double alpha : {0.5, 0.9, 0.99}) {
    const HFunction h(alpha);
    for (WalkSampling sampling : {WalkSampling::Classical, WalkSampling::Dwivedi, WalkSampling::Mis})
      for (Incidence incidence : {Incidence::Normal, Incidence::Diffuse}) {
        const HalfspaceResult r = simulate_halfspace(guided_config(sampling, alpha, incidence, 50000));
        const double reference =
            incidence == Incidence::Normal ? halfspace_albedo_collimated(h, 1.0) : halfspace_albedo_diffuse(h);
        EXPECT_LT(r.albedo_stderr, 3e-3);
        EXPECT_NEAR(r.albedo, reference, 4 * r.albedo_stderr)
            << walk_sampling_name(sampling) << " alpha=" << alpha << " incidence=" << int(incidence);
        EXPECT_EQ(r.truncated, 0u);
      }
  }
}

// Anisotropic scattering and a dielectric boundary (Fresnel reflections call fly()):
// no closed form; guided and MIS agree with classical within 4 combined sigma, and
// energy balances: specular + albedo + absorbed = 1.
TEST(GuidedHalfspace, AnisotropicDielectricAgreesWithClassical) {
  for (double g : {0.1, 0.8}) {
    HalfspaceConfig c = guided_config(WalkSampling::Classical, 0.95, Incidence::Diffuse, 40000);
    c.g = g;
    c.eta = 1.4;
    const HalfspaceResult classical = simulate_halfspace(c);
    for (WalkSampling sampling : {WalkSampling::Dwivedi, WalkSampling::Mis}) {
      c.sampling = sampling;
      c.seed = 18;
      const HalfspaceResult r = simulate_halfspace(c);
      EXPECT_NEAR(r.albedo, classical.albedo, 4 * std::hypot(r.albedo_stderr, classical.albedo_stderr))
          << walk_sampling_name(sampling) << " g=" << g;
      EXPECT_NEAR(r.specular + r.albedo + r.absorbed, 1.0, 4 * (r.albedo_stderr + r.absorbed_stderr))
          << walk_sampling_name(sampling) << " g=" << g;
    }
  }
}

// Guided sampling keeps the simulator's determinism for any thread count.
TEST(GuidedHalfspace, DeterministicWhateverTheThreadCount) {
  const HalfspaceConfig c = guided_config(WalkSampling::Mis, 0.9, Incidence::Diffuse, 20000);
  HalfspaceResult one, two;
  tbb::task_arena(1).execute([&] { one = simulate_halfspace(c); });
  tbb::task_arena(2).execute([&] { two = simulate_halfspace(c); });
  EXPECT_EQ(one.albedo, two.albedo);
  EXPECT_EQ(one.R, two.R);
}

TEST(GuidedHalfspace, RejectsBadGuidedProbability) {
  HalfspaceConfig c = guided_config(WalkSampling::Mis, 0.9, Incidence::Normal, 10);
  c.p_guided = 1.5;
  EXPECT_THROW(simulate_halfspace(c), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
