// The layered, diffuse-transmission and mix materials through the parser and the path
// tracer: each image against an independent reference (geometry, a furnace, a closed
// form), within 4 standard errors per pixel.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/core/microfacet.h"
#include "dermis/core/rng.h"
#include "dermis/materials/layered_bsdf.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "dermis/scene/scene_test_util.h"
#include "dermis/scene/spectra.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {
using test::has_warning;
using test::parse_world;

std::unique_ptr<RenderScene> scene_from(const std::string& text) {
  Diagnostics diag;
  return build_render_scene(parse_scene_string(text, "test.pbrt"), diag);
}

// A horizontal quad at height z, half-size h, facing +z.
std::string quad(float z, float h) {
  return fmt::format(
      "Shape \"trianglemesh\" \"point3 P\" [{0} {0} {2} {1} {0} {2} {1} {1} {2} {0} {1} {2}] "
      "\"integer indices\" [0 1 2 0 2 3]\n",
      -h, h, z);
}

// A closed box [-h, h]^2 x [z0, z1] (outward winding).
std::string box(float h, float z0, float z1) {
  return fmt::format(
      "Shape \"trianglemesh\" \"point3 P\" [{0} {0} {2} {1} {0} {2} {1} {1} {2} {0} {1} {2} "
      "{0} {0} {3} {1} {0} {3} {1} {1} {3} {0} {1} {3}] \"integer indices\" "
      "[0 2 1 0 3 2  4 5 6 4 6 7  0 1 5 0 5 4  1 2 6 1 6 5  2 3 7 2 7 6  3 0 4 3 4 7]\n",
      -h, h, z0, z1);
}

// Camera above the plane looking down at 40 degrees, a uniform sky and a square area
// light to one side: light from one direction and from all.
std::string lit_plane_header(int max_depth) {
  return fmt::format(
      "LookAt 0 -2.5 3  0 0 0  0 0 1\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 6 \"integer yresolution\" 6\n"
      "Integrator \"volpath\" \"integer maxdepth\" {}\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [0.3 0.3 0.3]\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [6 6 6] \"bool twosided\" true\n"
      "Translate 1.5 1 2.5\n{}AttributeEnd\n",
      max_depth, quad(0, 0.6f));
}

void expect_images_equal(const testing::PixelStatistics& a, const testing::PixelStatistics& b) {
  int failures = 0;
  double sum_a = 0, sum_b = 0, var = 0;
  for (std::size_t p = 0; p < a.mean.size(); ++p) {
    for (int c = 0; c < 3; ++c) {
      const double sigma = std::hypot(a.stderr_[p][c], b.stderr_[p][c]);
      if (std::abs(a.mean[p][c] - b.mean[p][c]) > 4 * sigma && failures++ < 5)
        ADD_FAILURE() << "pixel " << p << " channel " << c << ": " << a.mean[p][c] << " vs " << b.mean[p][c]
                      << " (4 sigma = " << 4 * sigma << ")";
    }
    sum_a += a.mean[p][0];
    sum_b += b.mean[p][0];
    var += sqr(double(a.stderr_[p][0])) + sqr(double(b.stderr_[p][0]));
  }
  EXPECT_EQ(failures, 0);
  // The image means (red): a sharper test of the same thing.
  EXPECT_NEAR(sum_a, sum_b, 4 * std::sqrt(var))
      << "image means " << sum_a / a.mean.size() << " vs " << sum_b / b.mean.size();
}

// (b) coateddiffuse against the same stack built as geometry: a smooth glass slab
// (thickness 0.002) with a diffuse plane inside it, rendered by the ordinary path tracer
// (refraction, internal reflection, the base). The material's coating has no optical
// depth (thickness 0), as the glass has none.
TEST(CoatedDiffuseRender, MatchesGlassSlabOverDiffusePlane) {
  const float t = 0.002f;
  const std::string material = lit_plane_header(1000) +
                               "Material \"coateddiffuse\" \"rgb reflectance\" [0.7 0.4 0.2] \"float eta\" 1.5 "
                               "\"float thickness\" 0 \"integer maxdepth\" 1000\n" +
                               quad(t, 30);
  const std::string geometry = lit_plane_header(1000) + "AttributeBegin\nMaterial \"dielectric\" \"float eta\" 1.5\n" +
                               box(30, 0, t) + "AttributeEnd\n" +
                               "Material \"diffuse\" \"rgb reflectance\" [0.7 0.4 0.2]\n" + quad(t / 2, 30);
  const auto a = testing::pixel_statistics(*scene_from(material), 3000, 1);
  const auto b = testing::pixel_statistics(*scene_from(geometry), 3000, 2);
  expect_images_equal(a, b);
}

