#include "dermis/render/volumetric_texture.h"

#include "dermis/render/subsurface/coefficients.h"

namespace dermis {

HomogeneousMedium volumetric_medium_at(const RenderScene& scene, int v, const SurfaceHit& entry) {
  const RenderScene::VolumetricMedium& vm = scene.volumetric_media[v];
  const Coefficients k = coefficients_from(medium_at(vm.params, &scene.textures, texture_context(entry)), vm.inversions,
                                           vm.roughness.at(entry).x);
  return HomogeneousMedium::from_coefficients(k.sigma_a, k.sigma_s, 1, vm.params.g);
}

}  // namespace dermis
