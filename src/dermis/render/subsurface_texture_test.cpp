// Textured subsurface parameters: a thick slab whose reflectance is a checkerboard
// returns, at the centre of each square, the reflectance that square asks for —
// F_avg + (1 - F_avg) A under uniform light, averaged over cosine-distributed views
// (A the square's albedo: the walk's exact table; for the probes, the energy of the
// square's profile within the probe radius) — within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/core/warp.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/render/subsurface/probe_method.h"
#include "dermis/scene/parser.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis {
namespace {

constexpr float kSquare = 4;  // scene units per checkerboard square
const RGB kTex1(0.8f, 0.5f, 0.25f), kTex2(0.3f, 0.6f, 0.9f);

std::string rgb(RGB v) { return "[" + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "]"; }

// A 1000 x 1000 x 100 box with its top face at z = 0 and uv = (x, y) / kSquare.
std::string checker_slab(const std::string& method) {
  const std::string uv = std::to_string(500 / kSquare), nuv = "-" + uv;
  return std::string(R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 2 "integer yresolution" 2
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Texture "albedo" "spectrum" "checkerboard" "rgb tex1" )") +
         rgb(kTex1) + " \"rgb tex2\" " + rgb(kTex2) + R"(
Material "subsurface" "texture reflectance" "albedo" "rgb mfp" [1 1 1] "float eta" 1.33 "string method" ")" +
         method + R"("
Shape "trianglemesh" "point3 P" [-500 -500 -100  500 -500 -100  500 500 -100  -500 500 -100
                                  -500 -500 0  500 -500 0  500 500 0  -500 500 0]
  "point2 uv" [)" + nuv + " " + nuv + " " + uv + " " + nuv + " " + uv + " " + uv + " " + nuv + " " + uv + " " + nuv +
         " " + nuv + " " + uv + " " + nuv + " " + uv + " " + uv + " " + nuv + " " + uv + R"(]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
}

// The albedo of a square's material as the method sees it.
RGB square_albedo(const std::string& method, RGB reflectance) {
  if (method == "randomwalk") return reflectance;  // the exact table's definition of A
  SubsurfaceParams p;
  p.method = method == "disk" ? SubsurfaceParams::Method::Disk : SubsurfaceParams::Method::DiskSingleAxis;
  p.reflectance = reflectance;
  p.mfp = RGB(1);
  const ProbeMethod m(p, nullptr);
  RGB e;
  for (int c = 0; c < 3; ++c)
    e[c] = float(sss::integrate([&](double r) { return m.profile().channel[c].eval(r) * 2 * kPiD * r; }, 0,
                                m.max_radius()));
  return e;
}

TEST(SubsurfaceTextures, CheckerboardSlabReturnsEachSquaresReflectance) {
  double F_avg = 0;
  const int nq = 20000;
  for (int i = 0; i < nq; ++i) {
    const double mu = (i + 0.5) / nq;
    F_avg += 2 * fresnel_dielectric(float(mu), 1.33f) * mu / nq;
  }
  for (const char* method : {"randomwalk", "disk", "disk-single-axis"}) {
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(checker_slab(method)), diag);
    // Centres of a tex1 square (floor(u) + floor(v) even) and a tex2 square.
    const struct { Vec3 p; RGB reflectance; } squares[] = {{{0.5f * kSquare, 0.5f * kSquare, 0}, kTex1},
                                                          {{1.5f * kSquare, 0.5f * kSquare, 0}, kTex2}};
    for (const auto& square : squares) {
      const RGB A = square_albedo(method, square.reflectance);
      const int n = 30000;
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
        EXPECT_NEAR(mean, F_avg + (1 - F_avg) * A[c], 4 * se)
            << method << ", reflectance " << square.reflectance[c] << ", channel " << c;
      }
    }
  }
}

// The methods that hold one profile or one medium per material say so.
TEST(SubsurfaceTextures, MethodsWithoutTexturesAreAnErrorAtTheMaterial) {
  for (const char* method : {"sphere-lines", "sphere-lines-retry", "pointcloud", "volumetric"}) {
    Diagnostics diag;
    try {
      build_render_scene(parse_scene_string(checker_slab(method)), diag);
      ADD_FAILURE() << method << ": no error";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("textured"), std::string::npos) << e.what();
      EXPECT_EQ(e.loc().line, 8) << e.what();
    }
  }
}

}  // namespace
}  // namespace dermis
