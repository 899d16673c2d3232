// The diffusion profile a subsurface material asks for ("profile"), per channel, for
// the methods built on profiles (probes, the point cloud).
#pragma once

#include "dermis/scene/subsurface_params.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis {

sss::ProfileRGB make_profile(const SubsurfaceParams& params);

}  // namespace dermis
