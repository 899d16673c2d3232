// Shading normals through the parser and the path tracer (geometry/shading_normal.h): a
// flat mesh whose vertex normals are tilted must shade as the tilted surface would, while
// light stays on the geometric side. References are closed forms (Lambert's cosine law)
// and the same surface tilted geometrically; the scenes have no noise (a delta light or
// one emitter of uniform radiance seen by a mirror), so the tolerances are float rounding,
// except where a path's random choices remain (4 standard errors there).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/core/vec.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180;

std::unique_ptr<RenderScene> scene_from(const std::string& text) {
  Diagnostics diag;
  return build_render_scene(parse_scene_string(text, "shading_normals.pbrt"), diag);
}

// The quad [-10, 10]^2 in the plane z = 0 (geometric normal +z), rotated by `tilt_deg`
// about the y axis, with vertex normals `normal` (none when empty).
std::string quad(double tilt_deg, const std::string& normal) {
  std::string n;
  if (!normal.empty()) n = " \"normal N\" [" + normal + " " + normal + " " + normal + " " + normal + "]";
  return fmt::format(
      "AttributeBegin\nRotate {} 0 1 0\nShape \"trianglemesh\" \"point3 P\" [-10 -10 0 10 -10 0 10 10 0 -10 10 0] "
      "\"integer indices\" [0 1 2 0 2 3]{}\nAttributeEnd\n",
      tilt_deg, n);
}

// The unit normal tilted by `deg` from +z toward +x, as pbrt text.
std::string tilted(double deg) { return fmt::format("{} 0 {}", std::sin(deg * kDeg), std::cos(deg * kDeg)); }

// A camera at `eye` looking at the origin with a narrow field of view, a 3 x 3 film.
std::string camera(const std::string& eye, const std::string& up = "0 1 0") {
  return "LookAt " + eye + "  0 0 0  " + up +
         "\nCamera \"perspective\" \"float fov\" 4\n"
         "Film \"rgb\" \"integer xresolution\" 3 \"integer yresolution\" 3\n"
         "Integrator \"volpath\" \"integer maxdepth\" 8\nWorldBegin\n";
}

// The image's mean red value; every pixel checked against `expected` within rel_tol (and
// 4 standard errors, for the paths with random choices).
void expect_image(const testing::PixelStatistics& st, double expected, double rel_tol, const std::string& what) {
  for (std::size_t p = 0; p < st.mean.size(); ++p)
    EXPECT_NEAR(st.mean[p][0], expected, rel_tol * std::abs(expected) + 1e-7 + 4 * st.stderr_[p][0])
        << what << ", pixel " << p;
}

// Pixel by pixel (the same camera rays: the same angles of incidence): a within rel_tol of
// b, and 4 standard errors of their difference where the paths make random choices.
void expect_same_image(const testing::PixelStatistics& a, const testing::PixelStatistics& b, double rel_tol,
                       const std::string& what) {
  for (std::size_t p = 0; p < a.mean.size(); ++p) {
    const double sigma = std::hypot(a.stderr_[p][0], b.stderr_[p][0]);
    EXPECT_NEAR(a.mean[p][0], b.mean[p][0], rel_tol * std::abs(b.mean[p][0]) + 1e-7 + 4 * sigma)
        << what << ", pixel " << p;
  }
}

double mean_red(const testing::PixelStatistics& st) {
  double s = 0;
  for (const RGB& m : st.mean) s += m[0];
  return s / double(st.mean.size());
}

