// The path tracer in pbrt-v4's grid media: delta tracking, next-event estimation through
// ratio tracking, spectral MIS (path/grid_volume_vertex.h).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "dermis/core/rng.h"
#include "dermis/render/renderer.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/spectral/blackbody.h"
#include "dermis/spectral/cie_observer.h"
#include "support/nanovdb_files.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

std::unique_ptr<RenderScene> scene_from(const std::string& text) {
  Diagnostics diag;
  return build_render_scene(parse_scene_string(text, "test.pbrt"), diag);
}

// A unit sphere filled with `medium` (index-matched), under a uniform sky and `lights`.
std::string medium_sphere(const std::string& medium, const std::string& sky, const std::string& lights = "") {
  return fmt::format(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 6 \"integer yresolution\" 6\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [{}]\n{}\n"
      "AttributeBegin\nRotate 30 1 2 3\nTranslate 0.1 -0.1 0.05\nMakeNamedMedium \"m\" {}\nAttributeEnd\n"
      "Material \"interface\"\nMediumInterface \"m\" \"\"\nShape \"sphere\"\n",
      sky, lights, medium);
}

// An nx x ny x nz grid of densities, 30 % of them zero and the rest up to `high`.
std::string random_densities(int nx, int ny, int nz, float high, uint64_t seed) {
  Rng rng(seed, 7);
  std::string s = fmt::format("\"integer nx\" {} \"integer ny\" {} \"integer nz\" {} \"float density\" [", nx, ny, nz);
  for (int i = 0; i < nx * ny * nz; ++i) s += fmt::format(" {}", rng.uniform() < 0.3f ? 0.0f : high * rng.uniform());
  return s + " ]";
}

// The chord of the unit sphere along pixel (x, y)'s centre ray.
float sphere_chord(const RenderScene& sc, int x, int y) {
  const Ray r = sc.camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
  const Vec3 d = normalize(r.d);
  const float b = dot(r.o, d), disc = b * b - (dot(r.o, r.o) - 1);
  return disc > 0 ? 2 * std::sqrt(disc) : 0;
}

// The per-pixel difference of two renders within 4 standard errors of the difference.
void expect_same_image(const testing::PixelStatistics& a, const testing::PixelStatistics& b) {
  int failures = 0;
  for (std::size_t p = 0; p < a.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double se = std::hypot(a.stderr_[p][c], b.stderr_[p][c]);
      if (std::abs(a.mean[p][c] - b.mean[p][c]) > 4 * se + 1e-6 && failures++ < 5)
        ADD_FAILURE() << "pixel " << p << " channel " << c << ": " << a.mean[p][c] << " vs " << b.mean[p][c]
                      << " (4 sigma = " << 4 * se << ")";
    }
  EXPECT_EQ(failures, 0);
}

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

constexpr const char* kCoefficients = "\"rgb sigma_a\" [0.2 0.5 1] \"rgb sigma_s\" [2 1 0.5] \"float g\" 0.3";
constexpr const char* kSun = "LightSource \"distant\" \"point3 from\" [1 2 -1] \"point3 to\" [0 0 0] \"rgb L\" [3 3 3]";

// A grid of constant density (its box reaching half a cell past the sphere, where the
// interpolation fades to zero) renders as the homogeneous medium of the same coefficients:
// every pixel within 4 sigma of the difference, lit by a sky and a distant light (next-event
// estimation through ratio tracking), in RGB and spectrally.
TEST(GridMediaRender, ConstantGridIsTheHomogeneousMedium) {
  const std::string grid = fmt::format(
      "\"string type\" \"uniformgrid\" \"integer nx\" 2 \"integer ny\" 2 \"integer nz\" 2 \"float density\" [1 1 1 1 "
      "1 1 1 1] \"point3 p0\" [-2.1 -2.1 -2.1] \"point3 p1\" [2.1 2.1 2.1] {}",
      kCoefficients);
  const auto gridded = scene_from(medium_sphere(grid, "0.5 0.5 0.5", kSun));
  const auto homogeneous =
      scene_from(medium_sphere(fmt::format("\"string type\" \"homogeneous\" {}", kCoefficients), "0.5 0.5 0.5", kSun));
  ASSERT_EQ(gridded->grid_media.size(), 1u);
  for (bool spectral : {false, true})
    expect_same_image(testing::pixel_statistics(*gridded, 512, 1, {}, spectral),
                      testing::pixel_statistics(*homogeneous, 512, 2, {}, spectral));
}

