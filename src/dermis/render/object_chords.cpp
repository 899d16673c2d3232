#include "dermis/render/object_chords.h"

#include <map>
#include <set>

#include "dermis/geometry/mean_chord.h"

namespace dermis {

std::vector<double> subsurface_object_chords(const RenderScene& sc) {
  // One pass over the shapes: each object's shapes, and the objects of each subsurface material.
  std::map<int, std::vector<const Shape*>> shapes_of_object;
  std::vector<std::set<int>> objects_of_material(sc.subsurface_params.size());
  for (std::size_t i = 0; i < sc.shapes.size() && i < sc.object_of_shape.size(); ++i) {
    const int object = sc.object_of_shape[i];
    if (object < 0) continue;
    shapes_of_object[object].push_back(&sc.shapes[i]);
    const int m = sc.shapes[i].material;
    if (m < 0 || sc.materials[std::size_t(m)].type != Material::Type::Subsurface) continue;
    const int k = sc.materials[std::size_t(m)].subsurface;
    if (k >= 0 && std::size_t(k) < objects_of_material.size()) objects_of_material[std::size_t(k)].insert(object);
  }
  std::vector<double> chords(sc.subsurface_params.size(), 0.0);
  for (std::size_t k = 0; k < chords.size(); ++k) {
    std::vector<const Shape*> shapes;
    bool instanced = false;
    for (int object : objects_of_material[k])
      for (const Shape* s : shapes_of_object[object]) {
        shapes.push_back(s);
        instanced = instanced || s->instance >= 0;
      }
    // An instanced object's shapes are in its own space, and each instance may scale it
    // differently, while the walk's lengths are the world's: no thickness.
    chords[k] = instanced ? 0.0 : mean_chord_length(shapes);
  }
  return chords;
}

}  // namespace dermis
