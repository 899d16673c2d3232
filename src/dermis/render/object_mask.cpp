#include "dermis/render/object_mask.h"

#include "dermis/render/film.h"

namespace dermis {

namespace {

// A shape of a `subsurface` material: one a method renders, or a `volumetric` one
// (assembled as a dielectric filled with the material's medium).
bool is_subsurface(const RenderScene& scene, const Shape& shape) {
  if (scene.materials[std::size_t(shape.material)].type == Material::Type::Subsurface) return true;
  for (const RenderScene::VolumetricMedium& v : scene.volumetric_media)
    if (shape.has_medium_interface && shape.inside_medium == v.medium) return true;
  return false;
}

}  // namespace

std::vector<uint8_t> subsurface_object_mask(const RenderScene& scene) {
  const PixelBounds px = film_pixel_bounds(scene.film);
  std::vector<uint8_t> mask(std::size_t(px.width()) * px.height(), 0);
  for (int y = px.y0; y < px.y1; ++y)
    for (int x = px.x0; x < px.x1; ++x) {
      const Ray ray = scene.camera.generate_ray({float(x) + 0.5f, float(y) + 0.5f}, {0.5f, 0.5f});
      SurfaceHit hit;
      if (scene.embree->intersect(ray, hit) && is_subsurface(scene, scene.shapes[std::size_t(hit.shape)]))
        mask[std::size_t(y - px.y0) * px.width() + (x - px.x0)] = 1;
    }
  return mask;
}

}  // namespace dermis
