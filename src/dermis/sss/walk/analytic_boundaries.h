// Boundaries of simple media seen from inside, as tracers for random_walk (random_walk.h):
// a half-space, a slab and a ball. Tests and benchmarks run the renderer's walk on them
// where the answer is known or the geometry must be exact.
#pragma once

#include <algorithm>
#include <cmath>

#include "dermis/sss/walk/random_walk.h"

namespace dermis::sss {

// The half-space z < 0: the plane z = 0, outward normal +z.
struct HalfspaceTracer {
  BoundaryHit operator()(Vec3 o, Vec3 d, double /*max_t: exact anyway*/ = 0) const {
    if (!(d.z > 0)) return {};
    const float t = std::max(0.0f, -o.z / d.z);
    Vec3 p = o + d * t;
    p.z = 0;
    return {true, t, p, {0, 0, 1}};
  }
};

// The slab -thickness < z < 0: top z = 0 (outward +z), bottom z = -thickness (outward -z).
// A ray starting on one face and running along it finds nothing.
struct SlabTracer {
  double thickness = 1;
  BoundaryHit operator()(Vec3 of, Vec3 df, double /*max_t: exact anyway*/ = 0) const {
    const Vec3d o(of), d(df);
    if (d.z == 0) return {};
    const double plane = d.z > 0 ? 0.0 : -thickness;
    const double t = std::max(0.0, (plane - o.z) / d.z);
    Vec3d p = o + d * t;
    p.z = plane;
    return {true, float(t), Vec3(p), d.z > 0 ? Vec3(0, 0, 1) : Vec3(0, 0, -1)};
  }
};

// A ball of radius r at the origin: the far root of |o + t d| = r.
struct SphereTracer {
  double radius = 1;
  BoundaryHit operator()(Vec3 of, Vec3 df, double /*max_t: exact anyway*/ = 0) const {
    const Vec3d o(of), d(df);
    const double b = dot(o, d), c = dot(o, o) - radius * radius;
    const double t = -b + std::sqrt(std::max(0.0, b * b - c));  // c <= 0 inside: the positive root
    if (!(t > 0)) return {};
    const Vec3d p = o + d * t;
    return {true, float(t), Vec3(p), Vec3(normalize(p))};
  }
};

}  // namespace dermis::sss
