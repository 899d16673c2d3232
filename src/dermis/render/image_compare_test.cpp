#include "dermis/render/image_compare.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "dermis/core/rng.h"

namespace dermis {
namespace {

namespace fs = std::filesystem;

Image random_image(int w, int h, uint64_t seed) {
  Image img(w, h);
  Rng rng(seed, 0);
  for (float& v : img.pixels) v = rng.uniform();
  return img;
}

TEST(CompareImages, ConstantOffsetGivesThatOffsetExactly) {
  // Dyadic values: a - b is exactly 0.25 in float, so the statistics are exact.
  Image b(16, 8, RGB(1.0f));
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x) b.set(x, y, RGB(1.0f + x / 8.0f, 2.0f, 0.5f));
  Image a = b;
  for (float& v : a.pixels) v += 0.25f;
  ImageComparison r = compare_images(a, b);
  EXPECT_EQ(r.width, 16);
  EXPECT_EQ(r.height, 8);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(r.rmse[c], 0.25f);
    EXPECT_EQ(r.max_abs_diff[c], 0.25f);
    EXPECT_EQ(r.mean_a[c] - r.mean_b[c], 0.25f);
  }
  EXPECT_EQ(r.rmse_all, 0.25);
  EXPECT_EQ(r.max_abs_diff_all, 0.25);
  // Mean of 1 + x/8 over x = 0..15 is 1 + 7.5/8.
  EXPECT_EQ(r.mean_b[0], 1.0f + 7.5f / 8);
  EXPECT_EQ(r.mean_b[1], 2.0f);
  // relMSE in G: every pixel 0.0625 / (4 + eps); in B: 0.0625 / (0.25 + eps).
  EXPECT_NEAR(r.relative_mse[1], 0.0625 / (4 + kRelativeMseEpsilon), 1e-7);
  EXPECT_NEAR(r.relative_mse[2], 0.0625 / (0.25 + kRelativeMseEpsilon), 1e-7);
}

TEST(CompareImages, IdenticalImagesHaveZeroError) {
  Image a = random_image(9, 7, 3);
  ImageComparison r = compare_images(a, a);
  EXPECT_EQ(r.rmse_all, 0);
  EXPECT_EQ(r.relative_mse_all, 0);
  EXPECT_EQ(r.max_abs_diff_all, 0);
  EXPECT_EQ(r.mean_a, r.mean_b);
}

TEST(CompareImages, ErrorInOneChannelOfHalfThePixels) {
  Image b = random_image(10, 10, 4);
  Image a = b;
  for (int y = 0; y < 10; y += 2)  // half the rows
    for (int x = 0; x < 10; ++x) a.set(x, y, b.at(x, y) + RGB(0, 0.5f, 0));
  ImageComparison r = compare_images(a, b);
  // RMSE_G = sqrt(0.5 * 0.25); all channels: sqrt(0.5 * 0.25 / 3). float addition
  // a = b + 0.5 rounds to within 2^-24 relative of 0.5.
  EXPECT_EQ(r.rmse[0], 0.0f);
  EXPECT_EQ(r.rmse[2], 0.0f);
  EXPECT_NEAR(r.rmse[1], std::sqrt(0.125), 1e-6);
  EXPECT_NEAR(r.rmse_all, std::sqrt(0.125 / 3), 1e-6);
  EXPECT_NEAR(r.max_abs_diff[1], 0.5, 1e-6);
}

TEST(CompareImages, RelativeMseEpsilonRegularizesBlackReference) {
  Image b(4, 4, RGB(0.0f));
  Image a(4, 4, RGB(0.1f));
  // (0.1)^2 / (0 + 0.01) = 1.
  EXPECT_NEAR(compare_images(a, b).relative_mse_all, 1.0, 1e-6);
  // Not symmetric: B is the reference.
  EXPECT_NEAR(compare_images(b, a).relative_mse_all, 0.01 / (0.01 + 0.01), 1e-6);
}

