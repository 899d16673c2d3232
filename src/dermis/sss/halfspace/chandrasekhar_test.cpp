#include "dermis/sss/halfspace/chandrasekhar.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dermis::sss {
namespace {

// Zeroth moment: integrating the H-equation over mu gives h0 = 1 + (alpha/4) h0^2,
// so int_0^1 H = (2/alpha)(1 - sqrt(1 - alpha)) (Chandrasekhar 1950, ch. V).
TEST(ChandrasekharH, ZerothMomentIdentity) {
  for (double alpha : {0.1, 0.5, 0.9, 0.99, 0.999, 1.0}) {
    HFunction h(alpha);
    EXPECT_NEAR(h.moment(0), 2 / alpha * (1 - std::sqrt(1 - alpha)), 1e-12) << alpha;
  }
}

// Conservative case: int H = 2 and int H mu = 2/sqrt(3) (Chandrasekhar 1950, ch. V),
// and H(1) = 2.9078 (Chandrasekhar 1950, Table of H for isotropic conservative scattering).
TEST(ChandrasekharH, ConservativeCase) {
  HFunction h(1.0);
  EXPECT_NEAR(h.moment(0), 2.0, 1e-12);
  EXPECT_NEAR(h.moment(1), 2 / std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(h(1.0), 2.9078, 5e-5);
  EXPECT_NEAR(halfspace_albedo_collimated(h, 1.0), 1.0, 1e-15);
  EXPECT_NEAR(halfspace_albedo_diffuse(h), 1.0, 1e-15);
}

TEST(ChandrasekharH, TendsToOneAsAlbedoVanishes) {
  for (double alpha : {1e-3, 1e-6}) {
    HFunction h(alpha);
    for (double mu : {0.0, 0.3, 1.0}) EXPECT_NEAR(h(mu), 1.0, alpha) << alpha << " " << mu;
  }
  HFunction zero(0.0);
  EXPECT_EQ(zero(0.7), 1.0);
  EXPECT_EQ(halfspace_albedo_collimated(zero, 1.0), 0.0);
}

// The original form, the reciprocal form (both by fixed-point iteration) and Newton
// agree, and 64 nodes agree with 128 (Nystrom interpolation between nodes).
TEST(ChandrasekharH, SolversAndNodeCountsAgree) {
  for (double alpha : {0.5, 0.9, 0.99}) {
    HFunction newton(alpha, 128, HSolver::Newton);
    HFunction original(alpha, 128, HSolver::Original, 1e-15);
    HFunction reciprocal(alpha, 128, HSolver::Reciprocal, 1e-15);
    HFunction coarse(alpha, 64, HSolver::Newton);
    for (double mu : {0.0, 0.01, 0.25, 0.5, 0.77, 1.0}) {
      EXPECT_NEAR(original(mu), newton(mu), 1e-12) << alpha << " " << mu;
      EXPECT_NEAR(reciprocal(mu), newton(mu), 1e-12) << alpha << " " << mu;
      EXPECT_NEAR(coarse(mu), newton(mu), 1e-9) << alpha << " " << mu;
    }
    // The Nystrom formula reproduces the node values.
    for (size_t i = 0; i < newton.nodes().size(); i += 17)
      EXPECT_NEAR(newton(newton.nodes()[i]), newton.values()[i], 1e-13);
    EXPECT_LT(newton.iterations(), 20);
  }
}

TEST(ChandrasekharH, AlbedoIncreasesWithSingleScatteringAlbedo) {
  double prev_n = 0;
  for (double alpha : {0.2, 0.5, 0.8, 0.95, 0.999}) {
    HFunction h(alpha);
    const double rn = halfspace_albedo_collimated(h, 1.0), rd = halfspace_albedo_diffuse(h);
    EXPECT_GT(rn, prev_n);
    EXPECT_GT(rd, rn);  // grazing light escapes more easily than normal light
    EXPECT_LT(rd, 1.0);
    prev_n = rn;
  }
}

TEST(ChandrasekharH, RejectsBadAlbedo) {
  EXPECT_THROW(HFunction(-0.1), std::invalid_argument);
  EXPECT_THROW(HFunction(1.5), std::invalid_argument);
  EXPECT_THROW(HFunction(std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