// (b, d) coatedconductor against geometry: a smooth glass slab over a rough gold-like
// conductor plane, rendered by the ordinary path tracer (the rough conductor, refraction
// and total internal reflection), against the material. A conductor's eta and k are its
// index over what surrounds it (Fresnel's equations take the ratio): inside the glass the
// plane's are the metal's divided by 1.5, as the material's base faces its coating.
TEST(CoatedConductorRender, MatchesGlassSlabOverRoughConductorPlane) {
  const float t = 0.002f;
  const std::string metal = "\"rgb conductor.eta\" [0.2 0.5 1.4] \"rgb conductor.k\" [3.6 2.4 1.8]";
  const std::string material = lit_plane_header(1000) + "Material \"coatedconductor\" " + metal +
                               " \"float conductor.roughness\" 0.05 \"float interface.eta\" 1.5 "
                               "\"float thickness\" 0 \"integer maxdepth\" 1000\n" +
                               quad(t, 30);
  const std::string geometry =
      lit_plane_header(1000) + "AttributeBegin\nMaterial \"dielectric\" \"float eta\" 1.5\n" + box(30, 0, t) +
      "AttributeEnd\n" +
      "Material \"conductor\" \"rgb eta\" [0.133333 0.333333 0.933333] \"rgb k\" [2.4 1.6 1.2] "
      "\"float roughness\" 0.05\n" +
      quad(t / 2, 30);
  const auto a = testing::pixel_statistics(*scene_from(material), 3000, 11);
  const auto b = testing::pixel_statistics(*scene_from(geometry), 3000, 12);
  expect_images_equal(a, b);
}

// A coated white sphere in a uniform environment of radiance 1: each pixel shows the
// stack's directional albedo R(wo) (a convex sphere: one bounce). The renderer's
// estimate (next-event estimation with eval, MIS with estimated densities, sampling)
// against the mean weight of sample() alone at that pixel's cos(wo). Smooth interface:
// R = 1 exactly (no absorption, a long walk); rough interface: R < 1 (single-scattering
// microfacets lose energy), the per-pixel reference from coated_sample().
TEST(CoatedDiffuseRender, CoatedWhiteSphereInFurnaceShowsItsAlbedo) {
  for (const float roughness : {0.0f, 0.2f}) {
    const auto sc = scene_from(fmt::format(
        "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
        "Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
        "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
        "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
        "Material \"coateddiffuse\" \"rgb reflectance\" [1 1 1] \"float roughness\" {} \"float thickness\" 0 "
        "\"integer maxdepth\" 100000\n"
        "Shape \"sphere\"\n",
        roughness));
    const auto st = testing::pixel_statistics(*sc, 4000, 3);
    CoatedLayer c;
    c.base_reflectance = RGB(1);
    c.interface_alpha_x = c.interface_alpha_y = roughness_to_alpha(roughness, true);
    c.thickness = 0;
    c.max_depth = 100000;
    for (int y = 0; y < st.height; ++y)
      for (int x = 0; x < st.width; ++x) {
        const std::size_t p = std::size_t(y) * st.width + x;
        const Ray ray = sc->camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
        // The unit sphere: |o + t d| = 1, the nearer root; the normal is the hit point.
        const float b = dot(ray.o, ray.d), disc = b * b - (dot(ray.o, ray.o) - 1);
        ASSERT_GT(disc, 0) << "pixel " << p << " misses the sphere";
        const Vec3 n = ray.o + ray.d * (-b - std::sqrt(disc));
        const float cos_o = -dot(ray.d, n);
        Rng rng(61, p);
        double s = 0, s2 = 0;
        const int m = 100000;
        for (int i = 0; i < m; ++i) {
          const auto smp = coated_sample(c, {std::sqrt(1 - cos_o * cos_o), 0, cos_o}, rng.uniform(),
                                         {rng.uniform(), rng.uniform()}, mix64(p * m + i));
          const double w = smp ? smp->weight[0] : 0.0;
          s += w, s2 += w * w;
        }
        const double ref = s / m, ref_se = std::sqrt(std::max(0.0, s2 / m - ref * ref) / (m - 1));
        if (roughness == 0) {
          EXPECT_NEAR(ref, 1.0, 4 * ref_se + 1e-6);
        }
        EXPECT_NEAR(st.mean[p][0], ref, 4 * std::hypot(double(st.stderr_[p][0]), ref_se) + 1e-6)
            << "roughness " << roughness << " pixel " << p;
      }
  }
}

