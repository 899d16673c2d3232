// PROVISIONAL (replaced by the image I/O branch): linear RGB images through OpenImageIO.
#pragma once

#include <string>
#include <vector>

#include "dermis/core/rgb.h"

namespace dermis {

struct Image {
  int width = 0, height = 0;
  std::vector<float> pixels;
  RGB at(int x, int y) const {
    const float* p = &pixels[3 * (std::size_t(y) * width + x)];
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, RGB v) {
    float* p = &pixels[3 * (std::size_t(y) * width + x)];
    p[0] = v[0]; p[1] = v[1]; p[2] = v[2];
  }
};

Image read_image(const std::string& path);
void write_image(const std::string& path, const Image& img);

}  // namespace dermis