TEST(CompareImages, DifferentSizesThrowNamingBothSizes) {
  try {
    compare_images(Image(4, 3), Image(3, 4));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("4x3 versus 3x4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(difference_image(Image(4, 3), Image(4, 4)), std::invalid_argument);
}

TEST(FalseColour, LuminanceRisesMonotonicallyAndEndsAreClamped) {
  float previous = -1;
  for (int i = 0; i <= 200; ++i) {
    float lum = false_colour(i / 200.0f).luminance();
    EXPECT_GT(lum, previous) << "t = " << i / 200.0f;
    previous = lum;
  }
  EXPECT_EQ(false_colour(-3.0f), false_colour(0.0f));
  EXPECT_EQ(false_colour(7.0f), false_colour(1.0f));
  EXPECT_EQ(false_colour(std::nanf("")), false_colour(0.0f));
  EXPECT_LT(false_colour(0).max(), 0.01f);       // near black
  EXPECT_GT(false_colour(1).luminance(), 0.8f);  // near white
}

TEST(DifferenceImage, ScalesToThe99thPercentile) {
  // 200 pixels with gray differences 1, 2, ..., 200: the nearest-rank 99th percentile
  // is the 198th value.
  Image b(200, 1, RGB(0.0f)), a(200, 1);
  for (int x = 0; x < 200; ++x) a.set(x, 0, RGB(float(x + 1)));
  EXPECT_NEAR(difference_quantile(a, b, 0.99), 198.0, 1e-4);
  EXPECT_NEAR(difference_quantile(a, b, 1.0), 200.0, 1e-4);
  EXPECT_NEAR(difference_quantile(a, b, 0.0), 1.0, 1e-4);
  double scale = 0;
  Image d = difference_image(a, b, &scale);
  EXPECT_NEAR(scale, 198.0, 1e-4);
  EXPECT_EQ(d.at(197, 0), false_colour(1.0f));                      // at the percentile
  EXPECT_EQ(d.at(199, 0), false_colour(1.0f));                      // above it, clamped
  RGB half = d.at(98, 0), expected = false_colour(99.0f / 198.0f);  // luminance of gray = value
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(half[c], expected[c], 1e-5);
}

TEST(DifferenceImage, SparseDifferencesFallBackToTheMaximum) {
  // One differing pixel in 1000: the 99th percentile is zero, so the maximum scales.
  Image b(100, 10, RGB(0.5f)), a = b;
  a.set(3, 4, RGB(1.5f, 0.5f, 0.5f));
  double scale = 0;
  Image d = difference_image(a, b, &scale);
  EXPECT_NEAR(scale, 0.2126, 1e-5);  // Rec.709 luminance of (1, 0, 0)
  EXPECT_EQ(d.at(3, 4), false_colour(1.0f));
  EXPECT_EQ(d.at(0, 0), false_colour(0.0f));
  Image same = difference_image(b, b, &scale);
  EXPECT_EQ(scale, 0);
  EXPECT_EQ(same.at(5, 5), false_colour(0.0f));
}

// The `dermis` command line beside this test binary (ctest also names it in
// DERMIS_TEST_BINARY).
std::string dermis_binary() {
  if (const char* env = std::getenv("DERMIS_TEST_BINARY")) return env;
  return (fs::read_symlink("/proc/self/exe").parent_path() / "dermis").string();
}

class CompareCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dermis_compare_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ASSERT_TRUE(fs::exists(dermis_binary())) << dermis_binary();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  // Runs `dermis ARGS`, returns the exit status; stdout and stderr go to files.
  int run(const std::string& args) {
    std::string cmd = dermis_binary() + " " + args + " >" + file("stdout.txt") + " 2>" + file("stderr.txt");
    int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string read(const std::string& name) {
    std::ifstream in(file(name));
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  fs::path dir_;
};

TEST_F(CompareCommand, PrintsTableAndWritesDifferenceImage) {
  Image b(8, 8, RGB(1.0f)), a(8, 8, RGB(1.5f));
  write_image(file("a.exr"), a);
  write_image(file("b.exr"), b);
  ASSERT_EQ(run("compare " + file("a.exr") + " " + file("b.exr") + " --diff " + file("d.png")), 0)
      << read("stderr.txt");
  const std::string out = read("stdout.txt");
  // The RMSE row: "RMSE" then R, G, B and all, each 0.5.
  std::istringstream rows(out);
  std::string line;
  bool found = false;
  while (std::getline(rows, line)) {
    std::istringstream words(line);
    std::string name;
    words >> name;
    if (name != "RMSE") continue;
    found = true;
    double v;
    int count = 0;
    while (words >> v) {
      EXPECT_EQ(v, 0.5) << line;
      ++count;
    }
    EXPECT_EQ(count, 4) << line;
  }
  EXPECT_TRUE(found) << out;
  EXPECT_NE(out.find("mean A"), std::string::npos) << out;
  EXPECT_NE(out.find("relMSE"), std::string::npos) << out;
  Image d = read_image(file("d.png"));
  EXPECT_EQ(d.width, 8);
}

TEST_F(CompareCommand, BadInputsExitWithStatus2AndAMessage) {
  write_image(file("a.exr"), Image(8, 8));
  write_image(file("b.exr"), Image(8, 4));
  EXPECT_EQ(run("compare " + file("a.exr") + " " + file("b.exr")), 2);
  EXPECT_NE(read("stderr.txt").find("8x8 versus 8x4"), std::string::npos) << read("stderr.txt");
  EXPECT_EQ(run("compare " + file("a.exr") + " " + file("missing.exr")), 2);
  EXPECT_NE(read("stderr.txt").find("missing.exr: could not read image"), std::string::npos);
  EXPECT_EQ(run("compare " + file("a.exr") + " " + file("a.exr") + " --diff " + file("d.xyz")), 2);
  EXPECT_NE(read("stderr.txt").find("unknown extension"), std::string::npos);
  EXPECT_EQ(run("compare " + file("a.exr")), 2);  // usage error
}

}  // namespace
}  // namespace dermis
