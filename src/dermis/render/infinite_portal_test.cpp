// pbrt-v4's infinite-light "portal": light arrives only from the side of the portal's
// rectangle that its normal (p3 - p0) x (p1 - p0) points to. A diffuse plane facing +z under a
// uniform sky of radiance 1 returns rho / pi E toward every view, E = pi (the whole upper
// hemisphere) without a portal or with one facing +z, pi / 2 with one facing +x (half of
// it: cos-weighted, by symmetry), 0 with one facing -z. Within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/core/warp.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

constexpr float kRho = 0.5f;

std::string portal_scene(const std::string& portal) {
  return "LookAt 0 0 10  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 2 "
         "\"integer yresolution\" 2\nIntegrator \"volpath\" \"integer maxdepth\" 5\nWorldBegin\n"
         "LightSource \"infinite\" \"rgb L\" [1 1 1] " +
         portal + "\nMaterial \"diffuse\" \"rgb reflectance\" [" + std::to_string(kRho) + " " + std::to_string(kRho) +
         " " + std::to_string(kRho) +
         "]\nShape \"trianglemesh\" \"point3 P\" [-100 -100 0  100 -100 0  100 100 0  -100 100 0] "
         "\"integer indices\" [0 1 2  0 2 3]\n";
}

// The mean radiance and its standard error toward cosine-distributed views of the origin.
std::pair<double, double> mean_radiance(const std::string& portal) {
  Diagnostics diag;
  const SceneDesc d = parse_scene_string(portal_scene(portal), "portal.pbrt");
  EXPECT_TRUE(d.diagnostics.warnings.empty()) << d.diagnostics.warnings.at(0);
  auto sc = build_render_scene(d, diag);
  const int n = 20000;
  double sum = 0, sum2 = 0;
  PathCounters counters;
  for (int i = 0; i < n; ++i) {
    Sampler rng(SamplerKind::Independent, 5, uint64_t(i), 0);  // independent: the standard error assumes it
    const Vec3 w = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
    const double L = trace_path(*sc, Ray{w, -w}, -1, rng, counters)[1];
    sum += L;
    sum2 += L * L;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(InfinitePortal, LightComesOnlyFromThePortalsSide) {
  const struct {
    std::string portal;
    double E;
  } cases[] = {
      {"", kPi},
      {"\"point3 portal\" [0 0 0  0 1 0  1 1 0  1 0 0]", kPi},                    // (p3 - p0) x (p1 - p0) = +z
      {"\"point3 portal\" [0 0 0  0 0 1  0 1 1  0 1 0]", kPi / 2},                // +x
      {"\"point3 portal\" [0 0 0  1 0 0  1 1 0  0 1 0]", 0},                      // -z
      {"\"point3 portal\" [5 5 5  5 5 7  5 8 7  5 8 5] \"float scale\" 2", kPi},  // +x, L doubled
  };
  for (const auto& c : cases) {
    const auto [mean, se] = mean_radiance(c.portal);
    EXPECT_NEAR(mean, kRho / kPi * c.E, 4 * se + 1e-6) << c.portal << ": se " << se;
  }
}

TEST(InfinitePortal, APortalThatIsNotARectangleIsAnError) {
  EXPECT_THROW(parse_scene_string(portal_scene("\"point3 portal\" [0 0 0  1 0 0  1 2 0  0 1 0]")), SceneError);
  EXPECT_THROW(parse_scene_string(portal_scene("\"point3 portal\" [0 0 0  1 0 0  1 1 0]")), SceneError);
}

}  // namespace
}  // namespace dermis