// Diffuse transmission with R + T = 1 in a white furnace: every path keeps its energy,
// so the sphere renders 1 (lights sampled on both sides, media crossed).
TEST(DiffuseTransmissionRender, WhiteFurnaceRendersOne) {
  // "scale" 2: R = 0.3, T = 0.7.
  const auto white = scene_from(
      "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
      "Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
      "Integrator \"volpath\" \"integer maxdepth\" 100000\nWorldBegin\n"
      "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
      "Material \"diffusetransmission\" \"rgb reflectance\" [0.15 0.15 0.15] \"rgb transmittance\" [0.35 0.35 0.35] "
      "\"float scale\" 2\n"
      "Shape \"sphere\"\n");
  const auto st = testing::pixel_statistics(*white, 2000, 4);
  for (std::size_t p = 0; p < st.mean.size(); ++p) EXPECT_NEAR(st.mean[p][0], 1.0, 4 * st.stderr_[p][0]) << p;
}

// A plane of diffuse transmission over a uniform sky only: seen from below, it shows T
// times the light's radiance (a huge emitting plane above it fills its upper
// hemisphere but for a fraction (5 / 1e4)^2 = 2.5e-7 of the cosine-weighted solid
// angle); seen from above, R times it.
TEST(DiffuseTransmissionRender, PlaneShowsTFromBelowAndRFromAbove) {
  const std::string body =
      "Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\n"
      "Integrator \"volpath\" \"integer maxdepth\" 1\nWorldBegin\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2] \"bool twosided\" true\n" +
      quad(5, 1e4f) +
      "AttributeEnd\n"
      "Material \"diffusetransmission\" \"rgb reflectance\" [0.2 0.2 0.2] \"rgb transmittance\" [0.5 0.5 0.5]\n" +
      quad(0, 1e4f);
  // From below the plane (z = -3) the only light reaches it through the plane; the area
  // light at z = 5 fills its upper hemisphere.
  const auto below = testing::pixel_statistics(
      *scene_from("LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n" + body), 2000, 5);
  for (std::size_t p = 0; p < below.mean.size(); ++p)
    EXPECT_NEAR(below.mean[p][0], 0.5 * 2, 4 * below.stderr_[p][0] + 1e-5) << p;
  const auto above = testing::pixel_statistics(
      *scene_from("LookAt 0 0 3  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n" + body), 2000, 6);
  for (std::size_t p = 0; p < above.mean.size(); ++p)
    EXPECT_NEAR(above.mean[p][0], 0.2 * 2, 4 * above.stderr_[p][0] + 1e-5) << p;
}

std::string mix_scene(const std::string& materials) {
  return "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 20\n"
         "Film \"rgb\" \"integer xresolution\" 4 \"integer yresolution\" 4\nWorldBegin\n"
         "LightSource \"infinite\" \"rgb L\" [1 1 1]\n"
         "MakeNamedMaterial \"black\" \"string type\" \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
         "MakeNamedMaterial \"white\" \"string type\" \"diffuse\" \"rgb reflectance\" [1 1 1]\n" +
         materials + "Shape \"sphere\"\n";
}

