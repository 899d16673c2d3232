// Fuzz target: the point-cloud file (load_point_cloud, the pre-pass's --load). Bad input
// must end in std::runtime_error naming the fault; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <stdexcept>

#include "dermis/sss/pointcloud/point_cloud_io.h"
#include "temp_file.h"
#include "unexpected.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = dermis::fuzz::write_temp_file(data, size, ".pcl");
  try {
    dermis::sss::pointcloud::load_point_cloud(path);
  } catch (const std::runtime_error&) {
    // the contract for bad input
  } catch (const std::exception& e) {
    dermis::fuzz::unexpected_exception("point_cloud", e);
  }
  return 0;
}
