// An environment map written for a test: pbrt-v4's equal-area square, 64 x 64, of radiance
// 0.5, with a sun (by default of radius 10 degrees at radiance 200) about a light-space
// direction.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "dermis/core/vec.h"
#include "dermis/lights/environment_map.h"
#include "dermis/render/image.h"

namespace dermis::testing {

// Writes the map to `path`: with a sun about the unit direction `sun`, or without (even).
inline void write_sky_with_sun(const std::string& path, std::optional<Vec3> sun, float sun_radius = 0.1745f,
                               float sun_radiance = 200) {
  constexpr int s = 64;
  Image img;
  img.width = img.height = s;
  img.pixels.assign(std::size_t(s) * s * 3, 0.5f);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x)
      if (sun && dot(equal_area_square_to_sphere({(x + 0.5f) / s, (y + 0.5f) / s}), *sun) > std::cos(sun_radius))
        for (int c = 0; c < 3; ++c) img.pixels[3 * (std::size_t(y) * s + x) + c] = sun_radiance;
  write_image(path, img);
}

}  // namespace dermis::testing
