#include "dermis/geometry/mean_chord.h"

#include <cmath>

namespace dermis {

double mean_chord_length(const std::vector<const Shape*>& shapes) {
  double volume = 0, area = 0;
  for (const Shape* s : shapes) {
    if (s->type == Shape::Type::Sphere) {
      const double r = s->radius;
      volume += 4.0 / 3.0 * kPiD * r * r * r;
      area += 4 * kPiD * r * r;
      continue;
    }
    if (s->type != Shape::Type::Mesh || s->positions.empty()) continue;
    Vec3d centre(0.0, 0.0, 0.0);  // the volume about the vertices' mean: no cancellation far from the origin
    for (const Vec3& p : s->positions) centre += Vec3d(p);
    centre = centre / double(s->positions.size());
    double v = 0, a = 0;
    Vec3d oriented(0.0, 0.0, 0.0);  // the sum of the faces' oriented area vectors: 0 for a closed surface
    for (std::size_t k = 0; k + 2 < s->indices.size(); k += 3) {
      const Vec3d p0 = Vec3d(s->positions[s->indices[k]]) - centre,
                  p1 = Vec3d(s->positions[s->indices[k + 1]]) - centre,
                  p2 = Vec3d(s->positions[s->indices[k + 2]]) - centre;
      const Vec3d twice_area = cross(p1 - p0, p2 - p0);
      v += dot(p0, cross(p1, p2)) / 6;  // the signed tetrahedron (centre, triangle)
      a += length(twice_area) / 2;
      oriented += twice_area / 2;
    }
    // An open surface (its oriented areas do not cancel) encloses no volume.
    if (!(length(oriented) <= kClosedSurfaceTolerance * a)) return 0;
    volume += std::abs(v);  // each mesh's orientation (inward or outward) on its own
    area += a;
  }
  const double chord = 4 * volume / area;
  return std::isfinite(chord) && chord > 0 ? chord : 0.0;
}

}  // namespace dermis
