#include "dermis/render/film.h"

#include <algorithm>
#include <cmath>

namespace dermis {

namespace {

// pbrt-v4's Gaussian filter: exp(-x^2 / (2 sigma^2)) minus its value at the radius.
std::vector<float> gaussian_table(float radius, float sigma, int n) {
  std::vector<float> f(n);
  float edge = std::exp(-radius * radius / (2 * sigma * sigma));
  for (int i = 0; i < n; ++i) {
    float x = -radius + (float(i) + 0.5f) / float(n) * 2 * radius;
    f[i] = std::max(0.0f, std::exp(-x * x / (2 * sigma * sigma)) - edge);
  }
  return f;
}

}  // namespace

FilterSampler::FilterSampler(const FilterDesc& desc) : desc_(desc) {
  if (desc_.type == FilterDesc::Type::Gaussian) {
    constexpr int kBins = 64;
    auto fx = gaussian_table(desc_.radius.x, desc_.sigma, kBins);
    auto fy = gaussian_table(desc_.radius.y, desc_.sigma, kBins);
    x_ = Distribution1D(fx);
    y_ = Distribution1D(fy);
  }
}

Vec2 FilterSampler::sample(Vec2 u) const {
  if (desc_.type == FilterDesc::Type::Box) return {(2 * u.x - 1) * desc_.radius.x, (2 * u.y - 1) * desc_.radius.y};
  float pdf;
  float sx = x_.sample_continuous(u.x, &pdf);
  float sy = y_.sample_continuous(u.y, &pdf);
  return {(2 * sx - 1) * desc_.radius.x, (2 * sy - 1) * desc_.radius.y};
}

std::vector<float> Film::resolve() const {
  std::vector<float> out(sum.size());
  for (std::size_t i = 0; i < samples.size(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = samples[i] ? float(sum[3 * i + c] / samples[i]) : 0.0f;
  return out;
}

PixelBounds film_pixel_bounds(const FilmDesc& f) {
  // In float, as pbrt-v4 computes it (0.3f * 40 rounds to 12, not 12.0000005).
  auto bound = [](int res, float fraction) { return std::clamp(int(std::ceil(float(res) * fraction)), 0, res); };
  PixelBounds b{bound(f.xres, f.crop[0]), bound(f.yres, f.crop[2]), bound(f.xres, f.crop[1]), bound(f.yres, f.crop[3])};
  b.x0 = std::min(b.x0, f.xres - 1);
  b.y0 = std::min(b.y0, f.yres - 1);
  b.x1 = std::max(b.x1, b.x0 + 1);
  b.y1 = std::max(b.y1, b.y0 + 1);
  return b;
}

}  // namespace dermis
