// Measured scattering coefficients usable by name: MakeNamedMedium "string preset" and the
// subsurface material's "string name" (pbrt-v4's 47 named media: Jensen et al. 2001 and
// Narasimhan et al. 2006).
#pragma once

#include <optional>
#include <span>
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
// "unknown medium preset" messages: " (did you mean 'Regular Milk'?)" for a near miss, else "".
std::string medium_preset_suggestion(const std::string& name);
// Every preset, in pbrt-v4's order.
std::span<const MediumPreset> medium_presets();

}  // namespace dermis
