// Textured material parameters (pbrt-v4 lets each of these be a texture): a plane whose
// parameter is a checkerboard of two values returns, at the centre of each square, what the
// same material with that square's value as a constant returns, within 4 standard errors of
// the difference of the two means (independent samples). The constant material is the
// reference: its parameters go through the paths that the BSDF tests check (microfacet,
// layered and conductor tests); this checks that each texture reaches its parameter, per hit.
// Light: a dim uniform sky and a bright distant light, so that roughness changes both the
// reflectance and the shape of the lobe; views cosine-distributed over the hemisphere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dermis/core/warp.h"
#include "dermis/render/integrator.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"

namespace dermis {
namespace {

constexpr float kSquare = 2;  // scene units per checkerboard square

// A parameter of a material and its two values; "spectrum" parameters take a grey value.
struct TexturedParam {
  std::string material;  // the material's type and its other parameters
  std::string name;      // the parameter
  bool spectrum;
  float value1, value2;
};

std::string value_text(const TexturedParam& t, float v) {
  return t.spectrum
             ? "\"rgb " + t.name + "\" [" + std::to_string(v) + " " + std::to_string(v) + " " + std::to_string(v) + "]"
             : "\"float " + t.name + "\" " + std::to_string(v);
}

// The plane z = 0 (uv = (x, y) / kSquare) with `material`; `texture` declares the checkerboard.
std::string plane_scene(const std::string& texture, const std::string& material) {
  const std::string h = "100", nh = "-100", uv = std::to_string(100 / kSquare), nuv = std::to_string(-100 / kSquare);
  return "LookAt 0 0 10  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 2 "
         "\"integer yresolution\" 2\nIntegrator \"volpath\" \"integer maxdepth\" 50\nWorldBegin\n"
         "LightSource \"infinite\" \"rgb L\" [0.2 0.2 0.2]\n"
         "LightSource \"distant\" \"point3 from\" [1 0.5 2] \"point3 to\" [0 0 0] \"rgb L\" [3 3 3]\n" +
         texture + "Material " + material + "\nShape \"trianglemesh\" \"point3 P\" [" + nh + " " + nh + " 0  " + h +
         " " + nh + " 0  " + h + " " + h + " 0  " + nh + " " + h + " 0] \"point2 uv\" [" + nuv + " " + nuv + " " + uv +
         " " + nuv + " " + uv + " " + uv + " " + nuv + " " + uv + "] \"integer indices\" [0 1 2  0 2 3]\n";
}

struct Mean {
  double mean[3] = {}, var_of_mean[3] = {};
};

// The mean radiance toward cosine-distributed views of the point p.
Mean mean_at(const RenderScene& scene, Vec3 p, uint64_t seed, int n) {
  Mean m;
  double sum[3] = {}, sum2[3] = {};
  PathCounters counters;
  for (int i = 0; i < n; ++i) {
    Sampler rng(SamplerKind::Independent, seed, uint64_t(i), 0);  // independent: the standard error assumes it
    const Vec3 w = sample_cosine_hemisphere({rng.uniform(), rng.uniform()});
    const RGB L = trace_path(scene, Ray{p + w, -w}, -1, rng, counters);
    for (int c = 0; c < 3; ++c) {
      sum[c] += L[c];
      sum2[c] += double(L[c]) * L[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    m.mean[c] = sum[c] / n;
    m.var_of_mean[c] = std::max(0.0, sum2[c] / n - m.mean[c] * m.mean[c]) / n;
  }
  return m;
}

TEST(TexturedMaterialParams, EachSquareReturnsWhatItsConstantReturns) {
  const std::vector<TexturedParam> cases = {
      {"\"conductor\"", "roughness", false, 0.02f, 0.5f},
      {"\"conductor\" \"float vroughness\" 0.1", "uroughness", false, 0.02f, 0.6f},
      {"\"conductor\"", "reflectance", true, 0.3f, 0.9f},
      {"\"dielectric\"", "roughness", false, 0.05f, 0.6f},
      {"\"coateddiffuse\" \"rgb reflectance\" [0.6 0.6 0.6]", "roughness", false, 0.15f, 0.8f},
      {"\"coateddiffuse\" \"rgb albedo\" [0.8 0.8 0.8]", "thickness", false, 0.05f, 2.0f},
      {"\"coateddiffuse\" \"float thickness\" 0.5", "albedo", true, 0.1f, 0.9f},
      {"\"coateddiffuse\" \"float thickness\" 0.5 \"rgb albedo\" [0.9 0.9 0.9]", "g", false, -0.8f, 0.8f},
      {"\"coatedconductor\"", "conductor.roughness", false, 0.02f, 0.6f},
      {"\"coatedconductor\"", "interface.roughness", false, 0.15f, 0.8f},
      {"\"coatedconductor\"", "reflectance", true, 0.2f, 0.9f},
  };
  const int n = 20000;
  for (const TexturedParam& t : cases) {
    const std::string kind = t.spectrum ? "spectrum" : "float";
    const std::string texture = "Texture \"checks\" \"" + kind + "\" \"checkerboard\" " +
                                value_text({"", "tex1", t.spectrum, 0, 0}, t.value1) + " " +
                                value_text({"", "tex2", t.spectrum, 0, 0}, t.value2) + "\n";
    Diagnostics diag;
    const SceneDesc textured_desc =
        parse_scene_string(plane_scene(texture, t.material + " \"texture " + t.name + "\" \"checks\""));
    EXPECT_TRUE(textured_desc.diagnostics.warnings.empty())
        << t.material << " " << t.name << ": "
        << (textured_desc.diagnostics.warnings.empty() ? "" : textured_desc.diagnostics.warnings[0]);
    auto textured = build_render_scene(textured_desc, diag);
    // The centres of a tex1 square (floor(u) + floor(v) even) and of a tex2 square.
    const Vec3 centre[2] = {{0.5f * kSquare, 0.5f * kSquare, 0}, {1.5f * kSquare, 0.5f * kSquare, 0}};
    const float value[2] = {t.value1, t.value2};
    double contrast = 0;  // how far apart the two constants' means are, in standard errors
    Mean constant_mean[2];
    for (int s = 0; s < 2; ++s) {
      auto constant =
          build_render_scene(parse_scene_string(plane_scene("", t.material + " " + value_text(t, value[s]))), diag);
      const Mean a = mean_at(*textured, centre[s], 17, n);
      const Mean b = mean_at(*constant, centre[s], 29, n);
      constant_mean[s] = b;
      for (int c = 0; c < 3; ++c) {
        const double se = std::sqrt(a.var_of_mean[c] + b.var_of_mean[c]);
        EXPECT_NEAR(a.mean[c], b.mean[c], 4 * se)
            << t.material << ", textured " << t.name << " = " << value[s] << ", channel " << c;
      }
      std::printf("%s, %s %.2f: textured %.5f, constant %.5f (se %.5f)\n", t.material.c_str(), t.name.c_str(), value[s],
                  a.mean[1], b.mean[1], std::sqrt(a.var_of_mean[1] + b.var_of_mean[1]));
    }
    contrast = std::abs(constant_mean[0].mean[1] - constant_mean[1].mean[1]) /
               std::sqrt(constant_mean[0].var_of_mean[1] + constant_mean[1].var_of_mean[1]);
    // The test can tell the two values apart: a texture that reached nothing would fail above.
    EXPECT_GT(contrast, 8) << t.material << " " << t.name << ": the two values give the same mean";
  }
}

}  // namespace
}  // namespace dermis
