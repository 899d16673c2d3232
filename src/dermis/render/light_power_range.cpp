#include "dermis/render/light_power_range.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace dermis {

namespace {

// The channels' mean, as light_power() takes it (in double: the float sum may overflow).
double mean(const RGB& c) { return (double(c[0]) + double(c[1]) + double(c[2])) / 3; }

}  // namespace

void check_light_power(std::span<const Light> lights, const SourceLoc& loc) {
  if (lights.empty()) return;
  double power = 0;
  for (const Light& l : lights) power += light_power(l, 0);
  if (power <= kMaxLightPower) return;
  const Light& l = lights.front();
  const double e = mean(l.emission);
  std::string what;
  switch (l.type) {
    case Light::Type::Point:
      what = fmt::format("the point light's power 4π·I = 4π × {:.3g} = {:.3g}", e, power);
      break;
    case Light::Type::Spot:
      what = fmt::format(
          "the spot light's power 2π·I·(1 − (cos(coneangle − conedelta) + cos(coneangle))/2) = {:.3g} "
          "(I = {:.3g})",
          power, e);
      break;
    case Light::Type::Sphere:
      what =
          fmt::format("the area light's power 4π²·r²·L = 4π² × {:.3g}² × {:.3g} = {:.3g}", double(l.radius), e, power);
      break;
    case Light::Type::Triangle: {
      double area = 0;
      for (const Light& t : lights) area += t.area;
      what = fmt::format("the area light's power π·L·A = π × {:.3g} × {:.3g} = {:.3g}{}", e, area, power,
                         l.two_sided ? " (two-sided: twice π·L·A)" : "");
      break;
    }
    case Light::Type::Distant:
    case Light::Type::Infinite:
      return;  // not checked (see the header)
  }
  const bool area_light = l.type == Light::Type::Sphere || l.type == Light::Type::Triangle;
  throw SceneError(
      loc, fmt::format("{} is beyond the range of 32-bit floats ({:.3g}) in which lights are "
                       "sampled; lower \"{}\" or \"scale\"{}",
                       what, kMaxLightPower, area_light ? "L" : "I", area_light ? " (or the shape's size)" : ""));
}

}  // namespace dermis
