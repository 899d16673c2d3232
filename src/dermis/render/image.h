// Images in memory (linear RGB float) and their files: OpenEXR and PNG written with
// OpenEXR and libpng, everything else through the OpenImageIO plugin (image_plugin.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dermis/core/rgb.h"

namespace dermis {

// Linear RGB float, row-major, top row first, 3 floats per pixel.
struct Image {
  int width = 0, height = 0;
  std::vector<float> pixels;
  // Further per-pixel values written as channels of their own by the OpenEXR writer (and
  // ignored by the other formats): e.g. a render's sample counts and error estimates.
  struct Channel {
    std::string name;
    std::vector<float> values;  // one per pixel
  };
  std::vector<Channel> extra_channels;

  Image() = default;
  // A width x height image filled with `fill`; throws std::invalid_argument on negative sizes.
  Image(int w, int h, RGB fill = RGB(0));

  RGB at(int x, int y) const {
    const float* p = &pixels[3 * (std::size_t(y) * std::size_t(width) + std::size_t(x))];
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, RGB v) {
    float* p = &pixels[3 * (std::size_t(y) * std::size_t(width) + std::size_t(x))];
    p[0] = v[0], p[1] = v[1], p[2] = v[2];
  }
  std::size_t pixel_count() const { return std::size_t(width) * std::size_t(height); }
};

// The sRGB transfer curve (IEC 61966-2-1:1999), one channel.
float srgb_to_linear(float encoded);
float linear_to_srgb(float linear);

// Reads any format OpenImageIO reads (through the plugin). Gray (1 channel) is replicated, gray+alpha
// and RGBA drop the alpha, extra channels beyond the fourth are ignored. 8- and
// 16-bit integer data tagged (or, untagged, presumed) sRGB is linearized.
// Throws std::runtime_error("PATH: could not read image: REASON").
Image read_image(const std::string& path);

// Writes by extension: .exr (32-bit float, zip; with the extra channels), .hdr (RGBE), .tif/.tiff (32-bit float),
// .png/.jpg/.jpeg (sRGB-encoded 8-bit, clamped to [0, 1]). The file appears
// atomically: it is written to "PATH.tmp-PID" beside PATH, then renamed. Throws
// std::runtime_error for an unknown extension, a non-finite pixel, or a failed write
// (leaving no file behind).
void write_image(const std::string& path, const Image& img);

// A PNG in memory (8-bit RGB with an sRGB chunk) from 8-bit sRGB values, width x height
// x 3, row-major, fast (a zlib level, 0 to 9, with Huffman coding alone: what the preview
// serves, preview/).
std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb8, int zlib_level);

}  // namespace dermis