// A Lambertian quad seen from above under a distant light: radiance (rho / pi) E cos,
// the cosine taken to the shading normal. The ratio to the same quad with normals equal
// to the geometric one is cos(ns, l) / cos(ng, l), whatever the light's units.
TEST(ShadingNormals, LambertianSurfaceFollowsTheInterpolatedNormal) {
  const double tilt = 60;
  for (const double light_deg : {0.0, 30.0, -30.0}) {
    const std::string light = fmt::format(
        "LightSource \"distant\" \"point3 from\" [{} 0 {}] \"point3 to\" [0 0 0] "
        "\"rgb L\" [1 1 1]\nMaterial \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n",
        std::sin(light_deg * kDeg), std::cos(light_deg * kDeg));
    const auto smooth = testing::pixel_statistics(*scene_from(camera("0 0 50") + light + quad(0, tilted(tilt))), 4, 1);
    const auto flat = testing::pixel_statistics(*scene_from(camera("0 0 50") + light + quad(0, tilted(0))), 4, 1);
    const double flat_value = mean_red(flat);
    ASSERT_GT(flat_value, 0.01);
    // cos(angle between ns and l) = cos(tilt - light_deg), clamped at 0 (light behind ns).
    const double ratio = std::max(0.0, std::cos((tilt - light_deg) * kDeg)) / std::cos(light_deg * kDeg);
    expect_image(smooth, ratio * flat_value, 1e-5, fmt::format("light at {} deg", light_deg));
  }
}

// Seen from where the shading normal faces away (a grazing view across the tilt), the
// vertex is shaded with its geometric normal: the flat quad's value, not black.
TEST(ShadingNormals, SeenFromBehindTheShadingNormalTheGeometricOneShades) {
  const std::string light =
      "LightSource \"distant\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0] \"rgb L\" [1 1 1]\n"
      "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n";
  const std::string eye = "-50 0 10";  // wo . ns < 0 < wo . ng for ns tilted 60 deg toward +x
  const auto smooth = testing::pixel_statistics(*scene_from(camera(eye, "0 0 1") + light + quad(0, tilted(60))), 4, 1);
  const auto flat = testing::pixel_statistics(*scene_from(camera(eye, "0 0 1") + light + quad(0, "")), 4, 1);
  ASSERT_GT(mean_red(flat), 0.01);
  expect_image(smooth, mean_red(flat), 1e-5, "grazing view");
}

// An emitter of uniform radiance 40 degrees from the vertical, in the plane y = 0, facing
// the origin: a mirror seen from straight above reflects it when its normal is tilted by 20.
std::string emitter_at_40() {
  return "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3 3 3] \"bool twosided\" true\n"
         "Rotate 40 0 1 0\nTranslate 0 0 20\n"
         "Shape \"trianglemesh\" \"point3 P\" [-6 -6 0 6 -6 0 6 6 0 -6 6 0] \"integer indices\" [0 1 2 0 2 3]\n"
         "AttributeEnd\n";
}

// A smooth mirror with normals tilted by 20 degrees shows what the same mirror tilted by
// 20 degrees shows (the emitter, at the same angle of incidence, so the same Fresnel
// factor); the flat mirror without normals reflects the black above it.
TEST(ShadingNormals, MirrorReflectsAboutTheInterpolatedNormal) {
  for (const std::string material :
       {"Material \"conductor\" \"float roughness\" 0 \"rgb eta\" [0.2 0.9 1.1] \"rgb k\" [3.9 2.4 2.2]\n",
        "Material \"dielectric\" \"float eta\" 1.5\n"}) {
    const std::string head = camera("0 0 50") + emitter_at_40() + material;
    const auto smooth = testing::pixel_statistics(*scene_from(head + quad(0, tilted(20))), 64, 3);
    const auto turned = testing::pixel_statistics(*scene_from(head + quad(20, "")), 64, 3);
    const auto flat = testing::pixel_statistics(*scene_from(head + quad(0, "")), 64, 3);
    ASSERT_GT(mean_red(turned), 0.05) << material;
    expect_same_image(smooth, turned, 1e-5, material);
    expect_image(flat, 0, 0, material);
  }
}

