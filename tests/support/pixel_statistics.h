// Per-pixel means and standard errors of the path tracer's estimator, for tests
// that state their tolerance in standard errors.
#pragma once

#include <cmath>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/render/integrator.h"
#include "dermis/render/render_scene.h"

namespace dermis::testing {

struct PixelStatistics {
  int width = 0, height = 0;
  std::vector<RGB> mean, stderr_;  // standard error of the mean, per channel
};

// Renders with pixel-centre rays (no filter) and spp samples per pixel.
inline PixelStatistics pixel_statistics(const RenderScene& sc, int spp, uint64_t seed) {
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
        Rng rng(seed, p, uint64_t(i));
        Ray ray = sc.camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
        RGB L = trace_path(sc, ray, sc.camera_medium, rng, counters);
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

}  // namespace dermis::testing
