// read_image on files whose headers lie about their size: refused with a message before
// the pixels are allocated.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include "dermis/render/image.h"

namespace dermis {
namespace {

std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// A PNG whose IHDR (with a correct CRC) claims width x height, followed by a few bytes of
// pixel data and IEND.
std::string png_header_only(uint32_t width, uint32_t height) {
  std::string ihdr = "IHDR" + be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  auto chunk = [](const std::string& type_and_data) {
    uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(type_and_data.data()), uInt(type_and_data.size())));
    return be32(uint32_t(type_and_data.size() - 4)) + type_and_data + be32(crc);
  };
  const std::string pixels(16, '\0');
  std::string idat(compressBound(uLong(pixels.size())), '\0');
  uLongf size = uLongf(idat.size());
  compress(reinterpret_cast<Bytef*>(idat.data()), &size, reinterpret_cast<const Bytef*>(pixels.data()), uLong(pixels.size()));
  idat.resize(size);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk(ihdr) + chunk("IDAT" + idat) + chunk("IEND");
}

std::string read_error(const std::string& name, const std::string& bytes) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("dermis_image_limits_" + std::to_string(::getpid()) + name)).string();
  std::ofstream(path, std::ios::binary) << bytes;
  std::string err;
  try {
    read_image(path);
  } catch (const std::runtime_error& e) {
    err = e.what();
  }
  std::filesystem::remove(path);
  return err;
}

TEST(ReadImageLimits, PngHeaderClaimingMoreThanTheFileHoldsIsRefused) {
  // 10000 x 10000 RGB8 is 300 MB of pixels; deflate cannot make that out of 80 bytes.
  const std::string err = read_error("lying.png", png_header_only(10000, 10000));
  EXPECT_NE(err.find("could not read image"), std::string::npos) << err;
  EXPECT_NE(err.find("but the file holds only"), std::string::npos) << err;
}

TEST(ReadImageLimits, PixelCountBeyondTheTextureLimitIsRefused) {
  const std::string err = read_error("huge.png", png_header_only(65535, 65535));
  EXPECT_NE(err.find("more than the 134217728 a texture may have"), std::string::npos) << err;
}

TEST(ReadImageLimits, EmptyAndGarbageFilesAreErrors) {
  EXPECT_NE(read_error("empty.png", "").find("could not read image"), std::string::npos);
  EXPECT_NE(read_error("garbage.exr", std::string(100, '\x7f')).find("could not read image"), std::string::npos);
}

}  // namespace
}  // namespace dermis
