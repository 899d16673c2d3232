#include "dermis/materials/null_scattering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "support/rgb_estimate.h"

namespace dermis {
namespace {

// A chromatic density grid along x, one sample thick in y and z, so that a ray along x
// through the samples' centres reads the piecewise-linear interpolation of the densities
// (with a step from 0 to 3 and back), and a transformed, tilted box for oblique rays.
// `block`: instead, a 16 x 8 x 8 grid of density 1.5 over its first ten x-slices and rising
// beyond, so that rays cross uniform majorant cells (read in closed form) and others.
struct Fixture {
  GridMedium grid;
  GridMediumView view;
  explicit Fixture(bool block = false) {
    grid.kind = GridMedium::Kind::Density;
    if (block) {
      std::vector<float> values;
      for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
          for (int x = 0; x < 16; ++x) values.push_back(x < 10 ? 1.5f : 1.5f + 0.4f * float(x - 9 + (y + z) % 3));
      grid.density = VoxelGrid<float>(16, 8, 8, make_shared_floats(values));
    } else {
      grid.density = VoxelGrid<float>(6, 1, 1, make_shared_floats({0.5f, 3, 0, 0, 1.5f, 2}));
    }
    grid.p0 = Vec3(0, 0, 0);
    grid.p1 = Vec3(2, 1, 1);
    grid.build_majorants();
    view = {&grid, RGB(0.3f, 0.1f, 0.6f), RGB(0.9f, 1.8f, 0.4f), 0, nullptr, false, RGB(0)};
  }
};

// The optical depth along the ray over [0, t] by the midpoint rule (2e5 steps: exact to
// ~1e-9 for these piecewise-linear densities).
RGB optical_depth(const GridMediumView& m, const Ray& ray, float t) {
  constexpr int n = 200000;
  RGB tau;
  const double h = double(t) / n;
  double s[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const MediumCoefficients k = m.at(ray.o + ray.d * float((i + 0.5) * h));
    for (int c = 0; c < 3; ++c) s[c] += (k.sigma_a[c] + k.sigma_s[c]) * h;
  }
  for (int c = 0; c < 3; ++c) tau[c] = float(s[c]);
  return tau;
}

using Estimate = testing::RgbEstimate;
const auto estimate = testing::estimate_rgb;

void expect_within_4_sigma(const Estimate& e, const double expected[3], const char* what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_LE(std::abs(e.mean[c] - expected[c]), 4 * e.se[c] + 1e-7)
        << what << " channel " << c << ": " << e.mean[c] << " vs " << expected[c];
}

// Ratio tracking's estimate of the transmittance, against exp(-optical depth), along the
// axis and along oblique rays that end inside the box.
TEST(NullScattering, RatioTrackingMatchesTheOpticalDepth) {
  for (const bool block : {false, true}) {
    SCOPED_TRACE(block ? "grid with uniform cells" : "grid along x");
    const Fixture f(block);
    if (block) {  // the uniform cells are there: stretches of rays are read in closed form
      int uniform = 0;
      for (const GridMedium::MajorantCell& c : f.grid.majorants) uniform += c.uniform >= 0;
      EXPECT_GT(uniform, 0);
    }
    const Ray rays[] = {{Vec3(-1, 0.5f, 0.5f), Vec3(1, 0, 0)},
                        {Vec3(-0.5f, -0.3f, 0.1f), normalize(Vec3(1, 0.6f, 0.3f))}};
    const float t_maxes[] = {std::numeric_limits<float>::infinity(), 1.6f};
    for (int r = 0; r < 2; ++r) {
      const float t_end = std::isinf(t_maxes[r]) ? 10.0f : t_maxes[r];
      const RGB tau = optical_depth(f.view, rays[r], t_end);
      const double expected[3] = {std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2])};
      Rng rng(11, uint64_t(r));
      const Estimate e =
          estimate(200000, [&] { return ratio_tracking_transmittance(f.view, rays[r], t_maxes[r], rng); });
      expect_within_4_sigma(e, expected, "transmittance");
    }
  }
}

