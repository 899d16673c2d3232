// The Python Scene: a parsed scene (meshes and textures read once) that can be changed
// between renders, and the render scene made from it, kept until something changes.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "dermis/core/sampler.h"
#include "dermis/render/render_scene.h"
#include "dermis/scene/scene_desc.h"

namespace dermis::python {

struct Scene {
  SceneDesc desc;
  std::string source;  // the file, or "<string>"
  // The render scene last built from `desc`, assembled and prepared; null after a change.
  // Preparation depends on the seed and sampler too (point clouds), kept beside it.
  std::shared_ptr<RenderScene> prepared;
  uint64_t prepared_seed = 0;
  SamplerKind prepared_sampler = SamplerKind::Sobol;
  // Set while a render runs without the GIL: changes from another Python thread wait.
  std::atomic<bool> busy{false};

  void changed();  // throws RuntimeError while busy; drops `prepared`
};

}  // namespace dermis::python
