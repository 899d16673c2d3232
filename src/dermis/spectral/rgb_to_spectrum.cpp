#include "dermis/spectral/rgb_to_spectrum.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include "dermis/spectral/rgb_to_spectrum_fit.h"

// The grid fitted at build time, built in by rgb_to_spectrum_data.S (CMakeLists.txt): a
// header (kTableMagic, the resolution) and the coefficients.
extern "C" const unsigned char dermis_rgb_to_spectrum_srgb[];
extern "C" const unsigned char dermis_rgb_to_spectrum_srgb_end[];

namespace dermis {

namespace {

constexpr char kTableMagic[16] = "dermis-rgb2spec";

// The z nodes, for the search.
const std::array<float, RgbToSpectrumGrid::kResolution>& z_nodes() {
  static const auto nodes = [] {
    std::array<float, RgbToSpectrumGrid::kResolution> z;
    for (int i = 0; i < RgbToSpectrumGrid::kResolution; ++i) z[std::size_t(i)] = float(RgbToSpectrumGrid::z_node(i));
    return z;
  }();
  return nodes;
}

}  // namespace

const RgbToSpectrumTable& RgbToSpectrumTable::srgb() {
  static const RgbToSpectrumTable table = [] {
    const unsigned char* begin = dermis_rgb_to_spectrum_srgb;
    const std::size_t bytes = std::size_t(dermis_rgb_to_spectrum_srgb_end - begin);
    int32_t resolution = 0;
    if (bytes >= 32) std::memcpy(&resolution, begin + 16, sizeof(resolution));
    if (bytes != 32 + RgbToSpectrumGrid::kCells * sizeof(SigmoidPolynomial) ||
        std::memcmp(begin, kTableMagic, sizeof(kTableMagic)) != 0 || resolution != RgbToSpectrumGrid::kResolution)
      throw std::logic_error("the built-in RGB-to-spectrum table does not match this code: rebuild Dermis");
    return RgbToSpectrumTable(
        std::span(reinterpret_cast<const SigmoidPolynomial*>(begin + 32), RgbToSpectrumGrid::kCells));
  }();
  return table;
}

RgbToSpectrumTable::RgbToSpectrumTable(std::span<const SigmoidPolynomial> grid) : grid_(grid) {
  if (grid.size() != RgbToSpectrumGrid::kCells) throw std::invalid_argument("RgbToSpectrumTable: not a full grid");
}

RgbSpectrum RgbToSpectrumTable::operator()(RGB rgb) const {
  constexpr int n = RgbToSpectrumGrid::kResolution;
  for (int k = 0; k < 3; ++k) rgb[k] = std::clamp(rgb[k], 0.0f, 1.0f);
  RgbSpectrum out;
  if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
    out.polynomial[0] = SigmoidPolynomial::constant(rgb[0]);
    out.weight[0] = 1;
    out.count = 1;
    return out;
  }
  const int channel = rgb[0] > rgb[1] ? (rgb[0] > rgb[2] ? 0 : 2) : (rgb[1] > rgb[2] ? 1 : 2);
  const float z = rgb[channel];
  // Weights linear in the rgb (in z and in the ratios to it): the blend's colour is the rgb.
  const float x = rgb[(channel + 1) % 3] / z * (n - 1), y = rgb[(channel + 2) % 3] / z * (n - 1);
  const int xi = std::min(int(x), n - 2), yi = std::min(int(y), n - 2);
  const auto& nodes = z_nodes();
  const int zi =
      int(std::clamp<std::ptrdiff_t>(std::upper_bound(nodes.begin(), nodes.end(), z) - nodes.begin() - 1, 0, n - 2));
  const float fx = x - float(xi), fy = y - float(yi);
  const float fz = (z - nodes[std::size_t(zi)]) / (nodes[std::size_t(zi) + 1] - nodes[std::size_t(zi)]);
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const float w = (dz ? fz : 1 - fz) * (dy ? fy : 1 - fy) * (dx ? fx : 1 - fx);
        if (w == 0) continue;
        out.polynomial[std::size_t(out.count)] = grid_[RgbToSpectrumGrid::index(channel, zi + dz, yi + dy, xi + dx)];
        out.weight[std::size_t(out.count)] = w;
        ++out.count;
      }
  return out;
}

UnboundedSpectrum unbounded_spectrum(const RgbToSpectrumTable& table, RGB rgb) {
  const float m = std::max({rgb[0], rgb[1], rgb[2], 0.0f});
  UnboundedSpectrum s;
  s.scale = 2 * m;
  s.reflectance = table(m > 0 ? rgb / s.scale : RGB(0));
  return s;
}

}  // namespace dermis
