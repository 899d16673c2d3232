// The random-walk subsurface method against the foundation's volumetric path tracer:
// with the `dielectric` boundary it is the same physics as a homogeneous medium inside
// a dielectric, with `matched` the same as a medium inside an index-matched interface.
// Region means agree within 4 standard errors (of the difference).
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/render/render_scene.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

const char* kHeader = R"(LookAt 0 -4 1.5  0 0 0  0 0 1
Camera "perspective" "float fov" 34
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [0.6 0.7 0.8]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [6 6 6]
  Translate 2 -2 3
  Shape "sphere" "float radius" 0.5
AttributeEnd
)";
const char* kCoefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";

struct Regions {
  std::vector<RGB> mean, var;  // region means and variances of those means
};

// 4 x 4 regions of 4 x 4 pixels each.
Regions regions(const testing::PixelStatistics& st) {
  Regions r;
  r.mean.assign(16, RGB(0));
  r.var.assign(16, RGB(0));
  for (int y = 0; y < st.height; ++y)
    for (int x = 0; x < st.width; ++x) {
      int k = (y / 4) * 4 + x / 4;
      const std::size_t p = std::size_t(y) * st.width + x;
      r.mean[k] += st.mean[p] / 16.0f;
      r.var[k] += st.stderr_[p] * st.stderr_[p] / 256.0f;
    }
  return r;
}

void expect_same_picture(const std::string& a, const std::string& b, int spp) {
  Diagnostics diag;
  auto sa = build_render_scene(parse_scene_string(a), diag);
  auto sb = build_render_scene(parse_scene_string(b), diag);
  Regions ra = regions(testing::pixel_statistics(*sa, spp, 31)), rb = regions(testing::pixel_statistics(*sb, spp, 32));
  int failures = 0;
  for (int k = 0; k < 16; ++k)
    for (int c = 0; c < 3; ++c) {
      double sigma = std::sqrt(double(ra.var[k][c]) + rb.var[k][c]);
      if (std::abs(ra.mean[k][c] - rb.mean[k][c]) > 4 * sigma && failures++ < 6)
        ADD_FAILURE() << "region " << k << " channel " << c << ": " << ra.mean[k][c] << " vs " << rb.mean[k][c]
                      << " (4 sigma = " << 4 * sigma << ")";
    }
  EXPECT_EQ(failures, 0);
}

TEST(SubsurfaceRandomWalk, DielectricBoundaryEqualsAMediumInsideADielectric) {
  for (const char* sampling : {"classical", "mis"}) {
    SCOPED_TRACE(sampling);
    std::string walk = std::string(kHeader) + "Material \"subsurface\" " + kCoefficients +
                       " \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\" "
                       "\"string walksampling\" \"" + sampling + "\"\nShape \"sphere\"\n";
    std::string volume = std::string(kHeader) + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                         "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\nShape \"sphere\"\n";
    expect_same_picture(walk, volume, 96);
  }
}

TEST(SubsurfaceRandomWalk, MatchedBoundaryEqualsAMediumInsideAnInterface) {
  std::string walk = std::string(kHeader) + "Material \"subsurface\" " + kCoefficients +
                     " \"string method\" \"randomwalk\" \"string boundary\" \"matched\"\nShape \"sphere\"\n";
  std::string volume = std::string(kHeader) + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kCoefficients +
                       "\nMediumInterface \"m\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  // The walk leaves straight through the matched boundary without next-event estimation
  // at its exit; the medium inside an interface does next-event estimation inside:
  // different estimators of the same image.
  expect_same_picture(walk, volume, 96);
}

}  // namespace
}  // namespace dermis
