// The subsurface methods on spectral paths (SubsurfaceEntry::wavelengths): each reads its
// parameters at the path's wavelengths and works per wavelength. Against Chandrasekhar's
// half-space at three wavelengths, the albedo each method is made to return at each, the
// volumetric reference, and the RGB render of grey parameters: within 4 standard errors.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dermis/core/sampler.h"
#include "dermis/core/warp.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/integrator.h"
#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/render/subsurface/profile_from_params.h"
#include "dermis/scene/parser.h"
#include "dermis/spectral/spectrum_at.h"
#include "dermis/sss/halfspace/chandrasekhar.h"
#include "dermis/sss/profiles/quadrature.h"
#include "support/lit_sphere_scene.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

// Three wavelengths, one in each third of the visible range.
SampledWavelengths three_wavelengths() {
  SampledWavelengths w;
  w.lambda = {450, 550, 640};
  w.pdf = {1, 1, 1};
  return w;
}

// A box 1000 x 1000 x 100 whose top face is z = 0, under a white sky ("rgb L" [1 1 1]: D65
// at luminance 1 on a spectral path).
std::string slab_scene(const std::string& material) {
  return R"(LookAt 0 0 10  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 2 "integer yresolution" 2
Integrator "volpath" "integer maxdepth" 100000
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
)" + material +
         R"(
Shape "trianglemesh" "point3 P" [-500 -500 -100  500 -500 -100  500 500 -100  -500 500 -100
                                  -500 -500 0  500 -500 0  500 500 0  -500 500 0]
  "integer indices" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  2 7 6   3 0 4  3 4 7]
)";
}

struct PerWavelength {
  RGB mean, stderr_;
};

// The radiance leaving the centre of the slab's top face at the wavelengths w, divided by
// the sky's there: over `views` cosine-distributed directions (hemispherical = true: the
// slab's albedo under diffuse light), or straight down. Independent samples.
PerWavelength slab_reflectance(const std::string& material, SampledWavelengths& w, int views, bool hemispherical,
                               uint64_t seed = 91) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(slab_scene(material)), diag);
  const RGB sky = illuminant_at(RGB(1), w);
  PathStart start;
  start.wavelengths = &w;
  double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
  PathCounters counters;
  for (int i = 0; i < views; ++i) {
    Sampler rng(SamplerKind::Independent, seed, uint64_t(i), 0);
    const Vec3 d = hemispherical ? sample_cosine_hemisphere({rng.uniform(), rng.uniform()}) : Vec3(0, 0, 1);
    const RGB L = trace_path(*sc, Ray{d * 1.0f, -d}, -1, rng, counters, start);
    for (int c = 0; c < 3; ++c) {
      const double v = L[c] / sky[c];
      s[c] += v;
      s2[c] += v * v;
    }
  }
  PerWavelength out;
  for (int c = 0; c < 3; ++c) {
    const double m = s[c] / views;
    out.mean[c] = float(m);
    out.stderr_[c] = float(std::sqrt(std::max(0.0, s2[c] / views - m * m) / views));
  }
  return out;
}

// Each wavelength within 4 standard errors of `expected`, and `rgb` (what the method would
// return had it read its RGB parameters) told apart from it in one wavelength at least.
void expect_per_wavelength(const PerWavelength& got, const RGB& expected, const RGB& rgb) {
  bool told_apart = false;
  for (int c = 0; c < 3; ++c) {
    std::printf("wavelength %d: %.5f +- %.5f, expected %.5f (its RGB's %.5f)\n", c, got.mean[c], got.stderr_[c],
                expected[c], rgb[c]);
    EXPECT_NEAR(got.mean[c], expected[c], 4 * got.stderr_[c]) << "wavelength " << c;
    told_apart = told_apart || std::abs(rgb[c] - expected[c]) > 8 * got.stderr_[c];
  }
  EXPECT_TRUE(told_apart) << "the test cannot tell the wavelengths' parameters from the RGB ones";
}