// A nanovdb medium (an .nvdb file of constant density 1 over [-2, 2]^3, voxels of 0.25)
// renders as the homogeneous medium, as the constant uniformgrid does.
TEST(GridMediaRender, ConstantNanoVdbIsTheHomogeneousMedium) {
  const std::string file = ::testing::TempDir() + "dermis_constant_" + std::to_string(::getpid()) + ".nvdb";
  std::vector<nanovdb::GridHandle<>> grids;
  grids.push_back(testing::nvdb_grid("density", 16, 0.25, -2.0, [](int, int, int) { return 1.0f; }));
  testing::write_nvdb(file, std::move(grids));
  const auto vdb = scene_from(
      medium_sphere(fmt::format("\"string type\" \"nanovdb\" \"string filename\" \"{}\" {}", file, kCoefficients),
                    "0.5 0.5 0.5", kSun));
  std::filesystem::remove(file);
  const auto homogeneous =
      scene_from(medium_sphere(fmt::format("\"string type\" \"homogeneous\" {}", kCoefficients), "0.5 0.5 0.5", kSun));
  ASSERT_EQ(vdb->grid_media.size(), 1u);
  expect_same_image(testing::pixel_statistics(*vdb, 512, 8, {}), testing::pixel_statistics(*homogeneous, 512, 9, {}));
}

// The white furnace: a non-absorbing, chromatic, strongly varying grid medium (densities
// 0 to 12, 30 % empty) in an index-matched sphere under a white sky scatters light but loses
// none, so every pixel is the sky's white whichever channel drew each flight and however the
// shadow rays' ratio tracking estimates the transmittance. Likewise an rgbgrid whose colours
// vary per sample, in RGB and spectrally.
TEST(GridMediaRender, NonAbsorbingGridsKeepTheFurnaceWhite) {
  const auto density = scene_from(medium_sphere(
      "\"string type\" \"uniformgrid\" " + random_densities(7, 5, 6, 12, 1) +
          " \"point3 p0\" [-1.2 -1 -1.3] \"point3 p1\" [1.1 1.4 1.2] \"rgb sigma_a\" [0 0 0] \"rgb sigma_s\" [2 1 0.4] "
          "\"float g\" 0.5",
      "1 1 1"));
  expect_image_equals(testing::pixel_statistics(*density, 256, 3, {}), RGB(1), 1e-6);
  // rgbgrid's sigma_a defaults to 1 (pbrt-v4): zero here, given.
  Rng rng(9, 1);
  std::string scattering, zeros;
  for (int i = 0; i < 64 * 3; ++i) {
    scattering += fmt::format(" {}", rng.uniform() < 0.2f ? 0.0f : 6 * rng.uniform());
    zeros += " 0";
  }
  const auto rgb = scene_from(
      medium_sphere("\"string type\" \"rgbgrid\" \"integer nx\" 4 \"integer ny\" 4 \"integer nz\" 4 \"rgb sigma_s\" [" +
                        scattering + " ] \"rgb sigma_a\" [" + zeros +
                        " ] \"point3 p0\" [-1.1 -1.1 -1.1] \"point3 p1\" [1.1 1.1 1.1] \"float scale\" 1.5",
                    "1 1 1"));
  expect_image_equals(testing::pixel_statistics(*rgb, 256, 4, {}), RGB(1), 1e-6);
  // Spectrally, the sky's white is D65 (1, 1, 1 up to the tables' rounding: 2e-3 here).
  expect_image_equals(testing::pixel_statistics(*rgb, 256, 5, {}, true), RGB(1), 2e-3);
}

// Emission in a purely absorbing medium (for the grids, density and Lescale constant over the
// unit sphere, their boxes reaching more than half a cell past it): a pixel-centre ray
// crossing a chord c sees Le Lescale (1 - e^(-sigma_a c)) + sky e^(-sigma_a c), for a
// homogeneous medium, a uniformgrid (Le times its Lescale grid) and an rgbgrid (its Le grid
// times Lescale, its Le given over pbrt-v4's CIE_Y_integral, the factor pbrt-v4 leaves in
// it) alike, within 4 sigma plus 1e-5 in RGB; spectrally, where sigma_a is grey so that the
// factor is the same at every wavelength, plus 2e-3 of the value (the uplift's round trip).
TEST(GridMediaRender, EmissionAlongTheChords) {
  constexpr float sigma_a = 0.7f, sky = 0.2f;
  const RGB Le(1, 0.5f, 0.25f);
  const std::string box =
      "\"point3 p0\" [-2.1 -2.1 -2.1] \"point3 p1\" [2.1 2.1 2.1] \"integer nx\" 2 \"integer ny\" 2 "
      "\"integer nz\" 2 ";
  const std::string uniformgrid =
      "\"string type\" \"uniformgrid\" " + box +
      "\"float density\" [1 1 1 1 1 1 1 1] \"float Lescale\" [2 2 2 2 2 2 2 2] \"rgb Le\" [1 0.5 0.25] "
      "\"rgb sigma_a\" [0.7 0.7 0.7] \"rgb sigma_s\" [0 0 0]";
  std::string a, s0, le;
  constexpr double y_integral = kPbrtV4CieYIntegral;
  for (int i = 0; i < 8; ++i)
    a += " 0.7 0.7 0.7", s0 += " 0 0 0",
        le += fmt::format(" {} {} {}", 1 / y_integral, 0.5 / y_integral, 0.25 / y_integral);
  const std::string rgbgrid = "\"string type\" \"rgbgrid\" " + box + "\"rgb sigma_a\" [" + a + "] \"rgb sigma_s\" [" +
                              s0 + "] \"rgb Le\" [" + le + "] \"float Lescale\" 2";
  const std::string homogeneous =
      "\"string type\" \"homogeneous\" \"rgb Le\" [1 0.5 0.25] \"float Lescale\" 2 \"rgb sigma_a\" [0.7 0.7 0.7] "
      "\"rgb sigma_s\" [0 0 0]";
  for (const std::string& medium : {homogeneous, uniformgrid, rgbgrid})
    for (bool spectral : {false, true}) {
      const auto sc = scene_from(medium_sphere(medium, fmt::format("{} {} {}", sky, sky, sky)));
      const testing::PixelStatistics st = testing::pixel_statistics(*sc, 256, 6, {}, spectral);
      int failures = 0;
      for (int y = 0; y < st.height; ++y)
        for (int x = 0; x < st.width; ++x) {
          const float chord = sphere_chord(*sc, x, y);
          const float tr = std::exp(-sigma_a * chord);
          const std::size_t p = std::size_t(y) * std::size_t(st.width) + std::size_t(x);
          for (int c = 0; c < 3; ++c) {
            const float expected = Le[c] * 2 * (1 - tr) + sky * tr;
            const float tol = 4 * st.stderr_[p][c] + (spectral ? 2e-3f * expected : 1e-5f);
            if (std::abs(st.mean[p][c] - expected) > tol && failures++ < 5)
              ADD_FAILURE() << (spectral ? "spectral " : "RGB ") << "pixel " << x << "," << y << " channel " << c
                            << ": " << st.mean[p][c] << " vs " << expected << " (chord " << chord << ")";
          }
        }
      EXPECT_EQ(failures, 0) << medium;
    }
}

