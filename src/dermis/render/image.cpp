#include "dermis/render/image.h"

#include "dermis/render/exr_header_check.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace dermis {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// How the values of a file's channels relate to linear radiance.
enum class Encoding { kLinear, kSrgb, kGamma };

Encoding file_encoding(const OIIO::ImageSpec& spec, float* gamma) {
  const std::string cs = lower(spec.get_string_attribute("oiio:ColorSpace"));
  if (cs.find("srgb") != std::string::npos) return Encoding::kSrgb;
  if (cs.find("linear") != std::string::npos || cs == "scene_linear") return Encoding::kLinear;
  if (cs.rfind("gamma", 0) == 0) {
    // OIIO names a PNG gAMA chunk "GammaCorrected" with the exponent in oiio:Gamma
    // (or spells it "GammaX.Y").
    *gamma = spec.get_float_attribute("oiio:Gamma", 0.0f);
    if (*gamma <= 0) *gamma = std::strtof(cs.c_str() + 5, nullptr);
    if (*gamma > 0) return Encoding::kGamma;
  }
  // Untagged: integer data (PNG, JPEG, 8/16-bit TIFF) is display-encoded by
  // convention; floating-point data is linear.
  const auto base = spec.format.basetype;
  const bool integer = base == OIIO::TypeDesc::UINT8 || base == OIIO::TypeDesc::UINT16 ||
                       base == OIIO::TypeDesc::INT8 || base == OIIO::TypeDesc::INT16;
  return integer ? Encoding::kSrgb : Encoding::kLinear;
}

// The OIIO format name for a file extension, and the pixel type written there.
struct OutputFormat {
  const char* oiio_name;
  OIIO::TypeDesc type;
  bool srgb_8bit;
};

const char* kSupportedExtensions = ".exr, .hdr, .tif, .tiff, .png, .jpg, .jpeg";

OutputFormat output_format(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".exr") return {"openexr", OIIO::TypeDesc::FLOAT, false};
  if (ext == ".hdr") return {"hdr", OIIO::TypeDesc::FLOAT, false};
  if (ext == ".tif" || ext == ".tiff") return {"tiff", OIIO::TypeDesc::FLOAT, false};
  if (ext == ".png") return {"png", OIIO::TypeDesc::UINT8, true};
  if (ext == ".jpg" || ext == ".jpeg") return {"jpeg", OIIO::TypeDesc::UINT8, true};
  throw std::runtime_error(fmt::format("{}: cannot write image: unknown extension '{}' (supported: {})", path,
                                       ext, kSupportedExtensions));
}

// What a header may claim before its pixels are read: at most kMaxImagePixels pixels, and,
// for formats whose compression ratio is bounded (PNG's deflate, HDR's run lengths, most
// OpenEXR compressions), no more bytes of pixels than the file could inflate to. A lying header is refused here
// rather than allocated (a 100-byte PNG claiming 65535 x 65535 used to take 1.8 GB).
constexpr std::size_t kMaxImagePixels = std::size_t(1) << 27;  // 16384 x 8192
constexpr std::uintmax_t kMaxDeflateRatio = 1032;              // deflate's largest expansion

template <class Fail>
void check_image_size(const OIIO::ImageSpec& spec, const std::string& format, const std::string& path, Fail fail) {
  const std::size_t pixels = std::size_t(spec.width) * std::size_t(spec.height);
  if (pixels > kMaxImagePixels)
    throw fail(fmt::format("the header claims {}x{} pixels, more than the {} a texture may have", spec.width,
                           spec.height, kMaxImagePixels));
  // OpenEXR: zip/zips/pxr24 (deflate after at most 4:3), piz, rle, b44 stay within twice
  // deflate's ratio; DWAA/DWAB (DCT then deflate) have no such bound and are not checked.
  std::uintmax_t ratio = 0;
  if (format == "png" || format == "hdr") ratio = kMaxDeflateRatio;
  if (format == "openexr" && lower(spec.get_string_attribute("compression")).rfind("dwa", 0) != 0)
    ratio = 2 * kMaxDeflateRatio;
  if (ratio == 0) return;
  std::error_code ec;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  const std::uintmax_t pixel_bytes = std::uintmax_t(pixels) * std::uintmax_t(spec.pixel_bytes());
  if (!ec && pixel_bytes / ratio > file_bytes)
    throw fail(fmt::format("the header claims {}x{} pixels ({} bytes) but the file holds only {} bytes: a corrupt "
                           "or truncated file",
                           spec.width, spec.height, pixel_bytes, file_bytes));
}

}  // namespace

