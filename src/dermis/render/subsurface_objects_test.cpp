// Subsurface objects made of several shapes (render_scene.h object_of_shape): walks and
// probes cross between the shapes of one object, which are the shapes sharing a
// subsurface material (pbrt-v4's rule) or the materials naming one "sssgroup".
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dermis/geometry/sphere_tessellation.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/parser.h"
#include "support/lit_sphere_scene.h"
#include "support/pixel_statistics.h"

namespace dermis {
namespace {

const std::string kHeader = testing::lit_sphere_header(12);

// A unit sphere as triangle meshes: whole, or its triangles with centroid z > 0 and
// z <= 0 as two shapes (the lit top and the bottom: light must cross between them).
std::string sphere_meshes(bool split, const std::string& material_top, const std::string& material_bottom) {
  std::vector<Vec3> p;
  std::vector<uint32_t> idx;
  tessellate_sphere(1, 16, p, idx);
  std::string points;
  for (const Vec3& v : p) points += fmt::format("{} {} {} ", v.x, v.y, v.z);
  std::string top, bottom;
  for (std::size_t t = 0; t < idx.size(); t += 3) {
    const float z = p[idx[t]].z + p[idx[t + 1]].z + p[idx[t + 2]].z;
    (split && z <= 0 ? bottom : top) += fmt::format("{} {} {} ", idx[t], idx[t + 1], idx[t + 2]);
  }
  auto mesh = [&](const std::string& material, const std::string& indices) {
    return material + "\nShape \"trianglemesh\" \"point3 P\" [" + points + "] \"integer indices\" [" + indices + "]\n";
  };
  return split ? mesh(material_top, top) + mesh(material_bottom, bottom) : mesh(material_top, top);
}

testing::PixelStatistics render(const std::string& scene, uint64_t seed, int spp = 64) {
  Diagnostics diag;
  auto sc = build_render_scene(parse_scene_string(kHeader + scene), diag);
  return testing::pixel_statistics(*sc, spp, seed);
}

// The split sphere renders like the whole one, for the walk and for probe rays, when
// its halves share the material or name one group: region means within 4 standard
// errors of their difference.
TEST(SubsurfaceObjects, ASphereSplitInTwoShapesRendersLikeTheWholeSphere) {
  for (const char* method : {"randomwalk", "disk"}) {
    SCOPED_TRACE(method);
    const std::string params =
        fmt::format("\"rgb reflectance\" [0.8 0.6 0.4] \"rgb mfp\" [0.6 0.4 0.25] \"string method\" \"{}\"", method);
    const std::string shared = "Material \"subsurface\" " + params;
    const testing::PixelStatistics whole = render(sphere_meshes(false, shared, ""), 11);
    testing::expect_same_region_means(whole, render(sphere_meshes(true, shared, ""), 12), 4, 4);
    const std::string grouped = "Material \"subsurface\" \"string sssgroup\" \"ball\" " + params;
    testing::expect_same_region_means(whole, render(sphere_meshes(true, grouped, grouped), 13), 4, 4);
  }
}

// Without a shared material or group the halves are two objects and light does not
// cross between them: the unlit bottom half is darker than in the whole sphere (the
// check that the test above can fail).
TEST(SubsurfaceObjects, HalvesOfDifferentMaterialsAreSeparateObjects) {
  const std::string params = "\"rgb reflectance\" [0.8 0.6 0.4] \"rgb mfp\" [0.6 0.4 0.25]";
  const std::string a = "Material \"subsurface\" " + params, b = "Material \"subsurface\" \"float g\" 0 " + params;
  const testing::PixelStatistics whole = render(sphere_meshes(false, a, ""), 21);
  const testing::PixelStatistics apart = render(sphere_meshes(true, a, b), 22);
  double d = 0, v = 0;
  for (std::size_t i = 0; i < whole.mean.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      d += whole.mean[i][c] - apart.mean[i][c];
      v += whole.stderr_[i][c] * whole.stderr_[i][c] + apart.stderr_[i][c] * apart.stderr_[i][c];
    }
  EXPECT_GT(d, 4 * std::sqrt(v));
}

// An opaque core inside a translucent sphere is a boundary the walk respects: light
// meeting it is reflected diffusely with its albedo (absorbed when black), as in the
// volumetric path tracer's image of the same medium in glass around the same core.
TEST(SubsurfaceObjects, AnOpaqueCoreDarkensTheWalkAsItDoesTheVolumetricReference) {
  const char* coefficients = "\"rgb sigma_a\" [0.05 0.1 0.2] \"rgb sigma_s\" [1.5 2 3] \"float g\" 0.2";
  for (const char* core : {"0", "0.7"}) {
    SCOPED_TRACE(core);
    const std::string core_shape = std::string("AttributeBegin\n  Material \"diffuse\" \"rgb reflectance\" [") + core +
                                   " " + core + " " + core +
                                   "]\n  Translate 0 0 0.3\n  Shape \"sphere\" \"float radius\" 0.5\n"
                                   "AttributeEnd\n";
    const std::string walk = std::string("Material \"subsurface\" ") + coefficients +
                             " \"float eta\" 1.4 \"string boundary\" \"dielectric\"\nShape \"sphere\"\n" + core_shape;
    const std::string volume =
        std::string("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" ") + coefficients +
        "\nAttributeBegin\n  MediumInterface \"m\" \"\"\n  Material \"dielectric\" \"float eta\" 1.4\n"
        "  Shape \"sphere\"\nAttributeEnd\nAttributeBegin\n  MediumInterface \"m\" \"m\"\n" +
        core_shape.substr(std::string("AttributeBegin\n").size());
    testing::expect_same_region_means(render(walk, 41, 128), render(volume, 42, 128), 4, 4);
  }
}

}  // namespace
}  // namespace dermis
