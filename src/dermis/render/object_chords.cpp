#include "dermis/render/object_chords.h"

#include <set>

#include "dermis/geometry/mean_chord.h"

namespace dermis {

std::vector<double> subsurface_object_chords(const RenderScene& sc) {
  std::vector<double> chords(sc.subsurface_params.size(), 0.0);
  for (std::size_t k = 0; k < chords.size(); ++k) {
    std::set<int> objects;  // the objects of the material's shapes
    for (std::size_t i = 0; i < sc.shapes.size(); ++i) {
      const int m = sc.shapes[i].material;
      if (m >= 0 && sc.materials[std::size_t(m)].type == Material::Type::Subsurface &&
          sc.materials[std::size_t(m)].subsurface == int(k) && i < sc.object_of_shape.size() &&
          sc.object_of_shape[i] >= 0)
        objects.insert(sc.object_of_shape[i]);
    }
    std::vector<const Shape*> shapes;
    bool instanced = false;
    for (std::size_t i = 0; i < sc.shapes.size() && i < sc.object_of_shape.size(); ++i)
      if (objects.count(sc.object_of_shape[i])) {
        shapes.push_back(&sc.shapes[i]);
        instanced = instanced || sc.shapes[i].instance >= 0;
      }
    // An instanced object's shapes are in its own space, and each instance may scale it
    // differently, while the walk's lengths are the world's: no thickness.
    chords[k] = instanced ? 0.0 : mean_chord_length(shapes);
  }
  return chords;
}

}  // namespace dermis
