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

// Renders with pixel-centre rays (no filter) and spp independent samples per pixel.
inline PixelStatistics pixel_statistics(const RenderScene& sc, int spp, uint64_t seed, const PathStart& start = {}) {
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
        RGB L = trace_path(sc, ray, sc.camera_medium, sampler, counters, start);
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

// Two estimates of the same picture agree: in every region of rw x rh pixels and every
// channel, the means differ by at most 4 standard errors (of the difference).
inline void expect_same_region_means(const PixelStatistics& a, const PixelStatistics& b, int rw, int rh) {
  int failures = 0;
  for (int ry = 0; ry + rh <= a.height; ry += rh)
    for (int rx = 0; rx + rw <= a.width; rx += rw) {
      const float n = float(rw * rh);
      RGB ma(0), mb(0), va(0), vb(0);
      for (int y = ry; y < ry + rh; ++y)
        for (int x = rx; x < rx + rw; ++x) {
          const std::size_t p = std::size_t(y) * a.width + x;
          ma += a.mean[p] / n, mb += b.mean[p] / n;
          va += a.stderr_[p] * a.stderr_[p] / (n * n), vb += b.stderr_[p] * b.stderr_[p] / (n * n);
        }
      for (int c = 0; c < 3; ++c) {
        const double sigma = std::sqrt(double(va[c]) + vb[c]);
        if (std::abs(ma[c] - mb[c]) > 4 * sigma && failures++ < 6)
          ADD_FAILURE() << "region at " << rx << "," << ry << " channel " << c << ": " << ma[c] << " vs " << mb[c]
                        << " (4 sigma = " << 4 * sigma << ")";
      }
    }
  EXPECT_EQ(failures, 0);
}

}  // namespace dermis::testing
