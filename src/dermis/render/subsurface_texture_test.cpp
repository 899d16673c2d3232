// Textured subsurface parameters: a thick slab whose reflectance is a checkerboard
// returns, at the centre of each square, the reflectance that square asks for —
// F_avg + (1 - F_avg) A under uniform light, averaged over cosine-distributed views —
// for every method, within 4 standard errors (plus, for the point cloud, its stated
// discretisation bias). A is the square's albedo as the method defines it: the exact
// table's for the walk and the volumetric reference (the requested reflectance); for
// the probes, the energy of the square's profile (made from the square's constant
// parameters, not from the texture) within the probe's reach at that entry; for the
// point cloud, the square's profile's albedo.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <variant>

#include "dermis/core/warp.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/render/subsurface/probe_method.h"
#include "dermis/render/subsurface/profile_from_params.h"
#include "dermis/scene/parser.h"
#include "dermis/sss/profiles/quadrature.h"
#include "support/lit_sphere_scene.h"

namespace dermis {
namespace {

constexpr float kSquare = 4;  // scene units per checkerboard square
const RGB kTex1(0.8f, 0.5f, 0.25f), kTex2(0.3f, 0.6f, 0.9f);

std::string rgb(RGB v) {
  return "[" + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "]";
}
std::string num(float v) { return std::to_string(v); }

// A box 2 half x 2 half x depth with its top face at z = 0 and uv = (x, y) / kSquare.
// The point cloud gets a smaller box (its points cover every face) at 4 points per
// mfp^2: at 1 its discretisation bias exceeded its stated 3% (-3.9% measured at A 0.5).
// The count is that density ("illuminationerror" 0): under the uniform sky the count
// chosen from the illumination is the 2700-point pilot, whose error at one point of the
// surface (the cloud's "splotches") was +7.6% here.
std::string checker_slab(const std::string& method) {
  const bool cloud = method == "pointcloud";
  const float half = cloud ? 60 : 500, depth = cloud ? 30 : 100;
  const std::string h = num(half), nh = num(-half), d = num(-depth);
  const std::string uv = num(half / kSquare), nuv = num(-half / kSquare);
  return std::string(R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 2 "integer yresolution" 2
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "albedo" "spectrum" "checkerboard" "rgb tex1" )") +
         rgb(kTex1) + " \"rgb tex2\" " + rgb(kTex2) + R"(
Material "subsurface" "texture reflectance" "albedo" "rgb mfp" [1 1 1] "float eta" 1.33 "string method" ")" +
         method + "\"" +
         (cloud ? R"( "integer irradiancesamples" 4 "float pointdensity" 4 "float illuminationerror" 0)" : "") + R"(
Shape "trianglemesh" "point3 P" [)" +
         nh + " " + nh + " " + d + "  " + h + " " + nh + " " + d + "  " + h + " " + h + " " + d + "  " + nh + " " + h +
         " " + d + "  " + nh + " " + nh + " 0  " + h + " " + nh + " 0  " + h + " " + h + " 0  " + nh + " " + h + R"( 0]
  "point2 uv" [)" +
         nuv + " " + nuv + " " + uv + " " + nuv + " " + uv + " " + uv + " " + nuv + " " + uv + " " + nuv + " " + nuv +
         " " + uv + " " + nuv + " " + uv + " " + uv + " " + nuv + " " + uv + R"(]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
}

SubsurfaceParams::Method method_named(const std::string& name) {
  using M = SubsurfaceParams::Method;
  if (name == "disk") return M::Disk;
  if (name == "disk-single-axis") return M::DiskSingleAxis;
  if (name == "sphere-lines") return M::SphereLines;
  if (name == "sphere-lines-retry") return M::SphereLinesRetry;
  return M::PointCloud;
}

// The albedo of a square as the method defines it (see the top of the file); `scene`
// is the textured slab (the probes' reach at the square's entry).
RGB square_albedo(const std::string& method, RGB reflectance, const RenderScene& scene) {
  if (method == "randomwalk" || method == "volumetric") return reflectance;  // the exact table's definition of A
  SubsurfaceParams p;
  p.method = method_named(method);
  p.reflectance = reflectance;
  p.mfp = RGB(1);
  const sss::ProfileRGB profile = make_profile(p);
  if (method == "pointcloud")
    return RGB(float(profile[0].albedo()), float(profile[1].albedo()), float(profile[2].albedo()));
  const double reach = std::get<ProbeMethod>(scene.subsurface.at(0)->method).max_radius(profile);
  RGB e;
  for (int c = 0; c < 3; ++c)
    e[c] = float(sss::integrate([&](double r) { return profile[c].eval(r) * 2 * kPiD * r; }, 0, reach, 1e-9));
  return e;
}

TEST(SubsurfaceTextures, CheckerboardSlabReturnsEachSquaresReflectanceForEveryMethod) {
  double F_avg = 0;
  const int nq = 20000;
  for (int i = 0; i < nq; ++i) {
    const double mu = (i + 0.5) / nq;
    F_avg += 2 * fresnel_dielectric(float(mu), 1.33f) * mu / nq;
  }
  for (const std::string method :
       {"randomwalk", "volumetric", "disk", "disk-single-axis", "sphere-lines", "sphere-lines-retry", "pointcloud"}) {
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(checker_slab(method)), diag);
    // Centres of a tex1 square (floor(u) + floor(v) even) and a tex2 square.
    const struct {
      Vec3 p;
      RGB reflectance;
    } squares[] = {{{0.5f * kSquare, 0.5f * kSquare, 0}, kTex1}, {{1.5f * kSquare, 0.5f * kSquare, 0}, kTex2}};
    for (const auto& square : squares) {
      const RGB A = square_albedo(method, square.reflectance, *sc);
      // The point cloud's estimate is nearly noiseless (a gather per sample): fewer samples.
      const int n = method == "pointcloud" ? 3000 : 30000;
      double sum[3] = {}, sum2[3] = {};
      PathCounters counters;
      for (int i = 0; i < n; ++i) {
        Sampler rng(SamplerKind::Independent, 91, uint64_t(i), 0);  // independent: the standard error assumes it
        const Vec3 w = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
        const RGB L = trace_path(*sc, Ray{square.p + w, -w}, -1, rng, counters);
        for (int c = 0; c < 3; ++c) {
          sum[c] += L[c];
          sum2[c] += double(L[c]) * L[c];
        }
      }
      for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n, se = std::sqrt(std::max(0.0, sum2[c] / n - mean * mean) / n);
        // The point cloud's stated bias (point_cloud_prepass_test.cpp, docs/materials.md):
        // 3% of the albedo term, from the cloud's equal-area shares on planes.
        const double bias = method == "pointcloud" ? 0.03 * (1 - F_avg) * A[c] : 0.0;
        EXPECT_NEAR(mean, F_avg + (1 - F_avg) * A[c], bias + 4 * se)
            << method << ", reflectance " << square.reflectance[c] << ", channel " << c << ", A " << A[c];
        std::printf("%s, reflectance %.2f: %.5f vs %.5f (%+.2f%% of the albedo term), se %.5f\n", method.c_str(),
                    square.reflectance[c], mean, F_avg + (1 - F_avg) * A[c],
                    100 * (mean - F_avg - (1 - F_avg) * A[c]) / ((1 - F_avg) * A[c]), se);
      }
    }
  }
}