// Tilted by 60 degrees, the shading normal would mirror a view from above to 30 degrees
// below the surface: that direction is no light (the surface's geometric side decides),
// even with an emitter there.
TEST(ShadingNormals, ReflectionIntoTheSurfaceCarriesNoLight) {
  const std::string below =
      "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [3 3 3] \"bool twosided\" true\n"
      "Rotate 120 0 1 0\nTranslate 0 0 20\n"
      "Shape \"trianglemesh\" \"point3 P\" [-15 -15 0 15 -15 0 15 15 0 -15 15 0] \"integer indices\" [0 1 2 0 2 3]\n"
      "AttributeEnd\n";
  const std::string head =
      camera("0 0 50") + below + "Material \"conductor\" \"float roughness\" 0 \"rgb reflectance\" [0.9 0.9 0.9]\n";
  const auto smooth = testing::pixel_statistics(*scene_from(head + quad(0, tilted(60))), 16, 5);
  expect_image(smooth, 0, 0, "reflection below the surface");
}

// The dielectric boundary of a subsurface material: its reflection (a pure absorber
// inside, so that nothing else returns) follows the shading normal as the mirror's does.
TEST(ShadingNormals, SubsurfaceEntryReflectsAboutTheInterpolatedNormal) {
  const std::string head =
      camera("0 0 50") + emitter_at_40() +
      "Material \"subsurface\" \"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [0 0 0] \"float eta\" 1.33\n";
  const auto smooth = testing::pixel_statistics(*scene_from(head + quad(0, tilted(20))), 256, 7);
  const auto turned = testing::pixel_statistics(*scene_from(head + quad(20, "")), 256, 7);
  const auto flat = testing::pixel_statistics(*scene_from(head + quad(0, "")), 256, 7);
  ASSERT_GT(mean_red(turned), 0.01);
  expect_same_image(smooth, turned, 1e-5, "subsurface entry");
  expect_image(flat, 0, 0, "flat subsurface quad");
}

// The image mean (red) of a is `ratio` times that of b, within 4 standard errors of
// mean(a) - ratio mean(b).
void expect_mean_ratio(const testing::PixelStatistics& a, const testing::PixelStatistics& b, double ratio) {
  double var_a = 0, var_b = 0;
  for (std::size_t p = 0; p < a.mean.size(); ++p)
    var_a += sqr(double(a.stderr_[p][0])), var_b += sqr(double(b.stderr_[p][0]));
  const double sigma = std::sqrt(var_a + sqr(ratio) * var_b) / double(a.mean.size());
  EXPECT_NEAR(mean_red(a), ratio * mean_red(b), 4 * sigma)
      << "expected ratio " << ratio << ", got " << mean_red(a) / mean_red(b);
}

// 1 - Fresnel reflectance of a smooth dielectric of relative index eta at incidence cos_i
// from outside (the textbook unpolarised formula; Born & Wolf, sec. 1.5.2).
double fresnel_transmittance(double cos_i, double eta) {
  const double sin_t = std::sqrt(std::max(0.0, 1 - cos_i * cos_i)) / eta, cos_t = std::sqrt(1 - sin_t * sin_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t), rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 1 - (rs * rs + rp * rp) / 2;
}

// A diffusion-profile slab (`disk` probes) seen and lit from straight above by a distant
// light: the camera's entry transmits 1 - F(cos wo.ns), the exit lobe takes the light in
// with (1 - F(cos l.ns)) cos(l.ns), and the profile's integral over the plane does not
// depend on the normals. With normals tilted by 30 degrees the image is therefore the flat
// slab's times T(cos 30)^2 cos 30 / T(1)^2, T = 1 - F; both estimates carry the probes'
// noise (4 standard errors of the image means).
TEST(ShadingNormals, SubsurfaceExitLobeFollowsTheInterpolatedNormal) {
  const double eta = 1.33, tilt = 30;
  const std::string head = camera("0 0 50") +
                           "LightSource \"distant\" \"point3 from\" [0 0 1] \"point3 to\" [0 0 0] \"rgb L\" [1 1 1]\n"
                           "Material \"subsurface\" \"string method\" \"disk\" \"rgb reflectance\" [0.8 0.8 0.8] "
                           "\"rgb mfp\" [0.5 0.5 0.5] \"float eta\" 1.33\n";
  const auto smooth = testing::pixel_statistics(*scene_from(head + quad(0, tilted(tilt))), 4000, 9);
  const auto flat = testing::pixel_statistics(*scene_from(head + quad(0, "")), 4000, 10);
  const double c = std::cos(tilt * kDeg);
  const double ratio = sqr(fresnel_transmittance(c, eta)) * c / sqr(fresnel_transmittance(1, eta));
  ASSERT_GT(mean_red(flat), 0.01);
  expect_mean_ratio(smooth, flat, ratio);
}

