// Parity with pbrt-v4 in spectral mode: small scenes (bench/pbrt_v4/parity/*.pbrt) rendered by
// Dermis with spectral transport, their image means per channel against the means pbrt-v4 gave
// the same files. pbrt-v4 ran outside the repository (github.com/mmp/pbrt-v4 at 5f7a6068,
// built CPU-only): `bench/pbrt_v4/parity.py --pbrt PBRT --spp 2048 --seeds 8`, whose output is
// the table below (the mean and its standard error, pooled over the pixels).
//
// The coated scene's coat is smooth: with a rough one, stock pbrt-v4 reads 1.5-4.7 % high (its
// LayeredBxDF::f weighs the base-sampled estimate with the wrong density; found while writing
// this test: docs/results/results-vs-pbrt-v4.md, "A rough coat").
//
// The bar is issue 65's: within 1 % of pbrt-v4's mean in every channel, beyond the two
// estimates' noise (4 standard errors of the difference). The subsurface scene renders with
// pbrt-v4's own model (`--subsurface pbrt-v4`: disk probes, photon-beam profile).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

struct PbrtMean {
  const char* scene;
  std::array<double, 3> mean, stderr_;
};

constexpr std::array<PbrtMean, 5> kPbrtV4Means{{
    // bench/pbrt_v4/parity.py output
    {"coateddiffuse", {0.174202, 0.059445, 0.036031}, {0.000087, 0.000053, 0.000068}},
    {"diffuse-blackbody", {0.290543, 0.131687, 0.072575}, {0.000056, 0.000035, 0.000018}},
    {"gold", {0.319389, 0.277876, 0.109591}, {0.000061, 0.000059, 0.000029}},
    {"juice", {0.255766, 0.218602, 0.120399}, {0.000376, 0.000249, 0.000157}},
    {"skin", {0.141450, 0.103187, 0.054809}, {0.000089, 0.000064, 0.000059}},
}};

constexpr double kParity = 0.01;  // issue 65's bar, relative to pbrt-v4's mean

std::unique_ptr<RenderScene> parity_scene(const std::string& name) {
  SceneDesc desc = parse_scene_file(std::string(DERMIS_SOURCE_DIR) + "/bench/pbrt_v4/parity/" + name + ".pbrt");
  for (std::size_t i = 0; i < desc.materials.size(); ++i)
    if (desc.materials[i].type == MaterialDesc::Type::Subsurface)  // pbrt-v4's model (render_job.h kPbrtV4Subsurface)
      EXPECT_TRUE(
          set_material_parameters(desc, i, "\"string method\" \"disk\" \"string profile\" \"photonbeam\"", "test")
              .empty());
  Diagnostics diag;
  return build_render_scene(desc, diag);
}

void PrintTo(const PbrtMean& p, std::ostream* os) { *os << p.scene; }

class SpectralPbrtV4Parity : public ::testing::TestWithParam<PbrtMean> {};

TEST_P(SpectralPbrtV4Parity, ImageMeanWithinOnePercentOfPbrtV4) {
  const PbrtMean& p = GetParam();
  const auto sc = parity_scene(p.scene);
  const testing::PixelStatistics st = testing::pixel_statistics(*sc, 1024, 3, {}, true);
  for (int c = 0; c < 3; ++c) {
    double mean = 0, var = 0;
    for (std::size_t i = 0; i < st.mean.size(); ++i)
      mean += st.mean[i][c], var += double(st.stderr_[i][c]) * st.stderr_[i][c];
    const double n = double(st.mean.size());
    mean /= n;
    const double sigma = std::sqrt(var / (n * n) + p.stderr_[c] * p.stderr_[c]);
    std::printf("%s channel %d: Dermis %.5f, pbrt-v4 %.5f (%+.2f %%, %.1f sigma)\n", p.scene, c, mean, p.mean[c],
                100 * (mean / p.mean[c] - 1), (mean - p.mean[c]) / sigma);
    EXPECT_LE(std::abs(mean - p.mean[c]), kParity * p.mean[c] + 4 * sigma) << p.scene << " channel " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SpectralPbrtV4Parity, ::testing::ValuesIn(kPbrtV4Means),
                         [](const ::testing::TestParamInfo<PbrtMean>& i) {
                           std::string n = i.param.scene;
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace dermis
