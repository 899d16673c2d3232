// Fits the RGB-to-spectrum grid (src/dermis/spectral/rgb_to_spectrum_fit.h) and writes it
// for the build to put into the library: make_rgb_to_spectrum OUT.bin. The file: 16 bytes
// "dermis-rgb2spec\0", the resolution (int32), 12 bytes of zeros, the coefficients.
#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>

#include "dermis/spectral/rgb_to_spectrum_fit.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    fmt::print(stderr, "usage: make_rgb_to_spectrum OUT.bin\n");
    return 2;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<dermis::SigmoidPolynomial> grid = dermis::fit_rgb_to_spectrum_grid();
  std::ofstream out(argv[1], std::ios::binary);
  const char magic[16] = "dermis-rgb2spec";
  const int32_t resolution = dermis::RgbToSpectrumGrid::kResolution;
  const char zeros[12] = {};
  out.write(magic, sizeof(magic));
  out.write(reinterpret_cast<const char*>(&resolution), sizeof(resolution));
  out.write(zeros, sizeof(zeros));
  out.write(reinterpret_cast<const char*>(grid.data()), std::streamsize(grid.size() * sizeof(grid[0])));
  if (!out) {
    fmt::print(stderr, "make_rgb_to_spectrum: cannot write {}\n", argv[1]);
    return 1;
  }
  fmt::print("make_rgb_to_spectrum: {} fits in {:.1f} s\n", grid.size(),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}
