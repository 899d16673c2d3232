// The point-cloud pre-pass (Jensen & Buehler 2002; Langlands & Mertens, seed 001):
// points over every subsurface object whose method is `pointcloud`, their transmitted
// irradiance computed with the renderer's own light transport, and the octree with
// its local disk tables (src/dermis/sss/pointcloud/), handed to the object's method.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "dermis/core/load_monitor.h"  // Interrupted
#include "dermis/core/sampler.h"
#include "dermis/render/process_group.h"
#include "dermis/render/progress.h"
#include "dermis/render/render_scene.h"

namespace dermis {

struct PointCloudOptions {
  std::size_t points = 0;  // points per object; 0: from the material's "pointdensity"
  std::string save_path;   // write the cloud(s) here (object k > 0 gets ".k" appended)
  std::string load_path;   // read them instead of computing them
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;
};

struct PointCloudReport {
  std::size_t clouds = 0, points = 0, memory_bytes = 0, file_bytes = 0;
  double prepass_seconds = 0;         // point distribution and irradiance (or loading)
  double build_seconds = 0;           // octrees and local disk tables
  std::vector<std::string> warnings;  // e.g. a cloud capped at its "maxpoints" budget
  std::vector<std::string> notes;     // how each cloud's point count was chosen
};

// Computes the clouds of the scene's point-cloud objects (the scene's other subsurface
// methods must be made already: the irradiance paths may meet them). Throws
// std::runtime_error with a message a user can act on; stops early (throwing
// Interrupted) when `cancel` becomes true. With a group, each process computes the
// irradiance of its share of the points (a point's value depends on its index, not on
// who computes it) and all receive every point's; the cancel flag is then combined so
// that all stop together; only rank 0 saves. Loading: every process reads the file.
PointCloudReport build_point_clouds(RenderScene& scene, const PointCloudOptions& options,
                                    Progress::Style progress = Progress::Style::kQuiet,
                                    const std::atomic<bool>* cancel = nullptr, ProcessGroup* group = nullptr);

}  // namespace dermis
