// Saving and loading a point cloud (points and their irradiance) as a binary file.
//
// Layout (little-endian): 8-byte magic "DRMSPCLD", uint32 version (1), uint32 record
// size (44), uint64 point count, then per point: position (3 float32), normal
// (3 float32), area (float32), triangle (uint32), irradiance RGB (3 float32).
#pragma once

#include <string>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/sss/pointcloud/point_distribution.h"

namespace dermis::sss::pointcloud {

struct PointCloud {
  std::vector<SurfacePoint> points;
  std::vector<RGB> irradiance;  // one per point
};

inline constexpr uint32_t kPointCloudFileVersion = 1;

// Throws std::runtime_error when the file cannot be written, std::invalid_argument when
// the sizes of points and irradiance differ.
void save_point_cloud(const std::string& path, const PointCloud& cloud);
// Throws std::runtime_error naming the file and the fault: missing, not a Dermis point
// cloud, another version, truncated or with trailing bytes, non-finite values, negative
// areas or irradiance, normals that are not unit length.
PointCloud load_point_cloud(const std::string& path);

}  // namespace dermis::sss::pointcloud
