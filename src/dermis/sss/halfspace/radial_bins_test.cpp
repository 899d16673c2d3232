#include "dermis/sss/halfspace/radial_bins.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dermis::sss {
namespace {

void check_consistent(const RadialBins& bins) {
  double area = 0;
  for (int i = 0; i < bins.count(); ++i) {
    area += bins.annulus_area(i);
    EXPECT_EQ(bins.index(bins.lo(i)), i);
    EXPECT_EQ(bins.index(std::nextafter(bins.hi(i), 0.0)), i);
    EXPECT_EQ(bins.index(0.5 * (bins.lo(i) + bins.hi(i))), i);
  }
  EXPECT_NEAR(area, 3.14159265358979323846 * bins.r_max() * bins.r_max(), 1e-12 * area);
  EXPECT_EQ(bins.index(bins.r_max()), -1);
  EXPECT_EQ(bins.index(1e300), -1);
}

TEST(RadialBins, LinearAndLogarithmicAreConsistent) {
  check_consistent(RadialBins::linear(10.0, 37));
  check_consistent(RadialBins::logarithmic(1e-3, 20.0, 50));
  RadialBins log_bins = RadialBins::logarithmic(0.01, 1.0, 3);
  EXPECT_NEAR(log_bins.hi(0), 0.01, 1e-15);
  EXPECT_NEAR(log_bins.hi(1), 0.1, 1e-15);
  EXPECT_EQ(log_bins.index(0.005), 0);
}

TEST(RadialBins, RejectsBadArguments) {
  EXPECT_THROW(RadialBins::linear(0.0, 10), std::invalid_argument);
  EXPECT_THROW(RadialBins::linear(1.0, 0), std::invalid_argument);
  EXPECT_THROW(RadialBins::logarithmic(2.0, 1.0, 10), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
