// Per-pixel means and standard errors of the path tracer's estimator, for tests
// that state their tolerance in standard errors.
#pragma once

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

}  // namespace dermis::testing
