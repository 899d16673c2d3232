// Light sources: emissive triangles and spheres (area lights), point, spot,
// distant and infinite (uniform or lat-long) lights. A tagged struct with
// switches (no virtual call per shadow ray).
#pragma once

#include <memory>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"
#include "dermis/geometry/ray.h"
#include "dermis/lights/environment_map.h"

namespace dermis {

struct Light {
  enum class Type { Triangle, Sphere, Point, Spot, Distant, Infinite };
  Type type = Type::Point;
  RGB emission;  // L for area, distant and uniform infinite lights; I for point and spot
  bool two_sided = false;
  // Triangle (world space) and its shape/primitive, for the normal's orientation.
  Vec3 p0, p1, p2;
  float area = 0;
  int shape = -1, prim = -1;
  // Triangle of a shape without shading normals: its unit normal, the same at every point
  // (Shape::triangle_normal's, computed once); otherwise looked up per sample.
  bool flat = false;
  Vec3 normal;
  // Sphere (world space).
  Vec3 center;
  float radius = 0;
  bool inward = false;  // sphere's normals point inward (ReverseOrientation)
  // Point and spot position; spot axis; distant: unit direction toward the light.
  Vec3 position, direction;
  float cos_falloff_start = 1, cos_falloff_end = 1;
  std::shared_ptr<const EnvironmentMap> environment;  // infinite light with a map
  // Infinite: pbrt-v4's portal, the unit normal (world space) of the side light comes from:
  // directions w toward the light with dot(w, portal_normal) <= 0 carry none. Zero: no portal.
  Vec3 portal_normal{0, 0, 0};
  int medium = -1;
  // The emission as a spectrum (RenderScene::spectra) where the scene gave one (a blackbody,
  // a named or tabulated spectrum), and that spectrum's colour at the scale it is kept at:
  // spectral rendering reads emission x its ratio to that colour (render/path/direct_light.h).
  int spectrum_data = -1;
  RGB spectrum_data_rgb{0, 0, 0};
};

struct LightSample {
  Vec3 wi;             // unit direction from the reference point toward the light
  float distance = 0;  // to the sampled point (infinity for distant and infinite lights)
  float pdf = 0;       // solid angle at the reference point (1 for delta lights)
  RGB L;               // radiance (or I/d^2 for point lights) arriving at the reference point
  Vec3 p_light;        // sampled point on the light (finite lights)
  Vec3 n_light;        // its normal (area lights)
  bool delta = false;
};

struct Shape;

// Samples a direction toward the light from reference point ref; `shapes` gives the
// area light's orientation rule. Returns false when nothing can be sampled. `ref_n`: the
// unit normal of the hemisphere a surface at ref scatters from (zero in a medium); a
// uniform infinite light is then sampled by the cosine about it (its light arrives
// weighted by that cosine: a constant sky is estimated without variance), else uniformly
// over the sphere.
bool light_sample(const Light& l, const std::vector<Shape>& shapes, Vec3 ref, Vec2 u, LightSample& s,
                  Vec3 ref_n = Vec3(0, 0, 0));
// Solid-angle density that light_sample() produces wi from ref (with the same ref_n),
// hitting the light at point p_light with normal n_light (area lights) or escaping
// (infinite lights).
float light_pdf(const Light& l, Vec3 ref, Vec3 wi, Vec3 p_light, Vec3 n_light, Vec3 ref_n = Vec3(0, 0, 0));
// Radiance emitted by an area light at a point with normal n toward direction w.
RGB area_light_radiance(const Light& l, Vec3 n, Vec3 w);
// Radiance of an infinite light arriving from direction w (toward the light).
RGB infinite_light_radiance(const Light& l, Vec3 w);
// The same, and in `pdf` light_pdf(l, ref, w, {}, {}, ref_n): an environment map looks its
// pixel up once for both (a ray that escaped, weighed by MIS).
RGB infinite_light_radiance(const Light& l, Vec3 w, Vec3 ref_n, float* pdf);
// Total emitted power (approximate for lights at infinity, whose power grows with the
// scene's radius), for light selection. In double: a light whose power is beyond the range
// of 32-bit floats (a point light of I = 3e37: 4 pi I) is seen as such (scene_assembly.cpp
// refuses it at its directive) instead of as infinity.
double light_power(const Light& l, double scene_radius);

}  // namespace dermis
