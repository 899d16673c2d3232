// Spectral transport (RenderOptions::spectral) through the parser and the path tracer: each
// image against a closed form or the RGB render, within 4 standard errors per pixel.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "dermis/core/fresnel.h"
#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/spectra.h"
#include "dermis/spectral/cie_observer.h"
#include "dermis/spectral/rgb_to_spectrum.h"
#include "dermis/spectral/spectrum_at.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

std::unique_ptr<RenderScene> scene_from(const std::string& text) {
  Diagnostics diag;
  return build_render_scene(parse_scene_string(text, "test.pbrt"), diag);
}

// A sphere of `material` filling the view, under a uniform sky of radiance `sky` and `extra`.
std::string sphere_scene(const std::string& material, const std::string& sky, const std::string& extra = "") {
  return fmt::format(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 6 \"integer yresolution\" 6\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [{}]\n{}\nMaterial {}\nShape \"sphere\"\n",
      sky, extra, material);
}

// The film's colour of sRGB's white, D65 at luminance 1 (spectrum_at.h): (1, 1, 1) up to the
// tables' rounding.
RGB d65_white() {
  const CieTables& c = cie_tables();
  double X = 0, Z = 0;
  for (int i = 0; i < CieTables::kSamples; ++i) X += c.d65[i] * c.x[i], Z += c.d65[i] * c.z[i];
  const auto rgb = xyz_to_linear_srgb(X / c.d65_y, 1, Z / c.d65_y);
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

// The squared distance from the origin (the unit sphere's centre) to pixel (x, y)'s
// pixel-centre ray.
float squared_distance_to_centre(const RenderScene& sc, int x, int y) {
  const Ray ray = sc.camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
  const Vec3 o = ray.o, d = normalize(ray.d);
  const float along = -dot(o, d);
  return dot(o, o) - along * along;
}

// |mean - expected| within 4 standard errors in every pixel and channel, with `floor`
// (stated per test) for what the expectation itself is known to within.
void expect_image_equals(const testing::PixelStatistics& st, RGB expected, double floor) {
  int failures = 0;
  for (std::size_t p = 0; p < st.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double tol = 4.0 * st.stderr_[p][c] + floor;
      if (std::abs(st.mean[p][c] - expected[c]) > tol && failures++ < 5)
        ADD_FAILURE() << "pixel " << p << " channel " << c << ": " << st.mean[p][c] << " vs " << expected[c]
                      << " (tolerance " << tol << ")";
    }
  EXPECT_EQ(failures, 0);
}

TEST(SpectralRender, D65IsSrgbWhite) {
  const RGB w = d65_white();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[c], 1.0f, 2e-3f) << c;
}

// The white furnace, spectral: a white diffuse sphere under a white sky shows the sky's
// colour, D65's white, at every pixel (every bounce reflects everything at every wavelength).
TEST(SpectralRender, WhiteFurnace) {
  const auto sc = scene_from(sphere_scene("\"diffuse\" \"rgb reflectance\" [1 1 1]", "1 1 1"));
  expect_image_equals(testing::pixel_statistics(*sc, 512, 1, {}, true), d65_white(), 2e-6);
}

// A coloured convex sphere under a white sky: each pixel is one bounce off the sphere,
// whose colour under D65 is its rgb (the uplift's round trip, within 1e-3:
// spectral/rgb_to_spectrum_test.cpp).
TEST(SpectralRender, ColouredFurnaceShowsTheReflectance) {
  const RGB r(0.7f, 0.45f, 0.3f);
  const auto sc = scene_from(sphere_scene("\"diffuse\" \"rgb reflectance\" [0.7 0.45 0.3]", "1 1 1"));
  const RGB white = d65_white();
  expect_image_equals(testing::pixel_statistics(*sc, 512, 2, {}, true), r * white, 1e-3);
}

