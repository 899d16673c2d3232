// Scene assembly: the parsed SceneDesc turned into the renderer's shapes (in Embree),
// materials, textures, media, lights and camera. Nothing here computes more than the
// BVH; the subsurface methods' tables and the point clouds are made by preparation
// (scene_preparation.h), before rendering.
#pragma once

#include <memory>

#include "dermis/core/load_monitor.h"
#include "dermis/render/render_scene.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

// Throws SceneError for problems found while building (e.g. an unreadable texture),
// and adds warnings to `diagnostics`. With a monitor, the BVH build reports its progress
// and stops (Interrupted) once the monitor's cancel flag is set.
std::unique_ptr<RenderScene> assemble_scene(const SceneDesc& desc, Diagnostics& diagnostics,
                                            const LoadMonitor* monitor = nullptr);

}  // namespace dermis