// The random walk with the index-matched boundary and isotropic scattering, the
// coefficients given in RGB and uplifted: at each wavelength the half-space's albedo for its
// single-scattering albedo sigma_s / sigma_t there, Chandrasekhar's
// R = 1 - 2 sqrt(1 - alpha) int H(mu) mu dmu (METHODS.md sec. 6).
TEST(SpectralSubsurface, WalkAtThreeWavelengthsIsChandrasekharsHalfSpace) {
  const RGB sigma_a(0.02f, 0.12f, 0.5f), sigma_s(1, 1, 1);
  const std::string material =
      "Material \"subsurface\" \"rgb sigma_a\" [0.02 0.12 0.5] \"rgb sigma_s\" [1 1 1] "
      "\"float eta\" 1 \"float g\" 0 \"string method\" \"randomwalk\" \"string boundary\" "
      "\"matched\"";
  SampledWavelengths w = three_wavelengths();
  const RGB sa = unbounded_at(sigma_a, w), ss = unbounded_at(sigma_s, w);
  RGB expected, rgb;
  for (int c = 0; c < 3; ++c) {
    expected[c] = float(sss::halfspace_albedo_diffuse(sss::HFunction(ss[c] / (sa[c] + ss[c]))));
    rgb[c] = float(sss::halfspace_albedo_diffuse(sss::HFunction(sigma_s[c] / (sigma_a[c] + sigma_s[c]))));
  }
  expect_per_wavelength(slab_reflectance(material, w, 20000, true), expected, rgb);
}

// The mean of 2 mu F(mu) over mu: the Fresnel reflectance under diffuse light.
double diffuse_fresnel(double eta) {
  return sss::integrate([&](double mu) { return 2 * mu * fresnel_dielectric(float(mu), float(eta)); }, 0, 1);
}

// The walk behind a dielectric boundary, given (reflectance, mfp): its exact albedo
// inversion, made per wavelength, returns at each wavelength the reflectance spectrum's
// value there: F + (1 - F) A(lambda) under diffuse light.
TEST(SpectralSubsurface, WalkInvertsTheReflectanceAtEachWavelength) {
  const RGB A(0.8f, 0.45f, 0.2f);
  const std::string material =
      "Material \"subsurface\" \"rgb reflectance\" [0.8 0.45 0.2] \"rgb mfp\" [1 0.5 0.25] \"float eta\" 1.4 "
      "\"string method\" \"randomwalk\" \"string boundary\" \"dielectric\"";
  SampledWavelengths w = three_wavelengths();
  const RGB A_w = reflectance_at(A, w);
  const float F = float(diffuse_fresnel(1.4));
  expect_per_wavelength(slab_reflectance(material, w, 3000, true), RGB(F) + A_w * (1 - F), RGB(F) + A * (1 - F));
}

// pbrt-v4's piecewise-linear spectrum of (lambda, value) pairs (here covering 360-830 nm).
double piecewise(const std::vector<double>& pairs, double l) {
  for (std::size_t i = 2; i < pairs.size(); i += 2)
    if (l <= pairs[i])
      return pairs[i - 1] + (pairs[i + 1] - pairs[i - 1]) * (l - pairs[i - 2]) / (pairs[i] - pairs[i - 2]);
  return pairs.back();
}

// The subsurface parameters of `material` as parsed (the scene is not built: slab_reflectance
// builds it).
SubsurfaceParams parsed_params(const std::string& material) {
  return parse_scene_string(slab_scene(material)).materials.at(0).subsurface;
}

