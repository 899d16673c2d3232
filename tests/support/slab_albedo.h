// The hemispherical albedo of a thick slab under a uniform sky, measured with the path
// tracer: the tests of the albedo inversion (a slab of the subsurface material must
// return the reflectance asked for) and of the half-space simulator (a slab of medium
// inside a dielectric must return what the simulator says).
#pragma once

#include <cmath>
#include <string>

#include "dermis/core/sampler.h"
#include "dermis/core/warp.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis::testing {

struct MeanAndError {
  double mean = 0, stderr_ = 0;  // standard error of the mean
};

// Radiance leaving the centre of the top face (z = 0) of a box 1000 x 1000 x 100 under
// a sky of radiance 1, averaged over `views` cosine-distributed directions: the slab's
// hemispherical albedo (with a reciprocal boundary, the light reflected per unit of
// diffusely incident light). `material`: the scene lines that make the box's material
// (a Material, or a MakeNamedMedium, MediumInterface and Material). Independent samples:
// the standard error is the sample standard deviation / sqrt(views).
inline MeanAndError slab_hemispherical_albedo(const std::string& material, int views, uint64_t seed = 77) {
  const std::string scene = R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 2 "integer yresolution" 2
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)" + material + R"(
Shape "trianglemesh" "point3 P" [-500 -500 -100  500 -500 -100  500 500 -100  -500 500 -100
                                  -500 -500 0  500 -500 0  500 500 0  -500 500 0]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(scene), diag);
  double sum = 0, sum2 = 0;
  PathCounters counters;
  for (int i = 0; i < views; ++i) {
    Sampler rng(SamplerKind::Independent, seed, uint64_t(i), 0);
    const Vec3 w = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
    const Ray ray{w * 1.0f, -w};  // arriving at the centre of the top face from direction w
    const double L = trace_path(*sc, ray, -1, rng, counters).average();
    sum += L;
    sum2 += L * L;
  }
  const double mean = sum / views;
  return {mean, std::sqrt(std::max(0.0, sum2 / views - mean * mean) / views)};
}

}  // namespace dermis::testing
