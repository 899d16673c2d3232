#include "dermis/materials/nanovdb_grid.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "dermis/core/rng.h"
#include "support/nanovdb_files.h"

namespace dermis {
namespace {

// A voxel function with no symmetry (so that an axis or an offset mixed up shows), zero at
// the grid's edges.
float voxel_value(int i, int j, int k) {
  if (i < 0 || j < 0 || k < 0 || i > 15 || j > 15 || k > 15) return 0;
  return 0.1f * float(i) + 0.05f * float(j * j % 7) + 0.3f * float((k + 2 * i) % 5);
}

// Trilinear interpolation of voxel_value at a point of index space.
double trilinear(double x, double y, double z) {
  const int i = int(std::floor(x)), j = int(std::floor(y)), k = int(std::floor(z));
  const double fx = x - i, fy = y - j, fz = z - k;
  double v = 0;
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    v += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) * voxel_value(i + dx, j + dy, k + dz);
  }
  return v;
}

class NanoVdbFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("dermis_nvdb_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // 16^3 voxels of 0.125, from -1: the box [-1, 1]^3.
  std::string write_grids(const std::string& name, std::function<float(int, int, int)> f = voxel_value,
                          bool temperature = true) {
    std::vector<nanovdb::GridHandle<>> grids;
    grids.push_back(testing::nvdb_grid("density", 16, 0.125, -1.0, f));
    if (temperature)
      grids.push_back(testing::nvdb_grid("temperature", 16, 0.125, -1.0, [](int, int, int) { return 1500.0f; }));
    testing::write_nvdb(path(name), std::move(grids));
    return path(name);
  }
  std::filesystem::path dir_;
};

// The grid's world box and its values, against trilinear interpolation of the voxels in
// index space (voxel (i, j, k) at world (i, j, k) / 8 - 1), as pbrt-v4 reads a nanovdb medium.
TEST_F(NanoVdbFiles, ReadsTheGridAsPbrtV4) {
  const auto grid = NanoVdbGrid::load(write_grids("a.nvdb"), "density");
  EXPECT_EQ(grid->world_min(), Vec3(-1, -1, -1));
  EXPECT_EQ(grid->world_max(), Vec3(1, 1, 1));
  EXPECT_GT(grid->bytes(), 0u);
  Rng rng(3, 1);
  for (int n = 0; n < 2000; ++n) {
    const Vec3 p(2.2f * rng.uniform() - 1.1f, 2.2f * rng.uniform() - 1.1f, 2.2f * rng.uniform() - 1.1f);
    ASSERT_NEAR(grid->value(p), trilinear((p.x + 1) * 8, (p.y + 1) * 8, (p.z + 1) * 8), 2e-5) << n;
  }
  EXPECT_TRUE(NanoVdbGrid::load(path("a.nvdb"), "temperature"));
  EXPECT_FALSE(NanoVdbGrid::load(path("a.nvdb"), "heat", true));  // optional and absent
}

// max_over bounds every value in its box, for boxes of every size, inside and across the grid.
TEST_F(NanoVdbFiles, MaxOverBoundsTheValues) {
  const auto grid = NanoVdbGrid::load(write_grids("b.nvdb"), "density");
  Rng rng(4, 1);
  for (int n = 0; n < 300; ++n) {
    const Vec3 a(3 * rng.uniform() - 1.5f, 3 * rng.uniform() - 1.5f, 3 * rng.uniform() - 1.5f);
    const Vec3 size = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * (n % 2 ? 0.2f : 1.0f);
    const float bound = grid->max_over(a, a + size);
    for (int m = 0; m < 50; ++m) {
      const Vec3 p = a + Vec3(size.x * rng.uniform(), size.y * rng.uniform(), size.z * rng.uniform());
      ASSERT_LE(grid->value(p), bound + 1e-6f) << n << " " << m;
    }
  }
}

// Every way a file can be wrong is an error naming what is wrong, never a crash.
TEST_F(NanoVdbFiles, BadFilesAreErrors) {
  auto error = [](const std::string& file, const std::string& name, const std::string& what) {
    try {
      NanoVdbGrid::load(file, name);
      ADD_FAILURE() << "no error for " << file;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const std::string good = write_grids("good.nvdb");
  error(path("missing.nvdb"), "density", "cannot open");
  std::ofstream(path("text.nvdb")) << "not a volume at all, but long enough to hold a header or two......";
  error(path("text.nvdb"), "density", "not an .nvdb file");
  error(good, "smoke", "no grid named \"smoke\" (the file has \"density\", \"temperature\")");
  // Truncated at several places, and one byte changed in each of several places of the grid's
  // data (a file of the density alone: its data is all that follows the first 400 bytes).
  std::string bytes;
  {
    std::ifstream in(write_grids("alone.nvdb", voxel_value, false), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  for (std::size_t cut : {std::size_t(20), bytes.size() / 3, bytes.size() - 9}) {
    std::ofstream(path("cut.nvdb"), std::ios::binary) << bytes.substr(0, cut);
    EXPECT_THROW(NanoVdbGrid::load(path("cut.nvdb"), "density"), std::runtime_error) << cut;
  }
  for (std::size_t at = 400; at < bytes.size(); at += bytes.size() / 7) {
    std::string changed = bytes;
    changed[at] = char(changed[at] ^ 0x5a);
    std::ofstream(path("changed.nvdb"), std::ios::binary) << changed;
    EXPECT_THROW(NanoVdbGrid::load(path("changed.nvdb"), "density"), std::runtime_error) << at;  // the checksum
  }
  error(write_grids("negative.nvdb", [](int i, int, int) { return i == 3 ? -1.0f : 1.0f; }), "density", "negative");
  error(
      write_grids("nan.nvdb", [](int i, int, int) { return i == 3 ? std::numeric_limits<float>::quiet_NaN() : 1.0f; }),
      "density", "NaN");
}

}  // namespace
}  // namespace dermis
