// The thickness of each subsurface material's object: the mean chord length 4V/S
// (geometry/mean_chord.h) of the shapes of its object (render_scene.h object_of_shape:
// the shapes sharing the material, or its "sssgroup"). For the walk's guiding
// (subsurface/walk_method.h, short_walk_guided_shares).
#pragma once

#include <vector>

#include "dermis/render/render_scene.h"

namespace dermis {

// Per entry of sc.subsurface_params: the mean chord length in world space, or 0 where it
// has none (no shape, an open surface) or it is not known (an object seen through
// instances: its shapes lie in its own space, and each instance may scale it).
std::vector<double> subsurface_object_chords(const RenderScene& sc);

}  // namespace dermis