// A grey scene (a grey sphere on a grey floor, a grey sky and a grey area light: every
// spectrum flat but the lights', which are D65) renders in spectral mode as in RGB times
// D65's white, within 4 sigma of the two estimates.
TEST(SpectralRender, GreySceneRendersAsRgb) {
  const std::string text = fmt::format(
      "LookAt 0 -3 1.2  0 0 0.3  0 0 1\nCamera \"perspective\" \"float fov\" 35\n"
      "Film \"rgb\" \"integer xresolution\" 8 \"integer yresolution\" 8\n"
      "Integrator \"volpath\" \"integer maxdepth\" 20\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [0.4 0.4 0.4]\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [5 5 5]\nTranslate 1 -1 2.5\n"
      "Shape \"trianglemesh\" \"point3 P\" [-0.4 -0.4 0 0.4 -0.4 0 0.4 0.4 0 -0.4 0.4 0] \"integer indices\" [0 2 1 0 "
      "3 "
      "2]\nAttributeEnd\n"
      "Material \"diffuse\" \"rgb reflectance\" [0.6 0.6 0.6]\nTranslate 0 0 0.5\nShape \"sphere\" \"float radius\" "
      "0.5\nTranslate 0 0 -0.5\nMaterial \"diffuse\" \"rgb reflectance\" [0.3 0.3 0.3]\n"
      "Shape \"trianglemesh\" \"point3 P\" [-4 -4 0 4 -4 0 4 4 0 -4 4 0] \"integer indices\" [0 1 2 0 2 3]\n");
  const auto sc = scene_from(text);
  const auto rgb = testing::pixel_statistics(*sc, 1024, 3);
  const auto spectral = testing::pixel_statistics(*sc, 1024, 4, {}, true);
  const RGB white = d65_white();
  int failures = 0;
  double sum_rgb = 0, sum_spectral = 0, var = 0;
  for (std::size_t p = 0; p < rgb.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double a = rgb.mean[p][c] * white[c], b = spectral.mean[p][c];
      const double sigma = std::hypot(rgb.stderr_[p][c] * white[c], spectral.stderr_[p][c]);
      if (std::abs(a - b) > 4 * sigma + 1e-6 && failures++ < 5)
        ADD_FAILURE() << "pixel " << p << " channel " << c << ": RGB " << a << ", spectral " << b;
      sum_rgb += a, sum_spectral += b, var += sigma * sigma;
    }
  EXPECT_EQ(failures, 0);
  EXPECT_NEAR(sum_spectral, sum_rgb, 4 * std::sqrt(var));  // the image means: sharper
}

// A unit sphere of the medium `ink` (its MakeNamedMedium parameters) in an index-matched
// boundary, under a white sky, seen by a 6 x 6 film.
std::string absorbing_sphere_scene(const std::string& ink) {
  return "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
         "Film \"rgb\" \"integer xresolution\" 6 \"integer yresolution\" 6\n"
         "Integrator \"volpath\" \"integer maxdepth\" 100\nWorldBegin\n"
         "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
         "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" " +
         ink + "\nMaterial \"interface\"\nMediumInterface \"ink\" \"\"\nShape \"sphere\"\n";
}

// Each pixel-centre ray crosses a chord c of the unit sphere: the film records D65 x
// exp(-sigma_a(lambda) c) through the observer, summed here at every nanometre; every pixel
// within 4 sigma (the wavelengths' noise) plus 1e-4 (the sum's).
void expect_beer_lambert(const RenderScene& sc, const testing::PixelStatistics& st,
                         const std::function<double(float)>& sigma_a) {
  const CieTables& cie = cie_tables();
  int failures = 0;
  for (int y = 0; y < st.height; ++y)
    for (int x = 0; x < st.width; ++x) {
      const float d2 = squared_distance_to_centre(sc, x, y);
      const double chord = d2 < 1 ? 2 * std::sqrt(1 - d2) : 0;  // through the unit sphere
      double X = 0, Y = 0, Z = 0;
      for (int i = 0; i < CieTables::kSamples; ++i) {
        const float lambda = float(CieTables::kLambdaMin + i);
        const double v = d65_at(lambda) * std::exp(-sigma_a(lambda) * chord) / cie.y_sum;
        X += v * cie.x[i], Y += v * cie.y[i], Z += v * cie.z[i];
      }
      const auto expected = xyz_to_linear_srgb(X, Y, Z);
      const std::size_t p = std::size_t(y) * st.width + x;
      for (int c = 0; c < 3; ++c)
        if (std::abs(st.mean[p][c] - expected[std::size_t(c)]) > 4 * st.stderr_[p][c] + 1e-4 && failures++ < 5)
          ADD_FAILURE() << "pixel " << x << "," << y << " channel " << c << ": " << st.mean[p][c] << " vs "
                        << expected[std::size_t(c)] << " (chord " << chord << ")";
    }
  EXPECT_EQ(failures, 0);
}