Image::Image(int w, int h, RGB fill) : width(w), height(h) {
  if (w < 0 || h < 0) throw std::invalid_argument(fmt::format("Image: negative size {}x{}", w, h));
  pixels.resize(3 * pixel_count());
  for (std::size_t i = 0; i < pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) pixels[3 * i + c] = fill[c];
}

// IEC 61966-2-1:1999, section 5.2 (decoding) and 5.3 (encoding).
float srgb_to_linear(float v) {
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}
float linear_to_srgb(float v) {
  if (v <= 0.0031308f) return 12.92f * v;
  return 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

Image read_image(const std::string& path) {
  auto fail = [&](const std::string& why) {
    return std::runtime_error(fmt::format("{}: could not read image: {}", path, why));
  };
  // OpenEXR allocates what a header's attributes claim before reading them.
  if (const std::string problem = exr_header_problem(path); !problem.empty()) throw fail(problem);
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::string why = OIIO::geterror();
    throw fail(why.empty() ? "unknown error" : why);
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw fail(fmt::format("empty image ({}x{}, {} channels)", spec.width, spec.height, spec.nchannels));
  check_image_size(spec, in->format_name(), path, fail);
  // Only the channels used are read (a header may claim thousands).
  const int nc = std::min(spec.nchannels, 3);
  std::vector<float> raw(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data())) {
    std::string why = in->geterror();
    throw fail(why.empty() ? "read failed" : why);
  }
  float gamma = 1;
  const Encoding encoding = file_encoding(spec, &gamma);
  in->close();

  Image img(spec.width, spec.height);
  // Gray and gray+alpha replicate channel 0; RGB and RGBA (and more) take the first three.
  const bool gray = nc < 3;
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) {
      float v = raw[i * std::size_t(nc) + std::size_t(gray ? 0 : c)];
      if (encoding == Encoding::kSrgb) v = srgb_to_linear(v);
      else if (encoding == Encoding::kGamma) v = std::pow(std::max(v, 0.0f), gamma);
      img.pixels[3 * i + std::size_t(c)] = v;
    }
  }
  return img;
}

void write_image(const std::string& path, const Image& img) {
  const OutputFormat format = output_format(path);
  if (img.width <= 0 || img.height <= 0 || img.pixels.size() != 3 * img.pixel_count())
    throw std::runtime_error(fmt::format("{}: cannot write image: invalid image ({}x{} with {} floats)", path,
                                         img.width, img.height, img.pixels.size()));
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    if (!std::isfinite(img.pixels[i])) {
      const std::size_t p = i / 3;
      throw std::runtime_error(fmt::format("{}: cannot write image: pixel ({}, {}) channel {} is {}", path,
                                           p % std::size_t(img.width), p / std::size_t(img.width), i % 3,
                                           img.pixels[i]));
    }
  }

  std::vector<float> data = img.pixels;
  if (format.srgb_8bit)
    for (float& v : data) v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));  // OIIO rounds to 8 bits

  OIIO::ImageSpec spec(img.width, img.height, 3, format.type);
  if (format.oiio_name == std::string("openexr")) spec.attribute("compression", "zip");
  if (format.oiio_name == std::string("jpeg")) spec.attribute("Compression", "jpeg:95");
  spec.attribute("oiio:ColorSpace", format.srgb_8bit ? "sRGB" : "Linear");

  const std::string tmp = fmt::format("{}.tmp-{}", path, static_cast<long>(::getpid()));
  auto fail = [&](const std::string& why) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    return std::runtime_error(fmt::format("{}: could not write image: {}", path, why));
  };
  auto out = OIIO::ImageOutput::create(format.oiio_name);
  if (!out) throw fail(fmt::format("OpenImageIO has no '{}' writer: {}", format.oiio_name, OIIO::geterror()));
  if (!out->open(tmp, spec)) throw fail(out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, data.data())) {
    std::string why = out->geterror();
    out->close();
    throw fail(why);
  }
  if (!out->close()) throw fail(out->geterror());
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw fail(fmt::format("rename from {} failed: {}", tmp, ec.message()));
}

}  // namespace dermis
