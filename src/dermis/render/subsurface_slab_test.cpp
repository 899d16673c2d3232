// The flat-slab invariant (METHODS.md sec. 0 and 6): a thick flat slab under uniform
// light returns, for every profile method, the specular reflection F plus (1 - F) times
// the profile's energy that the method can reach: within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>

#include "dermis/materials/fresnel.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/sss/profiles/quadrature.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

// A box whose top face is z = 0, w wide and w/4 thick, seen straight down through a
// narrow camera: with w = 20 probe radii no probe reaches its sides or bottom.
std::string slab_scene(const std::string& material, double w) {
  auto f = [w](double x) { return std::to_string(x * w); };
  std::string top = f(0.5), bottom = f(-0.25), lo = f(-0.5);
  return R"(LookAt 0 0 50  0 0 0  0 1 0
Camera "perspective" "float fov" 2
Film "rgb" "integer xresolution" 3 "integer yresolution" 3
Integrator "volpath" "integer maxdepth" 50
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)" + material +
         R"(
Shape "trianglemesh" "point3 P" [)" +
         lo + " " + lo + " " + bottom + "  " + top + " " + lo + " " + bottom + "  " + top + " " + top + " " + bottom +
         "  " + lo + " " + top + " " + bottom + "  " + lo + " " + lo + " 0  " + top + " " + lo + " 0  " + top + " " +
         top + " 0  " + lo + " " + top + R"( 0]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
}

// Energy of channel c of the method's profile within `radius` (Gauss-Kronrod).
double energy_within(const sss::RadialProfile& p, double radius) {
  return sss::integrate([&](double r) { return p.eval(r) * 2 * kPiD * r; }, 0, radius);
}

struct SlabCase {
  const char* method;
  const char* profile;
};

class FlatSlab : public ::testing::TestWithParam<SlabCase> {};

TEST_P(FlatSlab, ReturnsFresnelPlusTransmittedAlbedo) {
  const SlabCase c = GetParam();
  std::string material =
      std::string("Material \"subsurface\" \"rgb reflectance\" [0.8 0.5 0.25] \"rgb mfp\" [1.0 0.6 0.3] ") +
      "\"float eta\" 1.33 \"string method\" \"" + c.method + "\" \"string profile\" \"" + c.profile + "\"";
  Diagnostics diag;
  auto probe = build_render_scene(parse_scene_string(slab_scene(material, 1)), diag);
  ASSERT_EQ(probe->subsurface.size(), 1u);
  const double radius = std::get<ProbeMethod>(probe->subsurface[0]->method).max_radius();
  auto sc = build_render_scene(parse_scene_string(slab_scene(material, std::max(100.0, 20 * radius))), diag);
  const ProbeMethod& m = std::get<ProbeMethod>(sc->subsurface[0]->method);
  const float F = fresnel_dielectric(1.0f, 1.33f);
  RGB expected;
  for (int ch = 0; ch < 3; ++ch) {
    double e = std::string(c.method) == "sphere-lines-retry" ? m.lines()->fallback_weight(ch)
                                                             : energy_within(m.profile().channel[ch], radius);
    expected[ch] = float(F + (1 - F) * e);
  }
  auto st = testing::pixel_statistics(*sc, 4000, 17);
  for (std::size_t p = 0; p < st.mean.size(); ++p)
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(st.mean[p][ch], expected[ch], 4 * st.stderr_[p][ch])
          << c.method << "/" << c.profile << " pixel " << p << " channel " << ch;
}

std::vector<SlabCase> every_method_and_profile() {
  std::vector<SlabCase> cases;
  for (const char* method : {"disk", "disk-single-axis", "sphere-lines", "sphere-lines-retry"})
    for (const char* profile : {"burley", "burley-dmfp", "dipole", "gaussian", "cubic", "skin6", "tabulated"})
      cases.push_back({method, profile});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Methods, FlatSlab, ::testing::ValuesIn(every_method_and_profile()),
                         [](const ::testing::TestParamInfo<SlabCase>& i) {
                           std::string n = std::string(i.param.method) + "_" + i.param.profile;
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace dermis

#include <cstring>

#include "dermis/render/renderer.h"

namespace dermis {
namespace {

// Two instances of one subsurface object and a second object: every method renders
// them, and the same seed gives the same image with 1 and 2 threads.
TEST(SubsurfaceScenes, InstancesAndDeterminismForEveryMethod) {
  for (const char* method : {"disk", "sphere-lines", "sphere-lines-retry", "randomwalk"}) {
    SCOPED_TRACE(method);
    std::string scene = std::string(R"(LookAt 0 -6 2  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 24 "integer yresolution" 16
Integrator "volpath" "integer maxdepth" 64
WorldBegin
LightSource "infinite" "rgb L" [0.4 0.4 0.5]
LightSource "point" "rgb I" [20 20 20] "point3 from" [2 -3 4]
ObjectBegin "blob"
  Material "subsurface" "rgb reflectance" [0.8 0.6 0.4] "rgb mfp" [0.3 0.2 0.1] "string method" ")") +
                        method + R"("
  Shape "sphere" "float radius" 0.8
ObjectEnd
AttributeBegin Translate -1 0 0 ObjectInstance "blob" AttributeEnd
AttributeBegin Translate 1 0 0 Scale 0.7 0.7 0.7 ObjectInstance "blob" AttributeEnd
AttributeBegin
  Translate 0 1.5 0
  Material "subsurface" "rgb reflectance" [0.5 0.7 0.9] "rgb mfp" [0.2 0.2 0.2] "string method" ")" +
                        method + R"("
  Shape "sphere" "float radius" 0.6
AttributeEnd
)";
    Diagnostics diag;
    auto sc = build_render_scene(parse_scene_string(scene), diag);
    RenderOptions o;
    o.spp = 4;
    o.seed = 3;
    o.threads = 1;
    RenderResult a = render_image(*sc, o);
    o.threads = 2;
    RenderResult b = render_image(*sc, o);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)));
    EXPECT_EQ(a.nonfinite, 0u);
    // Both instances are lit: the pixels at their centres are not black.
    auto at = [&](int x, int y) { return a.rgb[3 * (std::size_t(y) * 24 + x)]; };
    EXPECT_GT(at(8, 9), 0.0f);
    EXPECT_GT(at(16, 9), 0.0f);
  }
}

}  // namespace
}  // namespace dermis
