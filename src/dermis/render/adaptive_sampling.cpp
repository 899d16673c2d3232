#include "dermis/render/adaptive_sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace dermis {

int default_min_spp(int spp) {
  const int root = int(std::ceil(std::sqrt(double(std::max(spp, 1)))));
  const int rounded = (std::max(16, root) + 15) / 16 * 16;
  return std::min(spp, rounded);
}

float pixel_noise_error(const Film& film, std::size_t pixel, double output_scale) {
  return pixel_noise_error(&film.sum[3 * pixel], &film.sum_sq[3 * pixel], film.samples[pixel], output_scale);
}

float pixel_noise_error(const double* sum, const double* sum_sq, uint32_t n, double output_scale) {
  if (n < 2) return std::numeric_limits<float>::infinity();
  double mean_sum = 0, se2_sum = 0;
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / n;
    // Sample variance: (sum of squares - n mean^2) / (n - 1); its mean's: that over n.
    const double variance = std::max(0.0, (sum_sq[c] - mean * sum[c]) / (n - 1));
    mean_sum += mean;
    se2_sum += variance / n;
  }
  if (se2_sum <= 0) return 0;
  const double standard_error = std::sqrt(se2_sum / 3) * output_scale;
  const double value = std::max(mean_sum / 3 * output_scale, kErrorValueFloor);
  return float(standard_error / std::sqrt(value));
}

void noise_error_map(const Film& film, double output_scale, std::span<float> error) {
  for (std::size_t p = 0; p < film.pixel_count(); ++p) error[p] = pixel_noise_error(film, p, output_scale);
}

void neighbourhood_max(std::span<const float> error, int width, int height, std::span<float> out) {
  // Separable: the maximum over rows of three, then over columns of three.
  std::vector<float> rows(error.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = std::size_t(y) * width + x;
      float m = error[i];
      if (x > 0) m = std::max(m, error[i - 1]);
      if (x + 1 < width) m = std::max(m, error[i + 1]);
      rows[i] = m;
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = std::size_t(y) * width + x;
      float m = rows[i];
      if (y > 0) m = std::max(m, rows[i - std::size_t(width)]);
      if (y + 1 < height) m = std::max(m, rows[i + std::size_t(width)]);
      out[i] = m;
    }
}

uint32_t next_adaptive_count(uint32_t count, uint32_t spp) {
  const uint32_t step = std::bit_floor(std::max<uint32_t>(16, count / 4));
  return uint32_t(std::min<uint64_t>(uint64_t(count) + step, spp));
}

}  // namespace dermis
