// The interface of the OpenImageIO plugin (src/dermis_oiio_plugin/): every image format
// but the two a render writes. Debian's OpenImageIO links 260 libraries (FFmpeg,
// GStreamer, OpenCV, GDAL, ...), whose loading took 0.44 s of every process; loaded with
// dlopen on the first image read (a texture, `dermis compare`) or written in another format,
// a render that reads no image starts in 20 ms. The plugin reports failures in `error`
// (no exception crosses the boundary).
#pragma once

#include <string>
#include <vector>

namespace dermis {

// What the plugin decodes: the first min(3, channels) channels as float, and how their
// values relate to linear radiance (the caller linearizes).
struct DecodedImage {
  enum class Encoding { kLinear, kSrgb, kGamma };
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;  // width x height x channels, top row first
  Encoding encoding = Encoding::kLinear;
  float gamma = 1;  // kGamma: value = encoded^gamma
};

}  // namespace dermis

extern "C" {
// Reads `path`; on failure leaves `error` non-empty (the reason, without the path).
void dermis_plugin_read_image(const char* path, dermis::DecodedImage* out, std::string* error);
// Writes `rgb` (width x height x 3 float; already sRGB-encoded where `format` is 8-bit) to
// `path` in OpenImageIO's `format` ("hdr", "tiff", "jpeg"); on failure `error` non-empty.
void dermis_plugin_write_image(const char* path, const char* format, int width, int height, const float* rgb,
                               std::string* error);
}

namespace dermis {

// The plugin's entry points, loaded on first use (thread-safe): from the environment
// variable DERMIS_OIIO_PLUGIN if set, else libdermis_oiio.so in the folder of the program
// or module this code is part of, or in one of its three parents (build/, build/python/dermis/,
// ...). Throws std::runtime_error saying where it looked when it cannot be loaded.
struct ImagePlugin {
  decltype(&dermis_plugin_read_image) read = nullptr;
  decltype(&dermis_plugin_write_image) write = nullptr;
};
const ImagePlugin& image_plugin();

}  // namespace dermis
