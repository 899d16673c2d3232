// Per-pixel means and standard errors of the path tracer's estimator, for tests
// that state their tolerance in standard errors.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dermis/core/sampler.h"
#include "dermis/render/integrator.h"
#include "dermis/render/render_scene.h"

namespace dermis::testing {

struct PixelStatistics {
  int width = 0, height = 0;
  std::vector<RGB> mean, stderr_;  // standard error of the mean, per channel
};

// Renders with pixel-centre rays (no filter) and spp independent samples per pixel;
// `spectral`: each sample with its wavelengths and its colour recorded as the renderer's
// film does (renderer.cpp).
inline PixelStatistics pixel_statistics(const RenderScene& sc, int spp, uint64_t seed, const PathStart& start = {},
                                        bool spectral = false) {
  PixelStatistics st;
  st.width = sc.film.xres;
  st.height = sc.film.yres;
  st.mean.resize(std::size_t(st.width) * st.height);
  st.stderr_.resize(st.mean.size());
  PathCounters counters;
  for (int y = 0; y < st.height; ++y)
    for (int x = 0; x < st.width; ++x) {
      std::size_t p = std::size_t(y) * st.width + x;
      double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
      for (int i = 0; i < spp; ++i) {
        // Independent samples, so that the sample variance gives the standard error.
        Sampler sampler(SamplerKind::Independent, seed, p, uint32_t(i));
        Ray ray = sc.camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
        RGB L;
        if (spectral) {
          SampledWavelengths w = SampledWavelengths::sample_visible(sampler.get1d());
          PathStart with_wavelengths = start;
          with_wavelengths.wavelengths = &w;
          L = w.to_linear_srgb(trace_path(sc, ray, sc.camera_medium, sampler, counters, with_wavelengths));
        } else {
          L = trace_path(sc, ray, sc.camera_medium, sampler, counters, start);
        }
        for (int c = 0; c < 3; ++c) {
          s[c] += L[c];
          s2[c] += double(L[c]) * L[c];
        }
      }
      for (int c = 0; c < 3; ++c) {
        double m = s[c] / spp;
        double var = std::max(0.0, s2[c] / spp - m * m) * spp / std::max(1, spp - 1);
        st.mean[p][c] = float(m);
        st.stderr_[p][c] = float(std::sqrt(var / spp));
      }
    }
  return st;
}

// Per-pixel means and standard errors for any sampler: `replicates` independent
// randomisations (seeds seed, seed + 1, ...) of `spp` samples each, the pixel's estimate
// the mean of the replicates and its standard error their spread (randomised
// quasi-Monte Carlo: a low-discrepancy sampler's samples are not independent, its
// randomisations are). Pixel-centre rays, as above.
inline PixelStatistics replicated_pixel_statistics(const RenderScene& sc, SamplerKind kind, int spp, int replicates,
                                                   uint64_t seed) {
  PixelStatistics st;
  st.width = sc.film.xres;
  st.height = sc.film.yres;
  st.mean.resize(std::size_t(st.width) * st.height);
  st.stderr_.resize(st.mean.size());
  PathCounters counters;
  for (int y = 0; y < st.height; ++y)
    for (int x = 0; x < st.width; ++x) {
      std::size_t p = std::size_t(y) * st.width + x;
      double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
      for (int r = 0; r < replicates; ++r) {
        double est[3] = {0, 0, 0};
        for (int i = 0; i < spp; ++i) {
          Sampler sampler(kind, seed + uint64_t(r), p, uint32_t(i));
          Ray ray = sc.camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
          RGB L = trace_path(sc, ray, sc.camera_medium, sampler, counters);
          for (int c = 0; c < 3; ++c) est[c] += L[c] / spp;
        }
        for (int c = 0; c < 3; ++c) {
          s[c] += est[c];
          s2[c] += est[c] * est[c];
        }
      }
      for (int c = 0; c < 3; ++c) {
        double m = s[c] / replicates;
        double var = std::max(0.0, s2[c] / replicates - m * m) * replicates / std::max(1, replicates - 1);
        st.mean[p][c] = float(m);
        st.stderr_[p][c] = float(std::sqrt(var / replicates));
      }
    }
  return st;
}

// One region's comparison of two estimates: the difference of their region means in a
// channel and its standard error (from the pixels' standard errors: the pixels are independent).
struct RegionComparison {
  int rx = 0, ry = 0, channel = 0;
  double mean_a = 0, mean_b = 0, sigma = 0;
  double z() const { return sigma > 0 ? (mean_a - mean_b) / sigma : (mean_a == mean_b ? 0.0 : INFINITY); }
};

// Every rw x rh region (left to right, top to bottom) and channel of two estimates.
inline std::vector<RegionComparison> region_comparisons(const PixelStatistics& a, const PixelStatistics& b, int rw,
                                                        int rh) {
  std::vector<RegionComparison> out;
  for (int ry = 0; ry + rh <= a.height; ry += rh)
    for (int rx = 0; rx + rw <= a.width; rx += rw) {
      const double n = double(rw * rh);
      double ma[3] = {0, 0, 0}, mb[3] = {0, 0, 0}, va[3] = {0, 0, 0}, vb[3] = {0, 0, 0};
      for (int y = ry; y < ry + rh; ++y)
        for (int x = rx; x < rx + rw; ++x) {
          const std::size_t p = std::size_t(y) * a.width + x;
          for (int c = 0; c < 3; ++c) {
            ma[c] += a.mean[p][c] / n, mb[c] += b.mean[p][c] / n;
            va[c] += double(a.stderr_[p][c]) * a.stderr_[p][c] / (n * n);
            vb[c] += double(b.stderr_[p][c]) * b.stderr_[p][c] / (n * n);
          }
        }
      for (int c = 0; c < 3; ++c) out.push_back({rx, ry, c, ma[c], mb[c], std::sqrt(va[c] + vb[c])});
    }
  return out;
}

// Two estimates of the same picture agree: in every region of rw x rh pixels and every
// channel, the means differ by at most 4 standard errors (of the difference). The standard
// errors come from each image's own sample variances; bench/statistics/ checks them against
// the spread over many seeds (docs/testing.md, "Statistical tests").
//
// detectable_bias > 0: also asserts that the comparison is able to see the bias the test is
// about. A relative bias of that size in `a` moves its most sensitive region-channel (the
// largest mean over sigma) by at least 6 sigma, so it would fail with probability >= 97.7 %
// (z about 6 +- 1 against the bound 4).
inline void expect_same_region_means(const PixelStatistics& a, const PixelStatistics& b, int rw, int rh,
                                     double detectable_bias = 0) {
  int failures = 0;
  double sensitivity = 0;  // the largest |mean| / sigma of a region-channel
  for (const RegionComparison& r : region_comparisons(a, b, rw, rh)) {
    if (std::abs(r.mean_a - r.mean_b) > 4 * r.sigma && failures++ < 6)
      ADD_FAILURE() << "region at " << r.rx << "," << r.ry << " channel " << r.channel << ": " << r.mean_a << " vs "
                    << r.mean_b << " (4 sigma = " << 4 * r.sigma << ")";
    // Regions with noise only: a region of sky alone has none (a sigma that is the rounding
    // of a constant), and a bias of the method under test does not move it.
    if (r.sigma > 1e-5 * std::abs(r.mean_b)) sensitivity = std::max(sensitivity, std::abs(r.mean_b) / r.sigma);
  }
  EXPECT_EQ(failures, 0);
  if (detectable_bias > 0) {
    EXPECT_GE(detectable_bias * sensitivity, 6.0)
        << "too noisy to see a bias of " << detectable_bias << ": the most sensitive region sees " << 6.0 / sensitivity
        << " at 6 sigma";
  }
}

}  // namespace dermis::testing