// A grid's temperature emits pbrt-v4's blackbody (normalised to 1 at its peak) at
// (temperature - cutoff) x scale, times Lescale: along the chords of an absorbing sphere,
// Lescale B(T) (1 - e^(-sigma_a c)) + sky e^(-sigma_a c), B(T) the film's colour of the
// blackbody (spectral/blackbody.h) times pbrt-v4's CIE_Y_integral (cie_observer.h), within 4 sigma plus 1e-3 of the
// value (the colour table's interpolation in RGB; spectrally the film's own sum).
TEST(GridMediaRender, TemperatureEmitsABlackbody) {
  constexpr float sigma_a = 0.7f, sky = 0.2f;
  const RGB B = normalized_blackbody_rgb((1900 - 300) * 1.5f) * kPbrtV4CieYIntegral;
  const auto sc = scene_from(medium_sphere(
      "\"string type\" \"uniformgrid\" \"point3 p0\" [-2.1 -2.1 -2.1] \"point3 p1\" [2.1 2.1 2.1] \"integer nx\" 2 "
      "\"integer ny\" 2 \"integer nz\" 2 \"float density\" [1 1 1 1 1 1 1 1] \"float temperature\" [1900 1900 1900 "
      "1900 1900 1900 1900 1900] \"float temperaturecutoff\" 300 \"float temperaturescale\" 1.5 \"float Lescale\" [3 3 "
      "3 "
      "3 3 3 3 3] \"rgb sigma_a\" [0.7 0.7 0.7] \"rgb sigma_s\" [0 0 0]",
      "0.2 0.2 0.2"));
  for (bool spectral : {false, true}) {
    const testing::PixelStatistics st = testing::pixel_statistics(*sc, 256, 7, {}, spectral);
    int failures = 0;
    for (int y = 0; y < st.height; ++y)
      for (int x = 0; x < st.width; ++x) {
        const float tr = std::exp(-sigma_a * sphere_chord(*sc, x, y));
        const std::size_t p = std::size_t(y) * std::size_t(st.width) + std::size_t(x);
        for (int c = 0; c < 3; ++c) {
          const float expected = 3 * B[c] * (1 - tr) + sky * tr;
          if (std::abs(st.mean[p][c] - expected) > 4 * st.stderr_[p][c] + 1e-3f * expected && failures++ < 5)
            ADD_FAILURE() << (spectral ? "spectral " : "RGB ") << "pixel " << x << "," << y << " channel " << c << ": "
                          << st.mean[p][c] << " vs " << expected;
        }
      }
    EXPECT_EQ(failures, 0);
  }
}

// Tracking draws its numbers from the sample and the ray (null_scattering.h tracking_rng):
// the same seed gives the same image whatever the thread count, RGB and spectral.
TEST(GridMediaRender, SameSeedSameImageWhateverTheThreadCount) {
  const auto sc = scene_from(medium_sphere("\"string type\" \"uniformgrid\" " + random_densities(5, 4, 3, 6, 2) +
                                               " \"point3 p0\" [-1 -1 -1] \"point3 p1\" [1 1 1] " + kCoefficients,
                                           "0.5 0.5 0.5", kSun));
  for (bool spectral : {false, true}) {
    RenderOptions o;
    o.spp = 8;
    o.seed = 5;
    o.spectral = spectral;
    o.threads = 1;
    const RenderResult a = render_image(*sc, o);
    o.threads = 2;
    const RenderResult b = render_image(*sc, o);
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float))) << spectral;
  }
}

}  // namespace
}  // namespace dermis
