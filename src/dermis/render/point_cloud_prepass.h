// The point-cloud pre-pass (Jensen & Buehler 2002; Langlands & Mertens, seed 001):
// points over every object whose subsurface method is `pointcloud`, their transmitted
// irradiance computed with the renderer's own light transport, and the octree with
// its local disk tables (src/dermis/sss/pointcloud/).
#pragma once

#include <cstdint>

#include "dermis/core/sampler.h"
#include <string>

namespace dermis {

struct RenderScene;

struct PointCloudOptions {
  std::size_t points = 0;   // points per object; 0: from the material's "pointdensity"
  std::string save_path;    // write the cloud(s) here (object k > 0 gets ".k" appended)
  std::string load_path;    // read them instead of computing them
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;
};

struct PointCloudReport {
  std::size_t clouds = 0, points = 0, memory_bytes = 0, file_bytes = 0;
  double prepass_seconds = 0;  // point distribution and irradiance (or loading)
  double build_seconds = 0;    // octrees and local disk tables
};

// Builds scene.point_clouds; throws std::runtime_error with a message a user can act on.
PointCloudReport build_point_clouds(RenderScene& scene, const PointCloudOptions& options);

}  // namespace dermis
