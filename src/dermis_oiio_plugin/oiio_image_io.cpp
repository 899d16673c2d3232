// The OpenImageIO plugin: reads any format OpenImageIO reads, writes .hdr, .tif, .jpg
// (render/image_plugin.h says why it is a plugin). Built as the module libdermis_oiio.so.
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include "dermis/render/image_plugin.h"

namespace {

using dermis::DecodedImage;

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

DecodedImage::Encoding file_encoding(const OIIO::ImageSpec& spec, float* gamma) {
  const std::string cs = lower(spec.get_string_attribute("oiio:ColorSpace"));
  if (cs.find("srgb") != std::string::npos) return DecodedImage::Encoding::kSrgb;
  if (cs.find("linear") != std::string::npos || cs == "scene_linear") return DecodedImage::Encoding::kLinear;
  if (cs.rfind("gamma", 0) == 0) {
    // OIIO names a PNG gAMA chunk "GammaCorrected" with the exponent in oiio:Gamma
    // (or spells it "GammaX.Y").
    *gamma = spec.get_float_attribute("oiio:Gamma", 0.0f);
    if (*gamma <= 0) *gamma = std::strtof(cs.c_str() + 5, nullptr);
    if (*gamma > 0) return DecodedImage::Encoding::kGamma;
  }
  // Untagged: integer data (PNG, JPEG, 8/16-bit TIFF) is display-encoded by
  // convention; floating-point data is linear.
  const auto base = spec.format.basetype;
  const bool integer = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::UINT16 ||
                       base == OIIO::TypeDesc::INT8 || base == OIIO::TypeDesc::INT16;
  return integer ? DecodedImage::Encoding::kSrgb : DecodedImage::Encoding::kLinear;
}

// What a header may claim before its pixels are read: at most kMaxImagePixels pixels, and,
// for formats whose compression ratio is bounded (PNG's deflate, HDR's run lengths, most
// OpenEXR compressions), no more bytes of pixels than the file could inflate to. A lying header is refused here
// rather than allocated (a 100-byte PNG claiming 65535 x 65535 used to take 1.8 GB).
constexpr std::size_t kMaxImagePixels = std::size_t(1) << 27;  // 16384 x 8192
constexpr std::uintmax_t kMaxDeflateRatio = 1032;              // deflate's largest expansion

std::string image_size_problem(const OIIO::ImageSpec& spec, const std::string& format, const char* path) {
  const std::size_t pixels = std::size_t(spec.width) * std::size_t(spec.height);
  if (pixels > kMaxImagePixels)
    return fmt::format("the header claims {}x{} pixels, more than the {} a texture may have", spec.width, spec.height,
                       kMaxImagePixels);
  // OpenEXR: zip/zips/pxr24 (deflate after at most 4:3), piz, rle, b44 stay within twice
  // deflate's ratio; DWAA/DWAB (DCT then deflate) have no such bound and are not checked.
  std::uintmax_t ratio = 0;
  if (format == "png" || format == "hdr") ratio = kMaxDeflateRatio;
  if (format == "openexr" && lower(spec.get_string_attribute("compression")).rfind("dwa", 0) != 0)
    ratio = 2 * kMaxDeflateRatio;
  if (ratio == 0) return "";
  std::error_code ec;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  const std::uintmax_t pixel_bytes = std::uintmax_t(pixels) * std::uintmax_t(spec.pixel_bytes());
  if (!ec && pixel_bytes / ratio > file_bytes)
    return fmt::format(
        "the header claims {}x{} pixels ({} bytes) but the file holds only {} bytes: a corrupt "
        "or truncated file",
        spec.width, spec.height, pixel_bytes, file_bytes);
  return "";
}

}  // namespace

extern "C" void dermis_plugin_read_image(const char* path, DecodedImage* out, std::string* error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    *error = OIIO::geterror();
    if (error->empty()) *error = "unknown error";
    return;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    *error = fmt::format("empty image ({}x{}, {} channels)", spec.width, spec.height, spec.nchannels);
    return;
  }
  if (*error = image_size_problem(spec, in->format_name(), path); !error->empty()) return;
  // Only the channels used are read (a header may claim thousands).
  out->width = spec.width;
  out->height = spec.height;
  out->channels = std::min(spec.nchannels, 3);
  out->data.assign(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(out->channels), 0.0f);
  if (!in->read_image(0, 0, 0, out->channels, OIIO::TypeDesc::FLOAT, out->data.data())) {
    *error = in->geterror();
    if (error->empty()) *error = "read failed";
    return;
  }
  out->encoding = file_encoding(spec, &out->gamma);
  in->close();
}

extern "C" void dermis_plugin_write_image(const char* path, const char* format, int width, int height, const float* rgb,
                                          std::string* error) {
  const bool eight_bit = format == std::string("jpeg");
  OIIO::ImageSpec spec(width, height, 3, eight_bit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  if (eight_bit) spec.attribute("Compression", "jpeg:95");
  spec.attribute("oiio:ColorSpace", eight_bit ? "sRGB" : "Linear");
  auto out = OIIO::ImageOutput::create(format);
  if (!out) {
    *error = fmt::format("OpenImageIO has no '{}' writer: {}", format, OIIO::geterror());
    return;
  }
  if (!out->open(path, spec)) {
    *error = out->geterror();
    return;
  }
  if (!out->write_image(OIIO::TypeDesc::FLOAT, rgb)) {
    *error = out->geterror();
    out->close();
    return;
  }
  if (!out->close()) *error = out->geterror();
}
