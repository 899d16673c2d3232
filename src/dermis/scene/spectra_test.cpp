// Spectra to RGB: named spectra, sampled spectra, spectrum files and blackbodies, checked
// against closed forms and published colorimetric values rather than against themselves.
#include "dermis/scene/spectra.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"
#include "dermis/spectral/named_spectra_data.h"

namespace dermis {
namespace {

using test::has_warning;
using test::parse_world;
using test::TempDir;

void expect_rgb(RGB a, RGB b, float tol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "channel " << i;
}

// Linear sRGB to CIE XYZ: IEC 61966-2-1:1999, eq. (F.8) (the inverse of the conversion under test).
void srgb_to_xyz(RGB c, double& X, double& Y, double& Z) {
  X = 0.4124564 * c[0] + 0.3575761 * c[1] + 0.1804375 * c[2];
  Y = 0.2126729 * c[0] + 0.7151522 * c[1] + 0.0721750 * c[2];
  Z = 0.0193339 * c[0] + 0.1191920 * c[1] + 0.9503041 * c[2];
}

const NamedSpectrumTable& table(const std::string& name) {
  for (const NamedSpectrumTable& t : named_spectrum_tables())
    if (name == t.name) return t;
  ADD_FAILURE() << "no table " << name;
  return named_spectrum_tables()[0];
}

double interpolate(std::span<const double> pairs, double x) {
  if (x <= pairs[0]) return pairs[1];
  for (size_t i = 2; i + 1 < pairs.size(); i += 2)
    if (x <= pairs[i])
      return pairs[i - 1] + (x - pairs[i - 2]) / (pairs[i] - pairs[i - 2]) * (pairs[i + 1] - pairs[i - 1]);
  return pairs[pairs.size() - 1];
}

TEST(Spectra, ConstantReflectanceIsGrey) {
  // A constant reflectance c looks grey under D65, the white of sRGB: RGB (c, c, c). The
  // tolerance, 5e-4 relative, covers D65's chromaticity from the CIE tables (x = 0.31272,
  // y = 0.32903) against sRGB's rounded white point (0.3127, 0.3290).
  for (double c : {0.25, 1.0, 3.0})
    expect_rgb(spectrum_rgb(std::vector<double>{300, 900}, std::vector<double>{c, c}, SpectrumType::Unbounded),
               RGB(float(c)), float(5e-4 * c));
}

TEST(Spectra, SampledSpectraAreLinearAndZeroOutsideTheirRange) {
  const std::vector<double> l{400, 500, 600, 700}, a{0.1, 0.5, 0.2, 0.9}, b{0.3, 0.1, 0.4, 0.2},
      sum{0.4, 0.6, 0.6, 1.1};
  const RGB ra = spectrum_rgb(l, a, SpectrumType::Unbounded), rb = spectrum_rgb(l, b, SpectrumType::Unbounded);
  expect_rgb(spectrum_rgb(l, sum, SpectrumType::Unbounded), ra + rb, 1e-5f);
  // Beyond 830 nm the observer sees nothing; pbrt-v4's sampled spectra are zero outside their range.
  expect_rgb(spectrum_rgb(std::vector<double>{900, 1000}, std::vector<double>{1, 1}, SpectrumType::Unbounded), RGB(0),
             0);
  // A named table keeps its end values instead (pbrt-v4's named spectra are extended).
  EXPECT_GT(spectrum_rgb(std::vector<double>{900, 1000}, std::vector<double>{1, 1}, SpectrumType::Unbounded,
                         SpectrumEnds::Extend)
                .g(),
            0.99f);
}

TEST(Spectra, NamedIlluminantsHaveTheirPublishedChromaticities) {
  // CIE 015:2004, Tables T.3 and T.8 (2-degree observer): chromaticity of each illuminant;
  // ACES D60: SMPTE ST 2065-1 white (0.32168, 0.33767). Tolerance 5e-4: the CIE sums the 5 nm
  // tables, Dermis integrates their linear interpolant at 1 nm (the fluorescent lines differ most).
  struct Published {
    const char* name;
    double x, y;
  };
  for (const Published& p : {Published{"stdillum-A", 0.44757, 0.40745}, Published{"stdillum-D50", 0.34567, 0.35850},
                             Published{"stdillum-D65", 0.31271, 0.32902}, Published{"stdillum-F1", 0.31310, 0.33727},
                             Published{"stdillum-F2", 0.37208, 0.37529}, Published{"stdillum-F4", 0.44018, 0.40329},
                             Published{"stdillum-F7", 0.31292, 0.32933}, Published{"stdillum-F11", 0.38052, 0.37713},
                             Published{"illum-acesD60", 0.32168, 0.33767}}) {
    const RGB c = *named_spectrum_rgb(p.name, SpectrumType::Illuminant);
    double X, Y, Z;
    srgb_to_xyz(c, X, Y, Z);
    EXPECT_NEAR(X / (X + Y + Z), p.x, 5e-4) << p.name;
    EXPECT_NEAR(Y / (X + Y + Z), p.y, 5e-4) << p.name;
    EXPECT_NEAR(Y, 1.0, 1e-4) << p.name << ": a light spectrum is normalized to luminance 1";
  }
  // D65 is the white of sRGB.
  expect_rgb(*named_spectrum_rgb("stdillum-D65", SpectrumType::Illuminant), RGB(1), 5e-4f);
}

TEST(Spectra, LightSpectraAreNormalizedToLuminanceOne) {
  // pbrt-v4 divides a light's spectrum by its photometric power, so a sampled emission
  // spectrum sets only the colour. The equal-energy spectrum E has X = Y = Z; at Y = 1 its
  // sRGB is the row sums of the XYZ -> sRGB matrix (IEC 61966-2-1): (1.20478, 0.94830, 0.90884).
  SceneDesc s = parse_world(
      "LightSource \"point\" \"spectrum I\" [300 2 800 2]\n"
      "LightSource \"point\" \"spectrum I\" [300 7 800 7] \"float scale\" 3\n");
  expect_rgb(s.lights[0].spectrum, RGB(1.20478f, 0.94830f, 0.90884f), 1e-3f);
  expect_rgb(s.lights[1].spectrum, s.lights[0].spectrum, 1e-6f);
  EXPECT_FLOAT_EQ(s.lights[1].scale, 3);
  EXPECT_TRUE(has_warning(s,
                          "test.pbrt:2:21: warning: sampled spectrum 'I' reduced to RGB (its chromaticity at "
                          "luminance 1"));
}

TEST(Spectra, BlackbodyColourOrderAndLuminance) {
  RGB warm = blackbody_rgb(2700), d65ish = blackbody_rgb(6504), cool = blackbody_rgb(12000);
  for (RGB c : {warm, d65ish, cool}) EXPECT_NEAR(c.luminance(), 1.0f, 2e-3f);  // normalized to Y = 1
  EXPECT_GT(warm.r(), warm.g());
  EXPECT_GT(warm.g(), warm.b());
  EXPECT_LT(cool.r(), cool.b());
  // A 6504 K blackbody is close to (not exactly) the D65 white: within 10% per channel.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(d65ish[i], 1.0f, 0.1f) << i;
  // Illuminant A is a 2856 K Planckian radiator (CIE 015:2004): the same colour.
  expect_rgb(blackbody_rgb(2856), *named_spectrum_rgb("stdillum-A", SpectrumType::Illuminant), 5e-3f);
}

TEST(Spectra, NamedMetalsFollowTheirData) {
  // Gold and copper: low index in the red, high in the blue; every metal's extinction grows
  // towards the red.
  for (const char* n : {"metal-Au-eta", "metal-Cu-eta", "metal-CuZn-eta"}) {
    const RGB c = *named_spectrum_rgb(n);
    EXPECT_LT(c.r(), c.g()) << n;
    EXPECT_LT(c.g(), c.b()) << n;
  }
  for (const char* n : {"metal-Ag-k", "metal-Al-k", "metal-Au-k", "metal-Cu-k", "metal-CuZn-k"}) {
    const RGB c = *named_spectrum_rgb(n);
    EXPECT_GT(c.r(), c.g()) << n;
    EXPECT_GT(c.g(), c.b()) << n;
  }
  // The luminance Y of a reflectance-like spectrum is its mean weighted by D65 * y-bar.
  // Computed here independently, at the nodes of the 5 nm CIE table; the two quadratures of
  // the same piecewise-linear data differ by < 1e-3 relative.
  const auto& d65 = table("stdillum-D65").pairs;
  for (const char* n : {"metal-Ag-eta", "metal-Ag-k", "metal-Al-eta", "metal-Al-k", "metal-Au-eta", "metal-Au-k",
                        "metal-Cu-eta", "metal-Cu-k", "metal-CuZn-eta", "metal-CuZn-k", "glass-BK7"}) {
    double num = 0, den = 0;
    for (const CieObserverSample& o : cie_1931_observer()) {
      const double w = interpolate(d65, o.lambda) * o.y;
      num += w * interpolate(table(n).pairs, o.lambda);
      den += w;
    }
    double X, Y, Z;
    srgb_to_xyz(*named_spectrum_rgb(n), X, Y, Z);
    EXPECT_NEAR(Y, num / den, 1e-3 * num / den) << n;
  }
}

TEST(Spectra, NamedGlassesMatchSchottIndices) {
  // The tables against Schott's catalogue n_d (587.56 nm), an independent source:
  // BK7 1.51680, BAF10 1.67003, FK51A 1.48656, LASF9 1.85025, SF5 1.67270, SF10 1.72825,
  // SF11 1.78472 (pbrt-v4 names the SF glasses "glass-F5/F10/F11"). 2e-4: interpolation
  // between nodes ~20 nm apart.
  struct Glass {
    const char* name;
    double nd;
  };
  for (const Glass& g : {Glass{"glass-BK7", 1.51680}, Glass{"glass-BAF10", 1.67003}, Glass{"glass-FK51A", 1.48656},
                         Glass{"glass-LASF9", 1.85025}, Glass{"glass-F5", 1.67270}, Glass{"glass-F10", 1.72825},
                         Glass{"glass-F11", 1.78472}}) {
    EXPECT_NEAR(interpolate(table(g.name).pairs, 587.56), g.nd, 2e-4) << g.name;
    // The scalar index Dermis uses: the mean over 400-700 nm, between the index at both ends.
    const float ior = *named_glass_ior(g.name);
    EXPECT_LT(ior, interpolate(table(g.name).pairs, 400)) << g.name;
    EXPECT_GT(ior, interpolate(table(g.name).pairs, 700)) << g.name;
  }
  EXPECT_NEAR(*named_glass_ior("glass-BK7"), 1.5196f, 1e-4f);  // as before this change
  EXPECT_FALSE(named_glass_ior("metal-Au-eta").has_value());
}

TEST(Spectra, EveryNameOfPbrtV4IsKnown) {
  // pbrt-v4's src/pbrt/util/spectrum.cpp, Spectra::Init: 37 spectra with data, 17 cameras x 3.
  const char* names[] = {"glass-BK7",      "glass-BAF10",  "glass-FK51A",   "glass-LASF9",  "glass-F5",
                         "glass-F10",      "glass-F11",    "metal-Ag-eta",  "metal-Ag-k",   "metal-Al-eta",
                         "metal-Al-k",     "metal-Au-eta", "metal-Au-k",    "metal-Cu-eta", "metal-Cu-k",
                         "metal-CuZn-eta", "metal-CuZn-k", "metal-MgO-eta", "metal-MgO-k",  "metal-TiO2-eta",
                         "metal-TiO2-k",   "stdillum-A",   "stdillum-D50",  "stdillum-D65", "stdillum-F1",
                         "stdillum-F2",    "stdillum-F3",  "stdillum-F4",   "stdillum-F5",  "stdillum-F6",
                         "stdillum-F7",    "stdillum-F8",  "stdillum-F9",   "stdillum-F10", "stdillum-F11",
                         "stdillum-F12",   "illum-acesD60"};
  EXPECT_EQ(named_spectrum_tables().size(), std::size(names));
  for (const char* n : names)
    for (SpectrumType t : {SpectrumType::Unbounded, SpectrumType::Illuminant}) {
      auto c = named_spectrum_rgb(n, t);
      ASSERT_TRUE(c.has_value()) << n;
      EXPECT_TRUE(c->is_finite() && c->r() >= 0 && c->g() >= 0 && c->b() >= 0) << n;
    }
  for (const char* n :
       {"canon_eos_100d_r", "canon_eos_5d_mkiv_g", "hasselblad_l1d_20c_b", "nikon_d850_r", "sony_ilce_9_b"})
    EXPECT_TRUE(is_camera_sensor_spectrum(n)) << n;
  EXPECT_EQ(camera_sensor_names().size(), 17u);
  EXPECT_FALSE(named_spectrum_rgb("metal-Fe-eta").has_value());
  EXPECT_FALSE(is_camera_sensor_spectrum("canon_eos_5d"));
}

// ---------------------------------------------------------------- spectrum files and errors

void expect_error_at(const std::string& body, const std::string& dir, const std::string& where,
                     const std::string& message) {
  try {
    parse_world(body, dir);
    ADD_FAILURE() << "no SceneError for " << body;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.loc().str(), where) << e.what();
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what() << "\nwanted: " << message;
  }
}

TEST(SpectrumFile, PairsCommentsAndBlankLinesRelativeToTheScene) {
  TempDir dir;
  // pbrt-v4's format: numbers separated by white space, '#' comments to the end of the line.
  dir.write("spd/grey.spd", "# a constant reflectance\n\n300 0.5   # first\n  900\t0.5\n# end");
  dir.write("spd/ramp.spd", "400 0.1 500 0.5\n600 0.2 700 0.9\n");
  SceneDesc s = parse_world(
      "Material \"diffuse\" \"spectrum reflectance\" \"spd/grey.spd\"\nShape \"sphere\"\n"
      "Material \"diffuse\" \"spectrum reflectance\" \"spd/ramp.spd\"\nShape \"sphere\"\n",
      dir.path());
  expect_rgb(s.materials[0].reflectance.value, RGB(0.5f), 5e-4f * 0.5f);  // grey, as ConstantReflectanceIsGrey
  expect_rgb(s.materials[1].reflectance.value,
             spectrum_rgb(std::vector<double>{400, 500, 600, 700}, std::vector<double>{0.1, 0.5, 0.2, 0.9},
                          SpectrumType::Unbounded),
             1e-6f);
  EXPECT_TRUE(has_warning(s, "test.pbrt:2:20: warning: spectrum file 'spd/grey.spd' for 'reflectance' reduced to RGB"));
}

TEST(SpectrumFile, ErrorsNameTheFileLineAndColumn) {
  TempDir dir;
  dir.write("word.spd", "400 0.5\n500 half\n");
  dir.write("odd.spd", "400 0.5\n500 0.4 600\n");
  dir.write("order.spd", "400 0.5 500 0.4\n  450 0.3\n");
  dir.write("empty.spd", "# nothing\n");
  const std::string d = dir.path() + "/";
  const std::string mat = "Material \"diffuse\" \"spectrum reflectance\" ";
  expect_error_at(mat + "\"word.spd\"\n", dir.path(), d + "word.spd:2:5", "'half' is not a number");
  expect_error_at(mat + "\"odd.spd\"\n", dir.path(), d + "odd.spd:2:9",
                  "5 numbers, not pairs: wavelength 600 nm has no value");
  expect_error_at(mat + "\"order.spd\"\n", dir.path(), d + "order.spd:2:3",
                  "wavelengths must increase (450 nm after 500 nm)");
  expect_error_at(mat + "\"empty.spd\"\n", dir.path(), d + "empty.spd:1:1", "holds no numbers");
  // A name that is neither a named spectrum nor a file: the scene's value, with a suggestion.
  expect_error_at(mat + "\"metal-Au-etta\"\n", dir.path(), "test.pbrt:2:43",
                  "unknown named spectrum 'metal-Au-etta' (did you mean 'metal-Au-eta'?) and no spectrum file '" + d +
                      "metal-Au-etta'");
  expect_error_at(mat + "\"canon_eos_5d_r\"\n", dir.path(), "test.pbrt:2:43", "camera sensor curve");
  // A directory is not a spectrum file.
  dir.write("sub/x.spd", "400 1 500 1");
  expect_error_at(mat + "\"sub\"\n", dir.path(), "test.pbrt:2:43", "spectrum file '" + d + "sub'");
}

// A reflectance given as a spectrum must lie in [0, 1] at every wavelength it is seen at
// (issue 65, item 7), not only its colour: an error at the scene's value, naming where.
TEST(SpectrumFile, AReflectanceSpectrumOutsideZeroToOneIsAnError) {
  TempDir dir;
  dir.write("bright.spd", "400 0.5 550 1.3 700 0.5\n");
  const std::string mat = "Material \"diffuse\" \"spectrum reflectance\" ";
  expect_error_at(mat + "[400 -0.2 700 0.5]\n", dir.path(), "test.pbrt:2:43",
                  "\"reflectance\" is a reflectance and must lie in [0, 1] at every wavelength of 360-830 nm; this "
                  "spectrum is -0.2 at 400 nm");
  expect_error_at(mat + "\"bright.spd\"\n", dir.path(), "test.pbrt:2:43", "this spectrum is 1.3 at 550 nm");
  expect_error_at("Material \"coateddiffuse\" \"spectrum albedo\" \"metal-Au-eta\"\n", dir.path(), "test.pbrt:2:44",
                  "\"albedo\" is a reflectance");
  // Within [0, 1]: fine, outside the visible range too.
  EXPECT_NO_THROW(parse_world(mat + "[300 2 360 1 830 0 900 -1]\n", dir.path()));
}

TEST(SpectrumFile, IndexOfRefractionFromAFile) {
  TempDir dir;
  dir.write("n.spd", "400 1.6 700 1.4\n");
  SceneDesc s = parse_world("Material \"dielectric\" \"spectrum eta\" \"n.spd\"\n", dir.path());
  EXPECT_NEAR(s.materials[0].eta, 1.5f, 1e-5f);  // the mean of a linear ramp is its midpoint
  EXPECT_TRUE(has_warning(s, "reduced to its mean over 400-700 nm"));
}

TEST(SubsurfaceSpectra, SigmaAAndSigmaSAsSampledSpectraAndFiles) {
  // Issue 11, item 5: "spectrum sigma_a" on subsurface, inline and from a file. Constant
  // spectra give grey coefficients (ConstantReflectanceIsGrey), times "scale".
  TempDir dir;
  dir.write("ss.spd", "300 1.5 900 1.5\n");
  SceneDesc s = parse_world(
      "Material \"subsurface\" \"spectrum sigma_a\" [300 0.01 900 0.01] "
      "\"spectrum sigma_s\" \"ss.spd\" \"float scale\" 2\nShape \"sphere\"\n"
      "Material \"subsurface\" \"spectrum sigma_a\" \"metal-Cu-k\" \"rgb sigma_s\" [1 1 1]\n",
      dir.path());
  const SubsurfaceParams& a = s.materials[0].subsurface;
  ASSERT_TRUE(a.sigma_a && a.sigma_s);
  expect_rgb(*a.sigma_a, RGB(0.02f), 0.02f * 5e-4f);
  expect_rgb(*a.sigma_s, RGB(3.0f), 3.0f * 5e-4f);
  expect_rgb(*s.materials[1].subsurface.sigma_a, *named_spectrum_rgb("metal-Cu-k"), 1e-6f);
}

}  // namespace
}  // namespace dermis
