#include "dermis/render/image.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "dermis/core/rng.h"

namespace dermis {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory for one test, removed afterwards.
class ImageFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("dermis_image_test_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  int files_in_dir() const {
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  fs::path dir_;
};

// Random linear values over several decades, including 0 and values above 1.
Image random_image(int w, int h, uint64_t seed) {
  Image img(w, h);
  Rng rng(seed, 0);
  for (float& v : img.pixels) v = rng.uniform() < 0.05f ? 0.0f : std::exp(8 * rng.uniform() - 6);
  return img;
}

void expect_message_contains(const std::exception& e, const std::string& what) {
  EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << "message: " << e.what();
}

TEST(Srgb, CurveRoundTripsAndMatchesReferencePoints) {
  // IEC 61966-2-1: the linear segment meets the power segment at 0.04045 / 0.0031308.
  EXPECT_NEAR(srgb_to_linear(0.04045f), 0.0031308f, 1e-6);
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.214041f, 1e-5);  // ((0.5 + 0.055) / 1.055)^2.4
  EXPECT_FLOAT_EQ(srgb_to_linear(1.0f), 1.0f);
  for (int i = 0; i <= 100; ++i) {
    float v = i / 100.0f;
    EXPECT_NEAR(linear_to_srgb(srgb_to_linear(v)), v, 1e-6);
  }
}

TEST_F(ImageFileTest, ExrRoundTripIsBitExact) {
  Image img = random_image(37, 23, 1);
  img.set(0, 0, RGB(-0.25f, 1e-30f, 65504.0f * 100));  // negative, denormal-ish, beyond half range
  write_image(file("a.exr"), img);
  Image back = read_image(file("a.exr"));
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  ASSERT_EQ(back.pixels.size(), img.pixels.size());
  for (std::size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(back.pixels[i], img.pixels[i]) << "float " << i;
  EXPECT_EQ(files_in_dir(), 1);  // no temporary left behind
}

TEST_F(ImageFileTest, PixelOrderIsRowMajorTopFirst) {
  Image img(3, 2);
  img.set(2, 0, RGB(1, 0, 0));
  img.set(0, 1, RGB(0, 0, 1));
  write_image(file("order.exr"), img);
  Image back = read_image(file("order.exr"));
  EXPECT_EQ(back.at(2, 0), RGB(1, 0, 0));
  EXPECT_EQ(back.at(0, 1), RGB(0, 0, 1));
  EXPECT_EQ(back.pixels[3 * 2 + 0], 1.0f);
}

TEST_F(ImageFileTest, PngRoundTripWithinEightBitQuantisation) {
  Image img(64, 16);
  Rng rng(2, 0);
  for (float& v : img.pixels) v = rng.uniform();
  img.set(0, 0, RGB(2.0f, -1.0f, 0.5f));  // clamped to [0, 1] on write
  write_image(file("a.png"), img);
  Image back = read_image(file("a.png"));
  ASSERT_EQ(back.width, 64);
  ASSERT_EQ(back.height, 16);
  EXPECT_EQ(back.at(0, 0)[0], 1.0f);
  EXPECT_EQ(back.at(0, 0)[1], 0.0f);
  for (std::size_t i = 3; i < img.pixels.size(); ++i) {
    // Encoded values are rounded to k/255: half a code step in sRGB space, i.e.
    // 0.5/255 times the slope of the decoding curve at that value.
    float encoded = linear_to_srgb(img.pixels[i]);
    float slope =
        (srgb_to_linear(std::min(1.0f, encoded + 0.5f / 255)) - srgb_to_linear(std::max(0.0f, encoded - 0.5f / 255)));
    ASSERT_NEAR(back.pixels[i], img.pixels[i], slope * 1.001f + 1e-7f) << "float " << i;
  }
  // The sRGB curve, not a plain copy: linear srgb_to_linear(128.2/255) encodes to code 128.
  Image mid(1, 1, RGB(srgb_to_linear(128.2f / 255)));
  write_image(file("mid.png"), mid);
  EXPECT_NEAR(read_image(file("mid.png")).at(0, 0)[0], srgb_to_linear(128 / 255.0f), 1e-6);
}

TEST_F(ImageFileTest, JpegHdrAndTiffAreWrittenAndReadBack) {
  Image img(8, 8, RGB(0.2f, 0.4f, 0.6f));
  write_image(file("a.jpg"), img);
  write_image(file("a.hdr"), img);
  write_image(file("a.tif"), img);
  for (const char* name : {"a.jpg", "a.hdr", "a.tif"}) {
    Image back = read_image(file(name));
    ASSERT_EQ(back.width, 8) << name;
    // JPEG: 8-bit plus compression; HDR: RGBE keeps ~8 bits of mantissa (1/256 relative).
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.at(4, 4)[c], img.at(4, 4)[c], 0.02) << name;
  }
  Image tif = read_image(file("a.tif"));
  EXPECT_EQ(tif.at(3, 3), img.at(3, 3));  // float TIFF is exact
}

