// read_image on files whose headers lie about their size: refused with a message before
// the pixels are allocated.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "dermis/render/exr_header_check.h"
#include "dermis/render/image.h"

namespace dermis {
namespace {

std::string be32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

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
  compress(reinterpret_cast<Bytef*>(idat.data()), &size, reinterpret_cast<const Bytef*>(pixels.data()),
           uLong(pixels.size()));
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

std::string le32(uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

// An OpenEXR header: magic, version 2 with `flags`, one string attribute whose size field
// claims `claimed` bytes, followed by `held` bytes.
std::string exr_with_attribute(uint32_t flags, uint32_t claimed, std::size_t held) {
  return std::string("\x76\x2f\x31\x01", 4) + le32(2 | flags) + std::string("comments\0string\0", 16) + le32(claimed) +
         std::string(held, 'x');
}

// OpenEXR 3.1 allocates an attribute's claimed size before reading it (fuzz_image_texture
// found a 708-byte file taking 1.9 GB: fuzz/regressions/image_texture/). Refused first.
TEST(ReadImageLimits, ExrAttributeClaimingMoreThanTheFileHoldsIsRefused) {
  std::string err = read_error("lying.exr", exr_with_attribute(0, 1800000000u, 40));
  EXPECT_NE(err.find("could not read image: attribute \"comments\" (string) claims 1800000000 bytes but the file "
                     "holds only 40 more"),
            std::string::npos)
      << err;
  err = read_error("negative.exr", exr_with_attribute(0, 0x80000000u, 40));
  EXPECT_NE(err.find("claims a negative size"), std::string::npos) << err;
  // The same lie in a file named .png: the magic, not the name, decides.
  err = read_error("lying-exr.png", exr_with_attribute(0, 1800000000u, 40));
  EXPECT_NE(err.find("claims 1800000000 bytes"), std::string::npos) << err;
}

// What the guard lets through: every header Dermis writes, single-part; a size that fits;
// files of other formats; and a multi-part file is read header by header.
TEST(ReadImageLimits, ExrGuardPassesWhatFits) {
  const std::string dir =
      std::filesystem::temp_directory_path().string() + "/dermis_exr_guard_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  write_image(dir + "/a.exr", Image(5, 3, RGB(0.25f)));
  EXPECT_EQ(exr_header_problem(dir + "/a.exr"), "");
  EXPECT_EQ(read_image(dir + "/a.exr").width, 5);
  std::ofstream(dir + "/fits.exr", std::ios::binary) << exr_with_attribute(0, 40, 40) + std::string(1, '\0');
  EXPECT_EQ(exr_header_problem(dir + "/fits.exr"), "");
  std::ofstream(dir + "/b.png", std::ios::binary) << png_header_only(4, 4);
  EXPECT_EQ(exr_header_problem(dir + "/b.png"), "");
  // Multi-part: the first header fits, the second lies.
  std::ofstream(dir + "/multi.exr", std::ios::binary) << exr_with_attribute(0x1000, 4, 4) + std::string(1, '\0') +
                                                             std::string("comments\0string\0", 16) + le32(1000) +
                                                             std::string(8, 'y');
  EXPECT_NE(exr_header_problem(dir + "/multi.exr").find("claims 1000 bytes but the file holds only 8 more"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dermis
