// Which pixels show a subsurface object: the mask a comparison of subsurface methods
// restricts its errors to (the rest of the image is the same for every method).
#pragma once

#include <cstdint>
#include <vector>

#include "dermis/render/render_scene.h"

namespace dermis {

// One byte per pixel of the film's crop window, row-major, top row first: 1 where the
// camera ray through the pixel's centre (lens centre) first hits a shape whose material
// is `subsurface` (whatever its method, `volumetric` included), else 0. Needs assembly only.
std::vector<uint8_t> subsurface_object_mask(const RenderScene& scene);

}  // namespace dermis
