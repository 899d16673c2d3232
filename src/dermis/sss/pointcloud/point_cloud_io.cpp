#include "dermis/sss/pointcloud/point_cloud_io.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace dermis::sss::pointcloud {
namespace {

constexpr char kMagic[8] = {'D', 'R', 'M', 'S', 'P', 'C', 'L', 'D'};
constexpr uint32_t kRecordBytes = 44;
static_assert(std::endian::native == std::endian::little, "point cloud files are little-endian");

template <class T>
void put(std::vector<char>& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}
template <class T>
T get(const char*& p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  p += sizeof(T);
  return v;
}

}  // namespace

void save_point_cloud(const std::string& path, const PointCloud& cloud) {
  if (cloud.points.size() != cloud.irradiance.size())
    throw std::invalid_argument("save_point_cloud: " + std::to_string(cloud.points.size()) + " points but " +
                                std::to_string(cloud.irradiance.size()) + " irradiance values");
  std::vector<char> out;
  out.reserve(24 + cloud.points.size() * kRecordBytes);
  out.insert(out.end(), kMagic, kMagic + 8);
  put(out, kPointCloudFileVersion);
  put(out, kRecordBytes);
  put(out, uint64_t(cloud.points.size()));
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const SurfacePoint& p = cloud.points[i];
    for (int a = 0; a < 3; ++a) put(out, p.position[a]);
    for (int a = 0; a < 3; ++a) put(out, p.normal[a]);
    put(out, p.area);
    put(out, p.triangle);
    for (int c = 0; c < 3; ++c) put(out, cloud.irradiance[i][c]);
  }
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error("save_point_cloud: cannot open '" + path + "' for writing");
  f.write(out.data(), std::streamsize(out.size()));
  if (!f) throw std::runtime_error("save_point_cloud: writing '" + path + "' failed");
}

PointCloud load_point_cloud(const std::string& path) {
  auto fail = [&](const std::string& why) { return std::runtime_error("point cloud '" + path + "': " + why); };
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) throw fail("cannot open the file");
  const std::streamoff size = f.tellg();
  f.seekg(0);
  std::vector<char> data(std::size_t(std::max<std::streamoff>(size, 0)));
  if (!f.read(data.data(), std::streamsize(data.size()))) throw fail("cannot read the file");
  if (data.size() < 24 || std::memcmp(data.data(), kMagic, 8) != 0)
    throw fail("not a Dermis point cloud (the header's magic \"DRMSPCLD\" is missing)");
  const char* p = data.data() + 8;
  const auto version = get<uint32_t>(p);
  if (version != kPointCloudFileVersion)
    throw fail("file version " + std::to_string(version) + ", this build reads version " +
               std::to_string(kPointCloudFileVersion));
  const auto record = get<uint32_t>(p);
  if (record != kRecordBytes) throw fail("record size " + std::to_string(record) + ", expected 44");
  const auto count = get<uint64_t>(p);
  const uint64_t body = data.size() - 24;
  if (count > body / kRecordBytes || body != count * kRecordBytes)
    throw fail("the header announces " + std::to_string(count) + " points (" + std::to_string(count * kRecordBytes) +
               " bytes) but the file holds " + std::to_string(body) + " bytes of points: truncated or corrupt");
  PointCloud cloud;
  cloud.points.resize(count);
  cloud.irradiance.resize(count);
  for (uint64_t i = 0; i < count; ++i) {
    SurfacePoint& s = cloud.points[i];
    for (int a = 0; a < 3; ++a) s.position[a] = get<float>(p);
    for (int a = 0; a < 3; ++a) s.normal[a] = get<float>(p);
    s.area = get<float>(p);
    s.triangle = get<uint32_t>(p);
    for (int c = 0; c < 3; ++c) cloud.irradiance[i][c] = get<float>(p);
    const RGB& e = cloud.irradiance[i];
    const bool finite = std::isfinite(s.position.x) && std::isfinite(s.position.y) && std::isfinite(s.position.z) &&
                        std::isfinite(s.area) && e.is_finite();
    if (!finite) throw fail("point " + std::to_string(i) + " has a non-finite value");
    if (s.area < 0 || e[0] < 0 || e[1] < 0 || e[2] < 0)
      throw fail("point " + std::to_string(i) + " has a negative area or irradiance");
    if (!(std::abs(length(Vec3d(s.normal)) - 1) < 1e-3))
      throw fail("point " + std::to_string(i) + " has a normal that is not unit length");
  }
  return cloud;
}

}  // namespace dermis::sss::pointcloud