// A subsurface material's coefficients given as samples are their own spectra: the matched
// walk's half-space albedo at each wavelength is Chandrasekhar's for sigma_a(lambda) of the
// samples (times scale), not for the spectrum of their colour (checked).
TEST(SpectralSubsurface, WalkReadsCoefficientsGivenAsSpectra) {
  const std::vector<double> pairs{360, 0.6, 500, 0.02, 600, 0.6, 700, 0.02, 830, 0.6};
  const std::string material =
      "Material \"subsurface\" \"spectrum sigma_a\" [360 0.6 500 0.02 600 0.6 700 0.02 830 0.6] "
      "\"rgb sigma_s\" [1 1 1] \"float scale\" 2 \"float eta\" 1 \"float g\" 0 \"string method\" \"randomwalk\" "
      "\"string boundary\" \"matched\"";
  SampledWavelengths w = three_wavelengths();
  const SubsurfaceParams params = parsed_params(material);
  const RGB ss = unbounded_at(RGB(2), w), colour = unbounded_at(*params.sigma_a, w);
  RGB expected, rgb;
  for (int c = 0; c < 3; ++c) {
    const double sa = 2 * piecewise(pairs, w.lambda[std::size_t(c)]);
    expected[c] = float(sss::halfspace_albedo_diffuse(sss::HFunction(ss[c] / (sa + ss[c]))));
    rgb[c] = float(sss::halfspace_albedo_diffuse(sss::HFunction(ss[c] / (colour[c] + ss[c]))));
  }
  expect_per_wavelength(slab_reflectance(material, w, 20000, true), expected, rgb);
}

// A reflectance given as samples is its own spectrum: the walk behind a dielectric returns
// F + (1 - F) A(lambda) of the samples at each wavelength, not of its colour's spectrum.
TEST(SpectralSubsurface, WalkInvertsAReflectanceGivenAsASpectrum) {
  const std::vector<double> pairs{360, 0.8, 470, 0.2, 580, 0.8, 690, 0.2, 830, 0.8};
  const std::string material =
      "Material \"subsurface\" \"spectrum reflectance\" [360 0.8 470 0.2 580 0.8 690 0.2 830 0.8] "
      "\"rgb mfp\" [1 0.5 0.25] \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" "
      "\"dielectric\"";
  SampledWavelengths w = three_wavelengths();
  const SubsurfaceParams params = parsed_params(material);
  const RGB colour = reflectance_at(*params.reflectance, w);
  RGB A;
  for (int c = 0; c < 3; ++c) A[c] = float(piecewise(pairs, w.lambda[std::size_t(c)]));
  const float F = float(diffuse_fresnel(1.4));
  expect_per_wavelength(slab_reflectance(material, w, 3000, true), RGB(F) + A * (1 - F), RGB(F) + colour * (1 - F));
}

// The disk probes with the Christensen-Burley profile, seen straight down: F(1) plus
// (1 - F(1)) times the energy of the profile made from the parameters at each wavelength,
// within the probes' reach (subsurface_slab_test.cpp's invariant, per wavelength). The
// profile's albedo at a wavelength is the reflectance spectrum's value there.
TEST(SpectralSubsurface, DiskProbesUseTheProfileOfEachWavelength) {
  const std::string material =
      "Material \"subsurface\" \"rgb reflectance\" [0.8 0.45 0.2] \"rgb mfp\" [0.05 0.03 0.02] \"float eta\" 1.33 "
      "\"string method\" \"disk\" \"string profile\" \"burley\"";
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(slab_scene(material)), diag);
  const ProbeMethod& m = std::get<ProbeMethod>(sc->subsurface.at(0)->method);
  SampledWavelengths w = three_wavelengths();
  const sss::ProfileRGB at_w = make_profile(
      sc->subsurface_params[0], medium_at_wavelengths(sc->subsurface_params[0], medium_at(sc->subsurface_params[0]), w),
      profile_table(sc->subsurface_params[0]));
  const float F = fresnel_dielectric(1.0f, 1.33f);
  const double reach = m.max_radius(at_w);
  ASSERT_LT(reach, 100);  // the probes stay on the top face
  RGB expected, rgb;
  for (int c = 0; c < 3; ++c) {
    auto energy = [&](const sss::RadialProfile& p) {
      return sss::integrate([&](double r) { return p.eval(r) * 2 * kPiD * r; }, 0, reach);
    };
    expected[c] = float(F + (1 - F) * energy(at_w.channel[c]));
    rgb[c] = float(F + (1 - F) * energy(m.profile().channel[c]));
  }
  expect_per_wavelength(slab_reflectance(material, w, 20000, false), expected, rgb);
}

