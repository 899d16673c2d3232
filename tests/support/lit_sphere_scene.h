// The scene the subsurface comparisons share: a camera looking down at the origin from
// (0, -4, 1.5), a sky and a small spherical light above; the caller adds the object.
// Two variants of it are compared by their region means (4 x 4 pixels) within 4 standard
// errors of the difference.
#pragma once

#include <fmt/format.h>

#include <string>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis::testing {

// resolution x resolution pixels; more_lights: LightSource lines added to the sky and the
// spherical light.
inline std::string lit_sphere_header(int resolution, const std::string& more_lights = "") {
  return fmt::format(R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" {0} "integer yresolution" {0}
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [0.6 0.7 0.8]
{1}AttributeBegin
  AreaLightSource "diffuse" "rgb L" [6 6 6]
  Translate 2 -2 3
  Shape "sphere" "float radius" 0.5
AttributeEnd
)",
                     resolution, more_lights);
}

// Scenes a and b (whole scene texts) render the same picture: independent samples with
// seeds `seed` and seed + 1, spp per pixel; detectable_bias as expect_same_region_means'.
inline void expect_same_picture(const std::string& a, const std::string& b, int spp, uint64_t seed,
                                double detectable_bias = 0) {
  Diagnostics diag;
  auto sa = build_render_scene(parse_scene_string(a), diag);
  auto sb = build_render_scene(parse_scene_string(b), diag);
  expect_same_region_means(pixel_statistics(*sa, spp, seed), pixel_statistics(*sb, spp, seed + 1), 4, 4,
                           detectable_bias);
}

}  // namespace dermis::testing
