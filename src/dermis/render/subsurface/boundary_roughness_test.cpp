// A subsurface material's boundary roughness per surface point (boundary_roughness.h)
// and what the material makes of it: the entry's rough dielectric and the exit lobe's
// table at the point (subsurface_method.h).
#include "dermis/render/subsurface/boundary_roughness.h"

#include <gtest/gtest.h>

#include <vector>

#include "dermis/render/subsurface/subsurface_method.h"

namespace dermis {
namespace {

std::vector<Texture> constant_texture(float value) {
  Texture t;
  t.type = Texture::Type::Constant;
  t.value = RGB(value);
  return {t};
}

SubsurfaceParams textured_params() {
  SubsurfaceParams p;
  p.method = SubsurfaceParams::Method::Disk;
  p.sigma_a = RGB(0.05f, 0.1f, 0.2f);
  p.sigma_s = RGB(2, 3, 4);
  p.eta = 1.4f;
  p.roughness_texture = 0;
  return p;
}

TEST(BoundaryRoughness, EvaluatesTheTextureAtThePointAndMapsItAsPbrtV4) {
  const SurfaceHit hit;
  const std::vector<Texture> textures = constant_texture(0.0625f);
  SubsurfaceParams p = textured_params();
  const BoundaryRoughness remapped(p, false, &textures);
  EXPECT_TRUE(remapped.textured());
  EXPECT_FLOAT_EQ(remapped.at(hit).x, 0.25f);  // alpha = sqrt(r)
  EXPECT_FLOAT_EQ(remapped.at(hit).y, 0.25f);
  EXPECT_FALSE(remapped.constant().rough());
  p.remap_roughness = false;
  EXPECT_FLOAT_EQ(BoundaryRoughness(p, false, &textures).at(hit).x, 0.0625f);
  EXPECT_FALSE(BoundaryRoughness(p, true, &textures).at(hit).rough());  // an index-matched boundary
  const std::vector<Texture> negative = constant_texture(-1);
  EXPECT_FALSE(BoundaryRoughness(p, false, &negative).at(hit).rough());
  SubsurfaceParams constant;
  constant.uroughness = 0.04f, constant.vroughness = 0.09f;
  EXPECT_FLOAT_EQ(BoundaryRoughness(constant, false, nullptr).at(hit).x, 0.2f);
  EXPECT_FLOAT_EQ(BoundaryRoughness(constant, false, nullptr).at(hit).y, 0.3f);
}

TEST(BoundaryRoughness, TheMaterialEntersAndLeavesThroughThePointsRoughness) {
  const std::vector<Texture> textures = constant_texture(0.0625f);
  const SubsurfaceMaterial m = make_subsurface_material(textured_params(), &textures);
  SurfaceHit hit;
  hit.ng = Vec3(0, 0, 1);
  const BSDF entry = m.entry_boundary(hit);
  EXPECT_FLOAT_EQ(entry.alpha_x, 0.25f);
  EXPECT_FLOAT_EQ(entry.alpha_y, 0.25f);
  RoughExitTable scratch;
  const BSDF exit = m.exit_lobe(hit, scratch);
  ASSERT_EQ(exit.exit_table, &scratch);
  const RoughExitTable direct = make_rough_exit_table(1.4f, 0.25f, 0.25f);  // a node of the textured tables
  for (int i = 0; i < RoughExitTable::kNodes; ++i) EXPECT_EQ(scratch.transmittance[i], direct.transmittance[i]) << i;
  EXPECT_EQ(exit.sw_norm, direct.norm);
  // Smooth where the texture says 0: the normalised-Fresnel lobe.
  const std::vector<Texture> zero = constant_texture(0);
  const SubsurfaceMaterial smooth = make_subsurface_material(textured_params(), &zero);
  const BSDF smooth_exit = smooth.exit_lobe(hit, scratch);
  EXPECT_EQ(smooth_exit.exit_table, nullptr);
  EXPECT_EQ(smooth_exit.sw_norm, subsurface_exit_normalization(1.4f));
  EXPECT_FALSE(smooth.entry_boundary(hit).is_rough());
}

}  // namespace
}  // namespace dermis
