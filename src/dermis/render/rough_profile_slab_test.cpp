// The profile methods (disk, sphere-lines, point cloud) behind a rough boundary against
// the volumetric reference (the medium inside the rough dielectric) on a thick slab
// (reflectance 0.4, mfp 1, eta 1.4, roughness 0.4): the mean radiance over cosine-
// distributed views of the centre of the top face, lit by a uniform sky (rough entry and
// albedo) or only by a wide emitting panel low over the horizon, 59 to 84 degrees from
// the normal (the exit lobe Sw toward grazing directions, where the rough lobe T / c and
// the smooth (1 - Fr) / c differ most). A distant light would not do: the volumetric
// path tracer cannot reach a delta light through the smooth boundary.
//
// Stated bias: the profile methods are approximations by design (the separable BSSRDF,
// the profile's shape, the probe's reach, the cloud's discretisation). Their bias on
// this slab is measured with the smooth boundary in the same test, and the rough
// boundary must not make it worse under the sky: |rough bias| <= |smooth bias| + 4 sigma,
// sigma the standard error of the difference of the two biases. Lit from near the
// horizon it does (measured below, not bounded).
// Each bias is a paired difference (method and volumetric reference traced from the
// same view directions, independent random numbers otherwise), whose standard error is
// that of the mean of independent pairs. docs/materials.md lists the measured biases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/core/sampler.h"
#include "dermis/core/warp.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

std::string num(double v) { return std::to_string(v); }

// A box 120 x 120 x 30 with its top face at z = 0 (far wider and deeper than the
// profiles reach at mfp 1; the point cloud's points cover every face, at 4 points per
// mfp^2 as in SubsurfaceTextures), lit by a uniform sky or only by a two-sided emitting
// panel at x = 20, y in [-100, 100], z in [2, 12].
enum class Light { Sky, LowPanel };
std::unique_ptr<RenderScene> slab(const std::string& material, Light light) {
  const std::string lights =
      light == Light::Sky ? "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
                          : "AttributeBegin\n  AreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n"
                            "  Shape \"trianglemesh\" \"point3 P\" [20 -100 2  20 100 2  20 100 12  20 -100 12] "
                            "\"integer indices\" [0 1 2  0 2 3]\nAttributeEnd\n";
  const std::string scene = R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 2 "integer yresolution" 2
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
)" + lights + material + R"(
Shape "trianglemesh" "point3 P" [-60 -60 -30  60 -60 -30  60 60 -30  -60 60 -30
                                  -60 -60 0  60 -60 0  60 60 0  -60 60 0]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
  Diagnostics diag;
  return build_render_scene(parse_scene_string(scene), diag);
}

std::string subsurface(const std::string& method, double roughness) {
  std::string m =
      "Material \"subsurface\" \"rgb reflectance\" [0.4 0.4 0.4] \"rgb mfp\" [1 1 1] \"float eta\" 1.4 "
      "\"float roughness\" " +
      num(roughness) + " \"string method\" \"" + method + "\"";
  if (method == "pointcloud") m += " \"integer irradiancesamples\" 4 \"float pointdensity\" 4";
  return m;
}

// Radiance toward `views` cosine-distributed directions from the centre of the top
// face, one independent path each; view i's direction depends on i only, so that two
// scenes traced with the same views make independent pairs.
std::vector<double> radiance_per_view(const RenderScene& scene, int views, uint64_t seed) {
  std::vector<double> L(views);
  PathCounters counters;
  for (int i = 0; i < views; ++i) {
    Rng view(1234, uint64_t(i));
    const Vec3 w = sample_cosine_hemisphere({view.uniform(), view.uniform()});
    Sampler rng(SamplerKind::Independent, seed, uint64_t(i), 0);
    L[i] = trace_path(scene, Ray{w * 1.0f, -w}, -1, rng, counters).average();
  }
  return L;
}

// The bias of `test` relative to `reference` over the same views: the mean of the paired
// differences over the reference's mean, with its standard error (independent pairs).
struct Bias {
  double test = 0, reference = 0, relative = 0, stderr_ = 0;
};
Bias paired_bias(const std::vector<double>& test, const std::vector<double>& reference) {
  const double n = double(test.size());
  double st = 0, sr = 0, sd = 0, sd2 = 0;
  for (std::size_t i = 0; i < test.size(); ++i) {
    const double d = test[i] - reference[i];
    st += test[i], sr += reference[i], sd += d, sd2 += d * d;
  }
  Bias b;
  b.test = st / n;
  b.reference = sr / n;
  const double mean = sd / n;
  b.relative = mean / b.reference;
  b.stderr_ = std::sqrt(std::max(0.0, sd2 / n - mean * mean) / (n - 1)) / b.reference;
  return b;
}

constexpr double kRoughness = 0.4;  // remapped: alpha 0.63

// excess: the stated extra bias of the rough boundary for this light; negative: measure only.
void expect_rough_bias_within_smooth_bias(Light light, int views, double excess) {
  const char* light_name = light == Light::Sky ? "sky" : "low panel";
  std::vector<double> reference[2];
  for (int rough = 0; rough < 2; ++rough)
    reference[rough] = radiance_per_view(*slab(subsurface("volumetric", rough ? kRoughness : 0.0), light), views, 21);
  for (const std::string method : {"disk", "sphere-lines", "pointcloud"}) {
    SCOPED_TRACE(method + std::string(", ") + light_name);
    Bias bias[2];
    for (int rough = 0; rough < 2; ++rough) {
      const double roughness = rough ? kRoughness : 0.0;
      bias[rough] =
          paired_bias(radiance_per_view(*slab(subsurface(method, roughness), light), views, 22), reference[rough]);
      std::printf("%s, %-12s roughness %.1f: %.5f vs volumetric %.5f, bias %+.2f%% +- %.2f%%\n", light_name,
                  method.c_str(), roughness, bias[rough].test, bias[rough].reference, 100 * bias[rough].relative,
                  100 * bias[rough].stderr_);
    }
    const double sigma = std::hypot(bias[0].stderr_, bias[1].stderr_);
    if (excess < 0) continue;  // a measurement only
    EXPECT_LE(std::abs(bias[1].relative), std::abs(bias[0].relative) + excess + 4 * sigma)
        << "rough bias " << bias[1].relative << ", smooth bias " << bias[0].relative << ", sigma " << sigma;
  }
}

// Under a uniform sky the exit lobe's shape does not matter (it integrates to one):
// this is the rough entry and the albedo (the exact rough table of the volumetric
// reference against the profile's energy), at a small standard error.
TEST(RoughProfileSlab, UnderASkyRoughBiasIsWithinTheSmoothBias) {
  expect_rough_bias_within_smooth_bias(Light::Sky, 10000, 0.0);
}

// Lit from near the horizon: light leaves toward grazing directions. There the rough
// boundary makes every profile method darker than the volumetric reference (measured
// -11 to -13 % +- 2.5 %, against -1.5 to -3.6 % +- 2 % with the smooth boundary; the
// table in docs/materials.md); the likely cause, not tested: the separable model assumes
// isotropic radiance under the boundary, and a rough boundary draws its grazing exits from
// grazing directions inside, where the radiance is lower. No bound is claimed for it, so
// this is a measurement, not a test (disabled; it asserts nothing):
//   build/dermis_tests --gtest_also_run_disabled_tests --gtest_filter='RoughProfileSlab.DISABLED_*'
TEST(RoughProfileSlab, DISABLED_MeasureTheBiasLitFromNearTheHorizon) {
  expect_rough_bias_within_smooth_bias(Light::LowPanel, 30000, -1);
}

}  // namespace
}  // namespace dermis