// A purely absorbing coloured sphere in an index-matched boundary, against a white sky: each
// pixel-centre ray crosses a chord c of it, and the film records D65 x exp(-sigma_a(lambda) c)
// through the observer, sigma_a the unbounded spectrum of its rgb (as pbrt-v4 reads a
// medium's coefficients), summed here at every nanometre; within 4 sigma (the wavelengths'
// noise) plus 1e-4 (the sum's).
TEST(SpectralRender, AbsorbingSphereShowsBeerLambertOfItsSpectrum) {
  const auto sc =
      scene_from(absorbing_sphere_scene("\"rgb sigma_a\" [2 0.6 0.2] \"rgb sigma_s\" [0 0 0] \"float scale\" 1"));
  const UnboundedSpectrum spectrum = unbounded_spectrum(RgbToSpectrumTable::srgb(), RGB(2.0f, 0.6f, 0.2f));
  expect_beer_lambert(*sc, testing::pixel_statistics(*sc, 256, 5, {}, true),
                      [&](float lambda) { return double(spectrum(lambda)); });
}

// The white furnace through a scattering, non-absorbing chromatic medium (free flights
// chosen by wavelength, spectral MIS): D65's white at every pixel. 1024 samples: at 256 the
// estimator's tails made the largest of the 108 pixel-channels' |z| exceed 4 for 1 seed in
// 40; at 1024, the largest over 40 seeds was 3.5, as for normal errors.
TEST(SpectralRender, ScatteringMediumFurnace) {
  const auto sc = scene_from(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 6 \"integer yresolution\" 6\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0 0 0] \"rgb sigma_s\" [4 1 0.3] "
      "\"float scale\" 1 \"float g\" 0.3\nMaterial \"interface\"\nMediumInterface \"fog\" \"\"\nShape \"sphere\"\n");
  expect_image_equals(testing::pixel_statistics(*sc, 1024, 6, {}, true), d65_white(), 2e-6);
}