// Writes a file with `channels` channels directly through OpenImageIO.
void write_raw(const std::string& path, int w, int h, int channels, OIIO::TypeDesc type,
               const std::vector<float>& values) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(w, h, channels, type);
  ASSERT_TRUE(out->open(path, spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

TEST_F(ImageFileTest, GrayAndAlphaInputsBecomeRgb) {
  write_raw(file("gray.exr"), 2, 1, 1, OIIO::TypeDesc::FLOAT, {0.25f, 3.0f});
  write_raw(file("graya.exr"), 2, 1, 2, OIIO::TypeDesc::FLOAT, {0.25f, 0.1f, 3.0f, 0.9f});
  write_raw(file("rgba.exr"), 2, 1, 4, OIIO::TypeDesc::FLOAT, {0.1f, 0.2f, 0.3f, 0.5f, 1.0f, 2.0f, 3.0f, 0.0f});
  Image gray = read_image(file("gray.exr"));
  EXPECT_EQ(gray.at(0, 0), RGB(0.25f));
  EXPECT_EQ(gray.at(1, 0), RGB(3.0f));
  Image graya = read_image(file("graya.exr"));
  EXPECT_EQ(graya.at(0, 0), RGB(0.25f));
  EXPECT_EQ(graya.at(1, 0), RGB(3.0f));
  Image rgba = read_image(file("rgba.exr"));
  EXPECT_EQ(rgba.at(0, 0), RGB(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(rgba.at(1, 0), RGB(1.0f, 2.0f, 3.0f));
  // An 8-bit gray PNG is sRGB-encoded: code 128 decodes to srgb_to_linear(128/255).
  write_raw(file("gray8.png"), 1, 1, 1, OIIO::TypeDesc::UINT8, {128 / 255.0f});
  EXPECT_NEAR(read_image(file("gray8.png")).at(0, 0)[1], srgb_to_linear(128 / 255.0f), 1e-6);
}

TEST_F(ImageFileTest, UnknownExtensionThrowsAndWritesNothing) {
  Image img(2, 2);
  try {
    write_image(file("a.bmpx"), img);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    expect_message_contains(e, "a.bmpx");
    expect_message_contains(e, ".exr");
    expect_message_contains(e, ".png");
  }
  EXPECT_THROW(write_image(file("noextension"), img), std::runtime_error);
  EXPECT_EQ(files_in_dir(), 0);
}

TEST_F(ImageFileTest, MissingDirectoryThrowsWithPathAndLeavesNothing) {
  Image img(2, 2);
  const std::string path = file("no_such_dir/out.exr");
  try {
    write_image(path, img);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    expect_message_contains(e, path);
  }
  EXPECT_EQ(files_in_dir(), 0);
}

TEST_F(ImageFileTest, ReadOnlyDirectoryThrowsAndLeavesNothing) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  fs::create_directories(dir_ / "ro");
  fs::permissions(dir_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  Image img(2, 2);
  for (const char* name : {"ro/out.exr", "ro/out.png"})
    EXPECT_THROW(write_image(file(name), img), std::runtime_error) << name;
  fs::permissions(dir_ / "ro", fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(dir_ / "ro"));
}

TEST_F(ImageFileTest, ParentThatIsAFileThrowsAndLeavesNothingElse) {
  std::FILE* f = std::fopen(file("plain").c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  Image img(2, 2);
  for (const char* name : {"plain/out.exr", "plain/out.png"})
    EXPECT_THROW(write_image(file(name), img), std::runtime_error) << name;
  EXPECT_EQ(files_in_dir(), 1);
}

TEST_F(ImageFileTest, FailedWriteKeepsThePreviousFile) {
  Image good(2, 2, RGB(0.5f));
  write_image(file("keep.exr"), good);
  Image bad(2, 2, RGB(1.0f));
  bad.set(1, 1, RGB(0, std::numeric_limits<float>::quiet_NaN(), 0));
  try {
    write_image(file("keep.exr"), bad);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    expect_message_contains(e, "pixel (1, 1)");
  }
  bad.set(1, 1, RGB(std::numeric_limits<float>::infinity()));
  EXPECT_THROW(write_image(file("keep.exr"), bad), std::runtime_error);
  EXPECT_EQ(read_image(file("keep.exr")).at(1, 1), RGB(0.5f));
  EXPECT_EQ(files_in_dir(), 1);
}

TEST_F(ImageFileTest, ReadOfMissingFileNamesThePath) {
  const std::string path = file("missing.exr");
  try {
    read_image(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    expect_message_contains(e, path + ": could not read image: ");
  }
}

TEST_F(ImageFileTest, ReadOfGarbageThrows) {
  {
    std::FILE* f = std::fopen(file("garbage.exr").c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fputs("this is not an image", f);
    std::fclose(f);
  }
  EXPECT_THROW(read_image(file("garbage.exr")), std::runtime_error);
}

}  // namespace
}  // namespace dermis