// Delta tracking with the one-sample balance heuristic over channels: in every channel the
// flights' weights reproduce the probability to pass (the transmittance), to scatter
// (int sigma_s T dt) and the mean scattering distance (int t sigma_s T dt), whichever channel
// drew each flight; with a throughput that prefers one channel strongly, too; with absorption
// as an event and as a weight.
TEST(NullScattering, DeltaTrackingIsUnbiasedInEveryChannel) {
  for (const bool block : {false, true}) {
    SCOPED_TRACE(block ? "grid with uniform cells" : "grid along x");
    const Fixture f(block);
    const Ray ray{Vec3(-0.5f, -0.3f, 0.1f), normalize(Vec3(1, 0.6f, 0.3f))};
    const float t_max = 1.6f;
    // Quadrature of the scattering density sigma_s(t) T(t) and t times it.
    constexpr int n = 100000;
    double pass[3], scatter[3] = {0, 0, 0}, mean_t[3] = {0, 0, 0};
    {
      double tau[3] = {0, 0, 0};
      const double h = double(t_max) / n;
      for (int i = 0; i < n; ++i) {
        const float t = float((i + 0.5) * h);
        const MediumCoefficients k = f.view.at(ray.o + ray.d * t);
        for (int c = 0; c < 3; ++c) {
          const double st = k.sigma_a[c] + k.sigma_s[c];
          const double tr_mid = std::exp(-(tau[c] + 0.5 * st * h));
          scatter[c] += k.sigma_s[c] * tr_mid * h;
          mean_t[c] += t * k.sigma_s[c] * tr_mid * h;
          tau[c] += st * h;
        }
      }
      for (int c = 0; c < 3; ++c) pass[c] = std::exp(-tau[c]);
    }
    for (const Absorption absorption : {Absorption::Analog, Absorption::Weighted})
      for (const RGB& beta : {RGB(1), RGB(0.05f, 1, 0.2f)})
        for (const RGB& preference : {RGB(1), RGB(1, 3, 0.5f)}) {
          SCOPED_TRACE(absorption == Absorption::Analog ? "analog absorption" : "weighted absorption");
          Rng rng(12, 1), channels(13, 2);
          std::vector<NullScatteringFlight> flights;
          for (int i = 0; i < 200000; ++i)
            flights.push_back(sample_null_scattering_flight(f.view, ray, t_max, beta, preference, channels.uniform(),
                                                            rng, absorption));
          auto over_flights = [&](const std::function<RGB(const NullScatteringFlight&)>& value) {
            std::size_t i = 0;
            return estimate(int(flights.size()), [&] { return value(flights[i++]); });
          };
          expect_within_4_sigma(over_flights([](const NullScatteringFlight& fl) {
                                  return fl.valid && !fl.scattered ? fl.weight : RGB(0);
                                }),
                                pass, "pass");
          expect_within_4_sigma(over_flights([](const NullScatteringFlight& fl) {
                                  return fl.valid && fl.scattered ? fl.weight : RGB(0);
                                }),
                                scatter, "scatter");
          expect_within_4_sigma(over_flights([](const NullScatteringFlight& fl) {
                                  return fl.valid && fl.scattered ? fl.weight * fl.t : RGB(0);
                                }),
                                mean_t, "distance");
        }
  }
}

// A channel with no medium passes with weight one over the box, and an absorbing-only
// medium never scatters.
TEST(NullScattering, EdgeCases) {
  Fixture f;
  f.view.sigma_a_unit = RGB(0.3f, 0, 2);
  f.view.sigma_s_unit = RGB(0.9f, 0, 0);
  const Ray ray{Vec3(-1, 0.5f, 0.5f), Vec3(1, 0, 0)};
  Rng rng(14, 1);
  for (int i = 0; i < 1000; ++i) {
    const NullScatteringFlight fl = sample_null_scattering_flight(f.view, ray, std::numeric_limits<float>::infinity(),
                                                                  RGB(0, 1, 0), RGB(1), 0.5f, rng);
    ASSERT_TRUE(fl.valid);
    ASSERT_FALSE(fl.scattered);
    ASSERT_EQ(fl.weight[1], 1.0f);
  }
}

}  // namespace
}  // namespace dermis