// The colour a film records for a spectrum given at every nanometre (CIE 1931, linear sRGB).
template <class Spectrum>
RGB film_colour(const Spectrum& s) {
  const CieTables& cie = cie_tables();
  double X = 0, Y = 0, Z = 0;
  for (int i = 0; i < CieTables::kSamples; ++i) {
    const double v = s(i, float(CieTables::kLambdaMin + i)) / cie.y_sum;
    X += v * cie.x[i], Y += v * cie.y[i], Z += v * cie.z[i];
  }
  const auto rgb = xyz_to_linear_srgb(X, Y, Z);
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

// A blackbody sky is its spectrum, not the spectrum of its colour: under a 2000 K sky of
// luminance 1, a saturated sphere shows the colour of planck x its reflectance's spectrum:
// per pixel within 4 sigma (+1e-4, the sums'), and the image's mean within 4 sigma of it
// while lighting by the spectrum of the sky's RGB would be beyond (checked).
TEST(SpectralRender, BlackbodyLightIsItsSpectrum) {
  const RGB r(0.05f, 0.3f, 0.9f);
  const auto sc = scene_from(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100\nWorldBegin\n"
      "LightSource \"infinite\" \"blackbody L\" [2000]\n"
      "Material \"diffuse\" \"rgb reflectance\" [0.05 0.3 0.9]\nShape \"sphere\"\n");
  const RgbSpectrum reflectance = RgbToSpectrumTable::srgb()(r);
  const CieTables& cie = cie_tables();
  auto planck = [](double l) {
    const double c = 299792458.0, h = 6.62607015e-34, kb = 1.380649e-23, m = l * 1e-9;
    return 1 / (std::pow(m, 5) * (std::exp(h * c / (m * kb * 2000)) - 1));
  };
  double sy = 0;
  for (int i = 0; i < CieTables::kSamples; ++i) sy += planck(CieTables::kLambdaMin + i) * cie.y[i];
  const double to_luminance_one = cie.y_sum / sy;
  const RGB expected = film_colour([&](int, float l) { return planck(l) * to_luminance_one * double(reflectance(l)); });
  const RGB sky_rgb = film_colour([&](int, float l) { return planck(l) * to_luminance_one; });
  const RgbSpectrum sky_uplift = RgbToSpectrumTable::srgb()(sky_rgb / (2 * sky_rgb.max()));
  const RGB via_rgb =
      film_colour([&](int, float l) { return 2 * sky_rgb.max() * sky_uplift(l) * d65_at(l) * double(reflectance(l)); });
  const auto st = testing::pixel_statistics(*sc, 4096, 7, {}, true);
  expect_image_equals(st, expected, 1e-4);
  bool told_apart = false;
  for (int c = 0; c < 3; ++c) {
    double mean = 0, var = 0;
    for (std::size_t p = 0; p < st.mean.size(); ++p)
      mean += st.mean[p][c], var += double(st.stderr_[p][c]) * st.stderr_[p][c];
    mean /= double(st.mean.size());
    const double sigma = std::sqrt(var) / double(st.mean.size());
    std::printf("channel %d: image %.5f +- %.5f, planck %.5f, via RGB %.5f\n", c, mean, sigma, expected[c], via_rgb[c]);
    EXPECT_NEAR(mean, expected[c], 4 * sigma + 1e-4);
    told_apart = told_apart || std::abs(via_rgb[c] - expected[c]) > 4 * sigma + 1e-4;
  }
  EXPECT_TRUE(told_apart) << "the test could not tell the spectrum from the spectrum of its colour";
}

// A named metal is its measured spectra: a smooth gold sphere under a white sky reflects
// D65 x Fresnel(cos theta, eta(lambda), k(lambda)) of metal-Au, at each pixel's angle.
TEST(SpectralRender, NamedMetalIsItsMeasuredSpectra) {
  const auto sc = scene_from(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
      "Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\" \"float roughness\" 0\n"
      "Shape \"sphere\"\n");
  const auto eta = named_spectrum_samples("metal-Au-eta", SpectrumType::Unbounded);
  const auto k = named_spectrum_samples("metal-Au-k", SpectrumType::Unbounded);
  const auto st = testing::pixel_statistics(*sc, 512, 8, {}, true);
  int failures = 0;
  for (int y = 0; y < st.height; ++y)
    for (int x = 0; x < st.width; ++x) {
      const float d2 = squared_distance_to_centre(*sc, x, y);
      const std::size_t p = std::size_t(y) * st.width + x;
      if (d2 >= 1) continue;                      // the sky
      const float cos_theta = std::sqrt(1 - d2);  // at the hit, the normal against -d
      const RGB expected = film_colour([&](int i, float l) {
        return d65_at(l) * fresnel_conductor(cos_theta, (*eta)[std::size_t(i)], (*k)[std::size_t(i)]);
      });
      for (int c = 0; c < 3; ++c)
        if (std::abs(st.mean[p][c] - expected[c]) > 4 * st.stderr_[p][c] + 1e-4 && failures++ < 5)
          ADD_FAILURE() << "pixel " << x << "," << y << " channel " << c << ": " << st.mean[p][c] << " vs "
                        << expected[c];
    }
  EXPECT_EQ(failures, 0);
}

// pbrt-v4's piecewise-linear spectrum of (lambda, value) pairs: zero outside its wavelengths.
double piecewise(const std::vector<double>& pairs, double l) {
  if (l < pairs.front() || l > pairs[pairs.size() - 2]) return 0;
  for (std::size_t i = 2; i < pairs.size(); i += 2)
    if (l <= pairs[i])
      return pairs[i - 1] + (pairs[i + 1] - pairs[i - 1]) * (l - pairs[i - 2]) / (pairs[i] - pairs[i - 2]);
  return pairs.back();
}

// Whether the image's mean in some channel is beyond 4 sigma of `other` (the colour a test
// would have seen had the renderer read the spectrum of a parameter's colour instead).
bool told_apart_from(const testing::PixelStatistics& st, const RGB& other) {
  for (int c = 0; c < 3; ++c) {
    double mean = 0, var = 0;
    for (std::size_t p = 0; p < st.mean.size(); ++p)
      mean += st.mean[p][c], var += double(st.stderr_[p][c]) * st.stderr_[p][c];
    const double n = double(st.mean.size());
    if (std::abs(mean / n - other[c]) > 4 * std::sqrt(var) / n + 1e-4) return true;
  }
  return false;
}

// A reflectance given as samples is its spectrum, zero outside its wavelengths as pbrt-v4's:
// a convex sphere under a sky of a flat spectrum over 430-650 nm (zero elsewhere, at
// luminance 1) shows sky x that spectrum at every pixel (within 4 sigma plus 1e-4, the
// sums'). Not what the spectrum of its colour would show (checked): under D65 the two are one
// colour, under this light they are not.
TEST(SpectralRender, ReflectanceGivenAsSamplesIsItsSpectrum) {
  const std::vector<double> pairs{400, 0.1, 470, 0.9, 540, 0.1, 610, 0.9, 680, 0.1};
  std::string text =
      sphere_scene("\"diffuse\" \"spectrum reflectance\" [400 0.1 470 0.9 540 0.1 610 0.9 680 0.1]", "1 1 1");
  const std::string white_sky = "\"rgb L\" [1 1 1]";
  text.replace(text.find(white_sky), white_sky.size(), "\"spectrum L\" [430 1 650 1]");
  const auto sc = scene_from(text);
  const CieTables& cie = cie_tables();
  double in_band_y = 0;
  for (int l = 430; l <= 650; ++l) in_band_y += cie.y[std::size_t(l - CieTables::kLambdaMin)];
  const double sky = cie.y_sum / in_band_y;  // luminance 1
  auto light = [&](float l) { return l >= 430 && l <= 650 ? sky : 0.0; };
  const RGB expected = film_colour([&](int, float l) { return light(l) * piecewise(pairs, l); });
  const RGB colour = sc->materials[0].reflectance;  // the RGB stand-in
  const RgbSpectrum uplift = RgbToSpectrumTable::srgb()(colour);
  const RGB via_rgb = film_colour([&](int, float l) { return light(l) * double(uplift(l)); });
  const auto st = testing::pixel_statistics(*sc, 512, 9, {}, true);
  expect_image_equals(st, expected, 1e-4);
  EXPECT_TRUE(told_apart_from(st, via_rgb)) << "the test cannot tell the spectrum from its colour's";
}

// A medium's sigma_a given as samples is its spectrum: a purely absorbing sphere in an
// index-matched boundary under a white sky shows D65 x exp(-sigma_a(lambda) chord) along
// each pixel-centre ray, sigma_a zero outside its wavelengths (pbrt-v4's rule), within 4
// sigma plus 1e-4.
TEST(SpectralRender, MediumGivenAsSamplesIsItsSpectrum) {
  const std::vector<double> pairs{420, 3, 500, 0.2, 580, 3, 660, 0.2};
  const auto sc = scene_from(absorbing_sphere_scene(
      "\"spectrum sigma_a\" [420 3 500 0.2 580 3 660 0.2] \"rgb sigma_s\" [0 0 0] \"float scale\" 0.5"));
  expect_beer_lambert(*sc, testing::pixel_statistics(*sc, 256, 10, {}, true),
                      [&](float lambda) { return 0.5 * piecewise(pairs, lambda); });
}

// The white furnace through a non-absorbing medium whose sigma_s is given as samples, inside
// an index-matched boundary: the free flights and the shadow rays read the same spectrum
// (render/spectral_media.h), so every pixel is D65's white within 4 sigma.
TEST(SpectralRender, MediumGivenAsSamplesKeepsTheFurnaceWhite) {
  const auto sc = scene_from(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 6 \"integer yresolution\" 6\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0 0 0] "
      "\"spectrum sigma_s\" [420 4 500 0.5 580 4 660 0.5] \"float g\" 0.3\nMaterial \"interface\"\n"
      "MediumInterface \"fog\" \"\"\nShape \"sphere\"\n");
  expect_image_equals(testing::pixel_statistics(*sc, 1024, 11, {}, true), d65_white(), 2e-6);
}

// A smooth glass of dispersive index (named glass-BK7) in the white furnace: each path keeps one
// wavelength at the glass (and so the film weighs it by three), and the sphere, which neither
// absorbs nor emits, shows D65's white at every pixel within 4 sigma.
TEST(SpectralRender, DispersiveGlassKeepsTheFurnaceWhite) {
  const auto sc = scene_from(sphere_scene("\"dielectric\" \"spectrum eta\" \"glass-BK7\"", "1 1 1"));
  ASSERT_GE(sc->materials[0].eta_data, 0);
  expect_image_equals(testing::pixel_statistics(*sc, 1024, 12, {}, true), d65_white(), 2e-6);
}

// A dispersive glass half-space over an absorbing interior, seen along its normal under a white
// sky, reflects D65 x F0(lambda) = ((n - 1) / (n + 1))^2 at each wavelength's own index n(lambda)
// (here rising from 1.3 at 360 nm to 2.2 at 830 nm), not at its mean index (checked): within
// 4 sigma plus 1e-4.
TEST(SpectralRender, DispersiveGlassReflectsTheFresnelOfEachWavelength) {
  const auto sc = scene_from(
      "LookAt 0 0 10  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 1\n"
      "Film \"rgb\" \"integer xresolution\" 2 \"integer yresolution\" 2\n"
      "Integrator \"volpath\" \"integer maxdepth\" 20\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
      "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [1000 1000 1000] "
      "\"rgb sigma_s\" [0 0 0]\nMediumInterface \"ink\" \"\"\n"
      "Material \"dielectric\" \"spectrum eta\" [360 1.3 830 2.2]\n"
      "Shape \"trianglemesh\" \"point3 P\" [-50 -50 -10  50 -50 -10  50 50 -10  -50 50 -10  -50 -50 0  50 -50 0  "
      "50 50 0  -50 50 0]\n  \"integer indices\" [0 2 1  0 3 2   4 5 6  4 6 7   0 1 5  0 5 4   1 2 6  1 6 5   2 3 7  "
      "2 7 6   3 0 4  3 4 7]\n");
  auto f0 = [](double n) { return (n - 1) * (n - 1) / ((n + 1) * (n + 1)); };
  const RGB expected = film_colour([&](int, float l) { return d65_at(l) * f0(1.3 + 0.9 * (l - 360) / 470); });
  const RGB mean_index = film_colour([&](int, float l) { return d65_at(l) * f0(sc->materials[0].eta); });
  const auto st = testing::pixel_statistics(*sc, 4096, 13, {}, true);
  expect_image_equals(st, expected, 1e-4);
  EXPECT_TRUE(told_apart_from(st, mean_index)) << "the test cannot tell dispersion from the mean index";
}

}  // namespace
}  // namespace dermis