std::unique_ptr<RenderScene> scene_from(const std::string& text) {
  Diagnostics diag;
  return build_render_scene(parse_scene_string(text, "test.pbrt"), diag);
}

// The walk behind a dielectric boundary and the volumetric reference of the same material
// (a medium inside a dielectric, its (reflectance, mfp) inverted per wavelength too), both
// spectral: region means within 4 standard errors of the difference.
TEST(SpectralSubsurface, WalkEqualsTheVolumetricReference) {
  const std::string header = testing::lit_sphere_header(12);
  const std::string params =
      "\"rgb reflectance\" [0.85 0.5 0.25] \"rgb mfp\" [0.6 0.3 0.15] \"float eta\" 1.4 \"float g\" 0.2";
  const auto walk =
      scene_from(header + "Material \"subsurface\" " + params +
                 " \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\"\nShape \"sphere\"\n");
  const auto volume = scene_from(header + "Material \"subsurface\" " + params +
                                 " \"string method\" \"volumetric\"\nShape \"sphere\"\n");
  testing::expect_same_region_means(testing::pixel_statistics(*walk, 96, 31, {}, true),
                                    testing::pixel_statistics(*volume, 96, 32, {}, true), 4, 4);
}

// Grey parameters uplift to flat spectra: a spectral render of a grey subsurface object under
// a grey sky is its RGB render, for the walk and the disk probes, within 4 standard errors.
TEST(SpectralSubsurface, GreyParametersRenderAsRgb) {
  for (const char* method : {"randomwalk", "disk"}) {
    SCOPED_TRACE(method);
    const std::string text = fmt::format(
        "LookAt 0 -4 1.5  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" 34\n"
        "Film \"rgb\" \"integer xresolution\" 10 \"integer yresolution\" 10\n"
        "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [0.7 0.7 0.7]\n"
        "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [5 5 5]\nTranslate 2 -2 3\n"
        "Shape \"sphere\" \"float radius\" 0.5\nAttributeEnd\n"
        "Material \"subsurface\" \"rgb reflectance\" [0.6 0.6 0.6] \"rgb mfp\" [0.3 0.3 0.3] \"float eta\" 1.33 "
        "\"string method\" \"{}\"\nShape \"sphere\"\n",
        method);
    const auto sc = scene_from(text);
    testing::expect_same_region_means(testing::pixel_statistics(*sc, 96, 41, {}, true),
                                      testing::pixel_statistics(*sc, 96, 42), 5, 5);
  }
}

// What stays RGB in a spectral render is named: the point cloud; the walk and the probes
// are spectral.
TEST(SpectralSubsurface, LimitationsNameThePointCloudAlone) {
  const std::string header = testing::lit_sphere_header(4);
  const std::string params = "\"rgb reflectance\" [0.8 0.6 0.5] \"rgb mfp\" [1 1 1]";
  for (const char* method : {"randomwalk", "disk", "sphere-lines", "volumetric"})
    EXPECT_EQ(spectral_limitations(*scene_from(header + "Material \"subsurface\" " + params + " \"string method\" \"" +
                                               method + "\"\nShape \"sphere\"\n")),
              "")
        << method;
  const auto cloud = scene_from(header + "Material \"subsurface\" " + params +
                                " \"string method\" \"pointcloud\"\nShape \"sphere\"\n");
  EXPECT_NE(spectral_limitations(*cloud).find("point-cloud"), std::string::npos);
}

}  // namespace
}  // namespace dermis
