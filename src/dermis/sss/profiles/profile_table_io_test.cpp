// A profile table written and read back is the same table, number for number; a file of
// another key, version or a damaged one is refused; the cache builds once and reads after.
#include "dermis/sss/profiles/profile_table_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "dermis/sss/profiles/gaussian.h"

namespace dermis::sss {
namespace {

ProfileTable small_table(double width) {
  ProfileTableOptions options;
  options.albedos = {0.1, 0.4, 0.7, 1.0};
  options.radial_nodes = 64;
  return ProfileTable(std::function<double(double, double)>(
                          [width](double a, double r) { return a * gaussian_2d(width, r) * (1 + 0.1 * r); }),
                      options);
}

// Every query a renderer makes gives the same bits.
void expect_same_table(const ProfileTable& a, const ProfileTable& b) {
  for (double albedo : {0.1, 0.25, 0.55, 0.9, 1.0}) {
    const auto qa = a.lookup(albedo), qb = b.lookup(albedo);
    EXPECT_EQ(qa.energy, qb.energy) << albedo;
    EXPECT_EQ(qa.scale, qb.scale) << albedo;
    for (double x : {1e-4, 0.01, 0.3, 1.0, 3.0}) {
      EXPECT_EQ(a.eval(qa, x), b.eval(qb, x)) << albedo << " " << x;
      EXPECT_EQ(a.pdf_radius(qa, x), b.pdf_radius(qb, x)) << albedo << " " << x;
    }
    for (double xi : {0.01, 0.5, 0.99}) EXPECT_EQ(a.sample_radius(qa, xi), b.sample_radius(qb, xi));
    EXPECT_EQ(a.r_max(qa, 0.99), b.r_max(qb, 0.99));
  }
  EXPECT_EQ(a.albedo_for_energy(0.3), b.albedo_for_energy(0.3));
}

std::string written(const ProfileTable& t, const std::string& key) {
  std::ostringstream out(std::ios::binary);
  EXPECT_TRUE(write_profile_table(out, key, t));
  return out.str();
}

std::shared_ptr<const ProfileTable> read(const std::string& bytes, const std::string& key) {
  std::istringstream in(bytes, std::ios::binary);
  return read_profile_table(in, key);
}

TEST(ProfileTableIo, RoundTripIsTheSameTable) {
  const ProfileTable t = small_table(0.25);
  const auto back = read(written(t, "gaussian-test"), "gaussian-test");
  ASSERT_TRUE(back);
  expect_same_table(t, *back);
}

TEST(ProfileTableIo, AnotherKeyOrADamagedFileIsRefused) {
  const std::string bytes = written(small_table(0.25), "gaussian-test");
  ASSERT_TRUE(read(bytes, "gaussian-test"));
  EXPECT_FALSE(read(bytes, "gaussian-tesT"));                              // another table
  EXPECT_FALSE(read(bytes.substr(0, bytes.size() - 1), "gaussian-test"));  // truncated
  EXPECT_FALSE(read(bytes + "x", "gaussian-test"));                        // trailing bytes
  EXPECT_FALSE(read("", "gaussian-test"));
  std::string magic = bytes;
  magic[0] = 'X';
  EXPECT_FALSE(read(magic, "gaussian-test"));
  std::string version = bytes;
  version[8] = char(kProfileTableFileVersion + 1);  // the version follows the 8-byte magic
  EXPECT_FALSE(read(version, "gaussian-test"));
  std::string nan = bytes;  // the last double of the last array (the cdf) made NaN
  const double q = std::nan("");
  std::memcpy(&nan[nan.size() - sizeof q], &q, sizeof q);
  EXPECT_FALSE(read(nan, "gaussian-test"));
}

TEST(ProfileTableIo, TheCacheBuildsOnceAndReadsAfter) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("dermis-table-cache-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  int builds = 0;
  auto build = [&] {
    ++builds;
    return small_table(0.25);
  };
  const auto first = cached_profile_table(dir.string(), "t.table", build);
  EXPECT_EQ(builds, 1);
  EXPECT_TRUE(std::filesystem::exists(dir / "t.table"));
  const auto second = cached_profile_table(dir.string(), "t.table", build);
  EXPECT_EQ(builds, 1);  // read from the file
  expect_same_table(*first, *second);
  // A damaged file is rebuilt and replaced.
  { std::ofstream(dir / "t.table", std::ios::binary | std::ios::trunc) << "not a table"; }
  const auto third = cached_profile_table(dir.string(), "t.table", build);
  EXPECT_EQ(builds, 2);
  expect_same_table(*first, *third);
  EXPECT_TRUE(cached_profile_table(dir.string(), "t.table", build));
  EXPECT_EQ(builds, 2);
  // No directory: no cache.
  cached_profile_table("", "t.table", build);
  EXPECT_EQ(builds, 3);
  // Only the table remains (the temporary file was renamed).
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dermis::sss
