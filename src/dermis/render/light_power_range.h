// The range of light powers the renderer accepts. Light selection tabulates each light's
// power (lights/light.h: light_power) in 32-bit floats, and a light whose power is beyond
// their range (a point light of I = 3e37 has 4 pi I = 3.8e38) once stopped the render with
// "Distribution1D: value 0 of the function is inf", naming neither the light nor where it
// is; such a light is reported at its directive instead.
#pragma once

#include <span>

#include "dermis/lights/light.h"
#include "dermis/scene/diagnostics.h"

namespace dermis {

// The largest light power accepted: the largest 32-bit float.
inline constexpr double kMaxLightPower = 3.4028234663852886e38;

// Throws SceneError at `loc` ("the point light's power 4π·I = 4π × 3e+37 = 3.77e+38 is
// beyond ...; lower "I" or "scale"") when the power of a finite light is beyond
// kMaxLightPower: one point or spot light, or the lights of one shape's area light (all
// its triangles together, or its sphere). Lights at infinity are not checked: their power
// grows with the scene's radius, only for selection, which normalises it in double; their
// radiance is bounded by the parser.
void check_light_power(std::span<const Light> lights, const SourceLoc& loc);

}  // namespace dermis
