// The diffusion profile a subsurface material asks for ("profile"), per channel, for
// the methods built on profiles (probes, the point cloud).
#pragma once

#include <memory>
#include <string>

#include "dermis/render/subsurface/coefficients.h"
#include "dermis/scene/subsurface_params.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/profiles/tabulated.h"

namespace dermis {

// The table of the `tabulated` profile (the dipole family at the material's eta), null
// for the other profiles. Built once per material: per-point profiles share it.
std::shared_ptr<const sss::ProfileTable> profile_table(const SubsurfaceParams& params);

// The cache file name of the photon-beam-diffusion table of (g, eta): every parameter of the
// table and the hash of the code that makes it (cmake/source_hashes.cmake), so that a table
// made by other code is never read.
std::string photon_beam_table_key(float g, float eta);

// The profile for the medium `at` (the material's constants, or its textures at one
// point); `table` from profile_table(). Allocates nothing for the closed-form profiles.
sss::ProfileRGB make_profile(const SubsurfaceParams& params, const MediumAt& at,
                             const std::shared_ptr<const sss::ProfileTable>& table);
inline sss::ProfileRGB make_profile(const SubsurfaceParams& params) {
  return make_profile(params, medium_at(params), profile_table(params));
}

}  // namespace dermis