// A clear absorbing slab (the random walk with its `dielectric` boundary; sigma_s = 0, so
// a walk is one straight flight) seen from straight above, a uniform emitter far below it.
// Its bottom face is flat, with vertex normals tilted by 45 degrees: the walk leaves it
// refracted about them, so the light found below carries the Fresnel transmittance of a
// 45-degree incidence from inside (that of the refracted angle from outside, by
// reciprocity), where the slab without those normals transmits at normal incidence. The
// ratio of the two images is T(45 deg inside) / T(0) up to paths reflected twice inside
// (F_top F_bottom e^-2, below 1e-4 of the image); 4 standard errors of the image means.
TEST(ShadingNormals, WalkLeavesThroughTheInterpolatedNormal) {
  const double eta = 1.33, tilt = 45;
  // The slab [-10, 10]^2 x [-1, 0], each face with vertices of its own and its normals.
  auto slab = [](const std::string& bottom_normal) {
    const std::string top = "-10 -10 0 10 -10 0 10 10 0 -10 10 0", bottom = "-10 -10 -1 -10 10 -1 10 10 -1 10 -10 -1";
    const std::string sides =
        "-10 -10 -1 10 -10 -1 10 -10 0 -10 -10 0  10 -10 -1 10 10 -1 10 10 0 10 -10 0  "
        "10 10 -1 -10 10 -1 -10 10 0 10 10 0  -10 10 -1 -10 -10 -1 -10 -10 0 -10 10 0";
    std::string normals = "0 0 1 0 0 1 0 0 1 0 0 1 ";
    for (int i = 0; i < 4; ++i) normals += bottom_normal + " ";
    for (const char* n : {"0 -1 0", "1 0 0", "0 1 0", "-1 0 0"})
      for (int i = 0; i < 4; ++i) normals += std::string(n) + " ";
    std::string indices;
    for (int f = 0; f < 6; ++f)
      indices += fmt::format("{0} {1} {2} {0} {2} {3} ", 4 * f, 4 * f + 1, 4 * f + 2, 4 * f + 3);
    return "Shape \"trianglemesh\" \"point3 P\" [" + top + " " + bottom + " " + sides + "] \"normal N\" [" + normals +
           "] \"integer indices\" [" + indices + "]\n";
  };
  const std::string head = camera("0 0 50") +
                           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2] \"bool twosided\" true\n"
                           "Shape \"trianglemesh\" \"point3 P\" [-100 -100 -30 100 -100 -30 100 100 -30 -100 100 -30] "
                           "\"integer indices\" [0 1 2 0 2 3]\nAttributeEnd\n"
                           "Material \"subsurface\" \"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [0 0 0] \"float eta\" 1.33 "
                           "\"string boundary\" \"dielectric\"\n";
  const std::string down_tilted = fmt::format("{} 0 {}", std::sin(tilt * kDeg), -std::cos(tilt * kDeg));
  const auto smooth = testing::pixel_statistics(*scene_from(head + slab(down_tilted)), 3000, 13);
  const auto flat = testing::pixel_statistics(*scene_from(head + slab("0 0 -1")), 3000, 14);
  const double sin_out = eta * std::sin(tilt * kDeg);  // the refracted angle's sine, outside
  const double ratio = fresnel_transmittance(std::sqrt(1 - sin_out * sin_out), eta) / fresnel_transmittance(1, eta);
  ASSERT_GT(mean_red(flat), 0.05);
  expect_mean_ratio(smooth, flat, ratio);
}

}  // namespace
}  // namespace dermis