// A mix of black and white at amount a renders a (white's share) on a convex sphere in
// a white furnace: one bounce, white with probability a; nested mixes multiply.
TEST(MixMaterialRender, BlackWhiteMixRendersAmount) {
  const auto simple =
      scene_from(mix_scene("MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" [\"black\" \"white\"] "
                           "\"float amount\" 0.3\n"
                           "NamedMaterial \"m\"\n"));
  const auto st = testing::pixel_statistics(*simple, 4000, 7);
  for (std::size_t p = 0; p < st.mean.size(); ++p) EXPECT_NEAR(st.mean[p][1], 0.3, 4 * st.stderr_[p][1]) << p;
  // mix(mix(black, white, 0.3), white, 0.5): white with probability 0.5 0.3 + 0.5 = 0.65.
  const auto nested = scene_from(mix_scene(
      "MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" [\"black\" \"white\"] \"float amount\" "
      "0.3\n"
      "MakeNamedMaterial \"n\" \"string type\" \"mix\" \"string materials\" [\"m\" \"white\"] \"float amount\" 0.5\n"
      "NamedMaterial \"n\"\n"));
  const auto sn = testing::pixel_statistics(*nested, 4000, 8);
  for (std::size_t p = 0; p < sn.mean.size(); ++p) EXPECT_NEAR(sn.mean[p][1], 0.65, 4 * sn.stderr_[p][1]) << p;
  // amount as a float texture (constant 0.8).
  const auto textured =
      scene_from(mix_scene("Texture \"a\" \"float\" \"constant\" \"float value\" 0.8\n"
                           "MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" [\"black\" \"white\"] "
                           "\"texture amount\" \"a\"\n"
                           "NamedMaterial \"m\"\n"));
  const auto stt = testing::pixel_statistics(*textured, 4000, 9);
  for (std::size_t p = 0; p < stt.mean.size(); ++p) EXPECT_NEAR(stt.mean[p][1], 0.8, 4 * stt.stderr_[p][1]) << p;
}

TEST(MixMaterialParse, ErrorsNameTheValue) {
  const std::string line =
      "MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" [\"black\" \"nope\"]\n";
  const std::string text = mix_scene(line);
  try {
    parse_scene_string(text, "test.pbrt");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    const int col = int(line.find("\"nope\"")) + 1;
    EXPECT_NE(
        std::string(e.what()).find(fmt::format("test.pbrt:8:{}: error: mix: unknown named material \"nope\"", col)),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_scene_string(mix_scene("MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" "
                                            "\"black\"\n"),
                                  "test.pbrt"),
               SceneError);                                                                    // one name
  EXPECT_THROW(parse_scene_string(mix_scene("Material \"mix\"\n"), "test.pbrt"), SceneError);  // none
  EXPECT_THROW(parse_scene_string(mix_scene("MakeNamedMaterial \"i\" \"string type\" \"interface\"\n"
                                            "Material \"mix\" \"string materials\" [\"i\" \"white\"]\n"),
                                  "test.pbrt"),
               SceneError);  // interface in a mix
}

// pbrt-v4's parameter names and defaults, read without "unsupported" or "unused" warnings.
TEST(CoatedMaterialsParse, PbrtV4ParametersAndDefaults) {
  const SceneDesc s = parse_world(
      "Material \"coateddiffuse\"\n"
      "Material \"coatedconductor\" \"float interface.roughness\" 0.01 \"spectrum conductor.eta\" \"metal-Au-eta\" "
      "\"spectrum conductor.k\" \"metal-Au-k\" \"float conductor.uroughness\" 0.2 \"float conductor.vroughness\" 0.1 "
      "\"float interface.eta\" 1.4 \"float thickness\" 0.05 \"rgb albedo\" [0.5 0.5 0.5] \"float g\" 0.3 "
      "\"integer maxdepth\" 20 \"integer nsamples\" 2 \"bool remaproughness\" false\n"
      "Material \"coatedconductor\" \"rgb reflectance\" [0.9 0.8 0.5]\n"
      "Material \"diffusetransmission\"\n");
  const MaterialDesc& d = s.materials[0];
  EXPECT_EQ(d.type, MaterialDesc::Type::CoatedDiffuse);
  EXPECT_FLOAT_EQ(d.thickness, 0.01f);
  EXPECT_FLOAT_EQ(d.eta, 1.5f);
  EXPECT_EQ(d.max_depth, 10);
  EXPECT_EQ(d.n_samples, 1);
  EXPECT_FLOAT_EQ(d.g, 0);
  EXPECT_EQ(d.albedo.max(), 0.0f);
  EXPECT_FLOAT_EQ(d.reflectance.value[0], 0.5f);
  const MaterialDesc& c = s.materials[1];
  EXPECT_EQ(c.type, MaterialDesc::Type::CoatedConductor);
  EXPECT_FLOAT_EQ(c.uroughness, 0.01f);
  EXPECT_FLOAT_EQ(c.conductor_uroughness, 0.2f);
  EXPECT_FLOAT_EQ(c.conductor_vroughness, 0.1f);
  EXPECT_FLOAT_EQ(c.eta, 1.4f);
  EXPECT_FLOAT_EQ(c.thickness, 0.05f);
  EXPECT_FLOAT_EQ(c.g, 0.3f);
  EXPECT_EQ(c.max_depth, 20);
  EXPECT_EQ(c.n_samples, 2);
  EXPECT_FALSE(c.remap_roughness);
  EXPECT_FLOAT_EQ(c.conductor_eta[0], named_spectrum_rgb("metal-Au-eta")->operator[](0));
  EXPECT_TRUE(s.materials[2].has_reflectance);
  EXPECT_EQ(s.materials[3].type, MaterialDesc::Type::DiffuseTransmission);
  EXPECT_FLOAT_EQ(s.materials[3].reflectance.value[0], 0.25f);
  EXPECT_FLOAT_EQ(s.materials[3].transmittance.value[0], 0.25f);
  EXPECT_FALSE(has_warning(s, "unsupported"));
  EXPECT_FALSE(has_warning(s, "unused"));
  EXPECT_FALSE(has_warning(s, "ignored"));
  EXPECT_THROW(parse_world("Material \"coateddiffuse\" \"float g\" 1\n"), SceneError);
  EXPECT_THROW(parse_world("Material \"coateddiffuse\" \"integer maxdepth\" 0\n"), SceneError);
}

}  // namespace
}  // namespace dermis
