#include "dermis/geometry/sphere_tessellation.h"

#include <cmath>

namespace dermis {

void tessellate_sphere(float radius, int n, std::vector<Vec3>& positions, std::vector<uint32_t>& indices) {
  int nu = 2 * n, nv = n;
  positions.clear();
  indices.clear();
  for (int j = 0; j <= nv; ++j) {
    float theta = kPi * float(j) / float(nv);
    for (int i = 0; i <= nu; ++i) {
      float phi = 2 * kPi * float(i) / float(nu);
      positions.push_back(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) *
                          radius);
    }
  }
  auto id = [nu](int i, int j) { return uint32_t(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      // Winding chosen so that cross(p0 - p2, p1 - p2) points outward.
      if (j != 0) indices.insert(indices.end(), {id(i, j), id(i, j + 1), id(i + 1, j)});
      if (j != nv - 1) indices.insert(indices.end(), {id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)});
    }
}

}  // namespace dermis
