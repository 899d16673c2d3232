#include "dermis/render/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <fmt/format.h>
#include <png.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "dermis/render/exr_header_check.h"
#include "dermis/render/image_plugin.h"

namespace dermis {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// How a file extension is written: OpenEXR and PNG (what a render writes) here, with
// Debian's OpenEXR and libpng; the others by the OpenImageIO plugin (image_plugin.h).
enum class Writer { kExr, kPng, kPlugin };
struct OutputFormat {
  Writer writer;
  const char* plugin_format;  // kPlugin: OpenImageIO's format name
  bool srgb_8bit;
};

const char* kSupportedExtensions = ".exr, .hdr, .tif, .tiff, .png, .jpg, .jpeg";

OutputFormat output_format(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".exr") return {Writer::kExr, nullptr, false};
  if (ext == ".png") return {Writer::kPng, nullptr, true};
  if (ext == ".hdr") return {Writer::kPlugin, "hdr", false};
  if (ext == ".tif" || ext == ".tiff") return {Writer::kPlugin, "tiff", false};
  if (ext == ".jpg" || ext == ".jpeg") return {Writer::kPlugin, "jpeg", true};
  throw std::runtime_error(
      fmt::format("{}: cannot write image: unknown extension '{}' (supported: {})", path, ext, kSupportedExtensions));
}

// 32-bit float R, G, B and the extra channels, zip-compressed, tagged linear (as
// OpenImageIO wrote it before).
void write_exr(const std::string& path, const Image& img) {
  Imf::Header header(img.width, img.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.insert("oiio:ColorSpace", Imf::StringAttribute("Linear"));
  Imf::FrameBuffer fb;
  const std::size_t xs = 3 * sizeof(float), ys = xs * std::size_t(img.width);
  char* base = reinterpret_cast<char*>(const_cast<float*>(img.pixels.data()));
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
  }
  for (const Image::Channel& extra : img.extra_channels) {
    if (extra.values.size() != img.pixel_count())
      throw std::invalid_argument(
          fmt::format("channel '{}' has {} values for {} pixels", extra.name, extra.values.size(), img.pixel_count()));
    header.channels().insert(extra.name, Imf::Channel(Imf::FLOAT));
    char* values = reinterpret_cast<char*>(const_cast<float*>(extra.values.data()));
    fb.insert(extra.name, Imf::Slice(Imf::FLOAT, values, sizeof(float), sizeof(float) * std::size_t(img.width)));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(img.height);
}

// libpng's part of write_png and encode_png: false when libpng failed (its errors longjmp
// back here, so this frame holds no C++ object: setjmp's rule). Written to the file `f`,
// else through `write` (with `sink` as libpng's io pointer); the rows from 8-bit `bytes`,
// else from sRGB-encoded `floats` in [0, 1], rounded (through `row`). zlib_level < 0: zlib's default.
bool png_write_rgb8(png_structp png, png_infop info, std::FILE* f, png_rw_ptr write, void* sink, int width, int height,
                    const float* floats, const png_byte* bytes, png_byte* row, int zlib_level) {
  if (setjmp(png_jmpbuf(png))) return false;
  if (f)
    png_init_io(png, f);
  else
    png_set_write_fn(png, sink, write, nullptr);
  if (zlib_level >= 0) {  // speed over size: one cheap filter, Huffman codes without matching
    png_set_compression_level(png, zlib_level);
    png_set_compression_strategy(png, Z_HUFFMAN_ONLY);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  }
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  const std::size_t n = 3 * std::size_t(width);
  for (int y = 0; y < height; ++y) {
    if (bytes) {
      png_write_row(png, bytes + n * std::size_t(y));
      continue;
    }
    const float* src = floats + n * std::size_t(y);
    for (std::size_t i = 0; i < n; ++i) row[i] = png_byte(std::lround(src[i] * 255.0f));
    png_write_row(png, row);
  }
  png_write_end(png, nullptr);
  return true;
}

// 8-bit RGB from sRGB-encoded values in [0, 1] (`data`), rounded, with an sRGB chunk.
void write_png(const std::string& path, int width, int height, const std::vector<float>& data) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw std::runtime_error(std::strerror(errno));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  std::vector<png_byte> row(3 * std::size_t(width));
  const bool ok =
      info && png_write_rgb8(png, info, f.get(), nullptr, nullptr, width, height, data.data(), nullptr, row.data(), -1);
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!ok) throw std::runtime_error("libpng failed to write it");
  if (std::fclose(f.release()) != 0) throw std::runtime_error(std::strerror(errno));  // a full disk shows here
}

void append_png_bytes(png_structp png, png_bytep bytes, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(bytes), n);
}

}  // namespace

std::string encode_png(int width, int height, const std::vector<uint8_t>& rgb8, int zlib_level) {
  if (width <= 0 || height <= 0 || rgb8.size() != 3 * std::size_t(width) * std::size_t(height))
    throw std::invalid_argument(fmt::format("encode_png: {} values for {}x{} RGB pixels", rgb8.size(), width, height));
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = info && png_write_rgb8(png, info, nullptr, append_png_bytes, &out, width, height, nullptr,
                                         rgb8.data(), nullptr, zlib_level);
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!ok) throw std::runtime_error("encode_png: libpng failed");
  return out;
}

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
  DecodedImage raw;
  std::string why;
  image_plugin().read(path.c_str(), &raw, &why);
  if (!why.empty()) throw fail(why);

  Image img(raw.width, raw.height);
  const std::size_t nc = std::size_t(raw.channels);
  // Gray and gray+alpha replicate channel 0; RGB and RGBA (and more) take the first three.
  const bool gray = nc < 3;
  for (std::size_t i = 0; i < img.pixel_count(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      float v = raw.data[i * nc + (gray ? 0 : c)];
      if (raw.encoding == DecodedImage::Encoding::kSrgb)
        v = srgb_to_linear(v);
      else if (raw.encoding == DecodedImage::Encoding::kGamma)
        v = std::pow(std::max(v, 0.0f), raw.gamma);
      img.pixels[3 * i + c] = v;
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

  std::vector<float> data;
  if (format.srgb_8bit) {
    data = img.pixels;
    for (float& v : data) v = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));  // rounded to 8 bits by the writer
  }

  const std::string tmp = fmt::format("{}.tmp-{}", path, static_cast<long>(::getpid()));
  auto fail = [&](const std::string& why) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    return std::runtime_error(fmt::format("{}: could not write image: {}", path, why));
  };
  try {
    if (format.writer == Writer::kExr) {
      write_exr(tmp, img);
    } else if (format.writer == Writer::kPng) {
      write_png(tmp, img.width, img.height, data);
    } else {
      std::string why;
      image_plugin().write(tmp.c_str(), format.plugin_format, img.width, img.height,
                           format.srgb_8bit ? data.data() : img.pixels.data(), &why);
      if (!why.empty()) throw std::runtime_error(why);
    }
  } catch (const std::exception& e) {
    throw fail(e.what());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw fail(fmt::format("rename from {} failed: {}", tmp, ec.message()));
}

}  // namespace dermis
