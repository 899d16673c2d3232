// Scene preparation: what must be computed before rendering and may take a while —
// the subsurface methods (albedo-inversion tables, profile and probe tables), the
// coefficients of the volumetric references, and the point clouds. Each stage shows
// progress when asked and stops on the cancel flag.
#pragma once

#include <atomic>
#include <memory>

#include "dermis/render/point_cloud_prepass.h"
#include "dermis/render/process_group.h"
#include "dermis/render/progress.h"
#include "dermis/render/render_scene.h"

namespace dermis {

struct PreparationOptions {
  PointCloudOptions point_clouds;
  Progress::Style progress = Progress::Style::kQuiet;
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT) to stop: throws Interrupted
  // The processes preparing the same scene together (null: this one alone): the albedo
  // tables and the point clouds' irradiance are computed in shares and exchanged; the
  // cancel flag is combined at each stage, so that all stop together.
  ProcessGroup* group = nullptr;
};

struct PreparationReport {
  double subsurface_seconds = 0;  // methods and volumetric coefficients
  PointCloudReport point_clouds;
};

// Throws SceneError (a material's parameters a method cannot use), std::runtime_error
// (point clouds: a file that cannot be read, instanced objects) or Interrupted.
PreparationReport prepare_scene(RenderScene& scene, const PreparationOptions& options = {});

// Assembly and preparation in one call, quietly (tests, benchmarks).
std::unique_ptr<RenderScene> build_render_scene(const SceneDesc& desc, Diagnostics& diagnostics,
                                                const PointCloudOptions& point_clouds = {});

}  // namespace dermis
