// The film: per-pixel sums of radiance samples. Reconstruction uses filter
// importance sampling (Ernst et al. 2006; pbrt-v4 sec. 8.8): each sample's
// position is drawn from the filter and it counts for its own pixel only, so every
// pixel is owned by one thread and the result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "dermis/core/distribution.h"
#include "dermis/core/rgb.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

class FilterSampler {
 public:
  explicit FilterSampler(const FilterDesc& desc);
  // Offset from the pixel centre, in pixels.
  Vec2 sample(Vec2 u) const;

 private:
  FilterDesc desc_;
  Distribution1D x_, y_;  // gaussian: tabulated marginals (the filter is separable)
};

// The pixels a render covers: the crop window's (pbrt-v4: ceil of the fractions times
// the resolution), at least one pixel; x in [x0, x1), y in [y0, y1) of the full image.
struct PixelBounds {
  int x0, y0, x1, y1;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};
PixelBounds film_pixel_bounds(const FilmDesc& film);

struct Film {
  int width = 0, height = 0;
  std::vector<double> sum;        // 3 per pixel
  std::vector<double> sum_sq;     // 3 per pixel: the sums of squares (the per-pixel variance)
  std::vector<uint32_t> samples;  // samples taken per pixel (non-finite ones included, as zero)
  // The sample count each pixel is to reach in the pass under way (renderer.cpp): a render
  // stopped in the middle of a pass is resumed by finishing that pass first, so that the
  // result equals a render never stopped even where pixels take different counts.
  std::vector<uint32_t> target;
  // Rays traced per pixel (closest-hit, shadow, probe and walk rays): the cost of its
  // samples, a deterministic measure of time (adaptive sampling's order of work).
  std::vector<uint64_t> rays;

  // Bytes of memory per pixel, for refusing a film that cannot be allocated.
  static constexpr std::size_t kBytesPerPixel = 6 * sizeof(double) + 2 * sizeof(uint32_t) + sizeof(uint64_t);

  Film(int w, int h)
      : width(w),
        height(h),
        sum(std::size_t(w) * h * 3, 0.0),
        sum_sq(std::size_t(w) * h * 3, 0.0),
        samples(std::size_t(w) * h, 0),
        target(std::size_t(w) * h, 0),
        rays(std::size_t(w) * h, 0) {}
  std::size_t pixel_count() const { return samples.size(); }
  // Linear RGB: the mean of each pixel's samples (0 where none were taken).
  std::vector<float> resolve() const;
};

}  // namespace dermis