// A textured `scale` (a float texture, per entry point) renders as the same constant
// scale: a constant texture against "float scale", for the walk (coefficients), the disk
// probes (reflectance and mfp; the Skin6 profile, whose mm it converts) and the volumetric
// reference; region means within 4 standard errors of the difference.
TEST(SubsurfaceTextures, ATexturedScaleRendersAsTheSameConstantScale) {
  const std::string header =
      testing::lit_sphere_header(16) + "Texture \"s\" \"float\" \"constant\" \"float value\" 2.5\n";
  for (const std::string params :
       {R"("rgb sigma_a" [0.02 0.06 0.12] "rgb sigma_s" [0.8 1.2 1.6] "string method" "randomwalk")",
        R"("rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [1 0.75 0.5] "string method" "disk")",
        R"("rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [1 1 1] "string profile" "skin6" "string method" "disk")",
        R"("rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [1 0.75 0.5] "string method" "volumetric")"}) {
    SCOPED_TRACE(params);
    testing::expect_same_picture(
        header + "Material \"subsurface\" " + params + " \"texture scale\" \"s\"\nShape \"sphere\"\n",
        header + "Material \"subsurface\" " + params + " \"float scale\" 2.5\nShape \"sphere\"\n", 64, 51);
  }
}

}  // namespace
}  // namespace dermis
