// Scene assembly: the parsed SceneDesc turned into the renderer's shapes (in Embree),
// materials, textures, media, lights and camera. Nothing here computes more than the
// BVH; the subsurface methods' tables and the point clouds are made by preparation
// (scene_preparation.h), before rendering.
#pragma once

#include <memory>

#include "dermis/render/render_scene.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

// Throws SceneError for problems found while building (e.g. an unreadable texture),
// and adds warnings to `diagnostics`.
std::unique_ptr<RenderScene> assemble_scene(const SceneDesc& desc, Diagnostics& diagnostics);

}  // namespace dermis
