#include "dermis/render/volumetric_texture.h"

#include "dermis/render/subsurface/coefficients.h"

namespace dermis {

namespace {

HomogeneousMedium volumetric_medium(const RenderScene::VolumetricMedium& vm, MediumAt at, float boundary_alpha,
                                    const SampledWavelengths* w) {
  if (w) at = medium_at_wavelengths(vm.params, at, *w);
  const Coefficients k = coefficients_from(at, vm.inversions, boundary_alpha);
  return HomogeneousMedium::from_coefficients(k.sigma_a, k.sigma_s, 1, vm.params.g);
}

}  // namespace

int volumetric_of_medium(const RenderScene& scene, int medium) {
  for (std::size_t i = 0; i < scene.volumetric_media.size(); ++i)
    if (scene.volumetric_media[i].medium == medium) return int(i);
  return -1;
}

HomogeneousMedium volumetric_medium_at(const RenderScene& scene, int v, const SurfaceHit& entry,
                                       const SampledWavelengths* w) {
  const RenderScene::VolumetricMedium& vm = scene.volumetric_media[v];
  return volumetric_medium(vm, medium_at(vm.params, &scene.textures, texture_context(entry)), vm.roughness.at(entry).x,
                           w);
}

HomogeneousMedium volumetric_medium_at_wavelengths(const RenderScene& scene, int v, const SampledWavelengths& w) {
  const RenderScene::VolumetricMedium& vm = scene.volumetric_media[v];
  return volumetric_medium(vm, medium_at(vm.params), vm.roughness.constant().x, &w);
}

}  // namespace dermis
