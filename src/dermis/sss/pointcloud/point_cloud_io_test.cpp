#include "dermis/sss/pointcloud/point_cloud_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

namespace dermis::sss::pointcloud {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("dermis_pointcloud_" + name + ".bin")).string();
}

PointCloud small_cloud() {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f}};
  PointCloud c;
  c.points = distribute_points(p, {0, 1, 2}, 50, 9);
  for (std::size_t i = 0; i < c.points.size(); ++i) c.irradiance.push_back(RGB(float(i), 0.5f, 2.0f));
  return c;
}

TEST(PointCloudIo, RoundTripIsExact) {
  const PointCloud c = small_cloud();
  const std::string path = temp_path("roundtrip");
  save_point_cloud(path, c);
  const PointCloud d = load_point_cloud(path);
  ASSERT_EQ(d.points.size(), c.points.size());
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    EXPECT_EQ(d.points[i].position, c.points[i].position);
    EXPECT_EQ(d.points[i].normal, c.points[i].normal);
    EXPECT_EQ(d.points[i].area, c.points[i].area);
    EXPECT_EQ(d.points[i].triangle, c.points[i].triangle);
    EXPECT_EQ(d.irradiance[i], c.irradiance[i]);
  }
  std::filesystem::remove(path);
}

void expect_rejected(const std::string& path, const std::string& words) {
  try {
    load_point_cloud(path);
    ADD_FAILURE() << "no exception for " << words;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(PointCloudIo, BadFilesAreRejectedWithAReason) {
  const std::string path = temp_path("bad");
  save_point_cloud(path, small_cloud());
  std::string bytes;
  {
    std::ifstream f(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  auto write = [&](const std::string& b) { std::ofstream(path, std::ios::binary | std::ios::trunc) << b; };
  expect_rejected(temp_path("does_not_exist"), "cannot open");
  write("hello world, this is not a point cloud");
  expect_rejected(path, "not a Dermis point cloud");
  std::string v = bytes;
  v[8] = 7;
  write(v);
  expect_rejected(path, "version 7");
  write(bytes.substr(0, bytes.size() - 10));
  expect_rejected(path, "truncated");
  std::string neg = bytes;
  const float minus = -1.0f;
  std::memcpy(&neg[24 + 24], &minus, 4);  // the first point's area
  write(neg);
  expect_rejected(path, "negative area");
  std::filesystem::remove(path);
  EXPECT_THROW(save_point_cloud(path, PointCloud{small_cloud().points, {}}), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss::pointcloud
