#include "dermis/sss/study/fit_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {
namespace {

// A reference R = e^{-r} / r on log-spaced bins [0.01 * 1.2^i, 0.01 * 1.2^{i+1}).
BinnedProfile log_reference(int n = 40) {
  BinnedProfile p;
  double lo = 0.01;
  for (int i = 0; i < n; ++i) {
    const double hi = lo * 1.2;
    p.r_lo.push_back(lo);
    p.r_hi.push_back(hi);
    const double mid = std::sqrt(lo * hi);
    p.value.push_back(std::exp(-mid) / mid);
    p.standard_error.push_back(0.05 * p.value.back());
    lo = hi;
  }
  return p;
}

BinnedProfile scaled(const BinnedProfile& p, double k) {
  BinnedProfile q = p;
  for (double& v : q.value) v *= k;
  return q;
}

// A model 1.1 x the reference is 10% off in every measure (and 0.9 x too), exactly.
TEST(FitError, UniformScaleGivesThatRelativeError) {
  const BinnedProfile ref = log_reference();
  for (ErrorMeasure m : {ErrorMeasure::LogRadius, ErrorMeasure::LinearRadius, ErrorMeasure::Energy}) {
    EXPECT_NEAR(relative_error(ref, scaled(ref, 1.1), m, 0.02, 3.0), 0.1, 1e-14) << error_measure_name(m);
    EXPECT_NEAR(relative_error(ref, scaled(ref, 0.9), m, 0.02, 3.0), 0.1, 1e-14) << error_measure_name(m);
    EXPECT_EQ(relative_error(ref, ref, m, 0.02, 3.0), 0.0);
  }
}

// Error in one bin only: each measure weighs it by its share of the range.
TEST(FitError, OneBinOffIsWeightedByTheMeasure) {
  const BinnedProfile ref = log_reference();
  BinnedProfile model = ref;
  const int k = 10;
  model.value[k] *= 1.5;
  const double lo = ref.r_lo[k], hi = ref.r_hi[k];
  const double r_a = ref.r_lo[2], r_b = ref.r_hi[30];
  EXPECT_NEAR(relative_error(ref, model, ErrorMeasure::LogRadius, r_a, r_b),
              0.5 * std::log(hi / lo) / std::log(r_b / r_a), 1e-14);
  EXPECT_NEAR(relative_error(ref, model, ErrorMeasure::LinearRadius, r_a, r_b), 0.5 * (hi - lo) / (r_b - r_a), 1e-14);
  double energy = 0;
  for (size_t i = 0; i < ref.value.size(); ++i)
    energy += ref.value[i] * kPiD * (ref.r_hi[i] * ref.r_hi[i] - ref.r_lo[i] * ref.r_lo[i]);
  EXPECT_NEAR(relative_error(ref, model, ErrorMeasure::Energy, r_a, r_b),
              0.5 * ref.value[k] * kPiD * (hi * hi - lo * lo) / energy, 1e-14);
  // Outside the range, the range measures do not see it.
  EXPECT_EQ(relative_error(ref, model, ErrorMeasure::LogRadius, ref.r_lo[11], r_b), 0.0);
}

// Partial overlap of a bin with the range counts the overlap only.
TEST(FitError, PartialBinOverlap) {
  BinnedProfile ref;
  ref.r_lo = {0, 1, 2};
  ref.r_hi = {1, 2, 4};
  ref.value = {1, 1, 1};
  BinnedProfile model = ref;
  model.value = {1, 2, 1};  // 100% off on [1, 2)
  EXPECT_NEAR(relative_error(ref, model, ErrorMeasure::LinearRadius, 0.5, 3), 1.0 / 2.5, 1e-15);
  EXPECT_NEAR(relative_error(ref, model, ErrorMeasure::LogRadius, 0.5, 3), std::log(2.0) / std::log(6.0), 1e-15);
  // Energy: |2 - 1| * pi (4 - 1) / (pi * 16).
  EXPECT_NEAR(relative_error(ref, model, ErrorMeasure::Energy, 0.5, 3), 3.0 / 16, 1e-15);
}

TEST(FitError, NoiseFloorAndEnergyRadius) {
  const BinnedProfile ref = log_reference();
  for (ErrorMeasure m : {ErrorMeasure::LogRadius, ErrorMeasure::LinearRadius, ErrorMeasure::Energy})
    EXPECT_NEAR(noise_floor(ref, m, 0.02, 3.0), 0.05 * std::sqrt(2 / kPiD), 1e-14);
  BinnedProfile flat;
  flat.r_lo = {0, 1};
  flat.r_hi = {1, 2};
  flat.value = {1, 1};
  // Uniform R on the disk of radius 2: half the energy inside sqrt(2), 1/8 inside 1/sqrt(2).
  EXPECT_NEAR(energy_radius(flat, 4 * kPiD, 0.5), std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(energy_radius(flat, 4 * kPiD, 0.125), std::sqrt(0.5), 1e-14);
  // Energy beyond the bins (total larger than their sum): the last edge.
  EXPECT_EQ(energy_radius(flat, 100 * kPiD, 0.99), 2.0);
}

TEST(FitError, RejectsBadInput) {
  const BinnedProfile ref = log_reference();
  BinnedProfile shorter = ref;
  shorter.value.pop_back();
  shorter.r_lo.pop_back();
  shorter.r_hi.pop_back();
  EXPECT_THROW(relative_error(ref, shorter, ErrorMeasure::Energy, 0.02, 3), std::invalid_argument);
  EXPECT_THROW(relative_error(ref, ref, ErrorMeasure::LogRadius, 3, 0.02), std::invalid_argument);
  EXPECT_THROW(relative_error(ref, ref, ErrorMeasure::LogRadius, 0, 1), std::invalid_argument);
  BinnedProfile hole = ref;
  hole.value[5] = 0;
  EXPECT_THROW(relative_error(hole, ref, ErrorMeasure::LogRadius, 0.01, 1), std::invalid_argument);
  EXPECT_THROW(noise_floor(BinnedProfile{ref.r_lo, ref.r_hi, ref.value, {}}, ErrorMeasure::Energy, 0, 0),
               std::invalid_argument);
  EXPECT_THROW(energy_radius(ref, 1, 1.0), std::invalid_argument);
  EXPECT_THROW(energy_radius(ref, 0, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
