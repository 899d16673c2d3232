// Measured scattering coefficients usable by name in MakeNamedMedium "string preset".
#pragma once

#include <optional>
#include <string>

#include "dermis/core/rgb.h"

namespace dermis {

struct MediumPreset {
  const char* name;
  RGB sigma_s_prime;  // reduced scattering coefficient, mm^-1
  RGB sigma_a;        // absorption coefficient, mm^-1
};

// Looks a preset up ignoring case, spaces, '-' and '_' ("skin1", "Skin 1", "SKIN1").
// As pbrt does, the reduced scattering coefficient is used as sigma_s with g = 0.
std::optional<MediumPreset> find_medium_preset(const std::string& name);
// "Apple, Chicken1, ..." for error messages.
std::string medium_preset_names();

}  // namespace dermis
