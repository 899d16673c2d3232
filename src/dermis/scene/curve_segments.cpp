#include "dermis/scene/curve_segments.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace dermis {

namespace {

Vec3 lerp(float t, Vec3 a, Vec3 b) { return a * (1 - t) + b * t; }

// Degree elevation of a quadratic Bézier (Farin, Curves and Surfaces for CAGD, 5th ed.,
// eq. 6.2: b_i' = i/(n+1) b_{i-1} + (1 - i/(n+1)) b_i, here n = 2).
void elevate_quadratic(Vec3 q0, Vec3 q1, Vec3 q2, Vec3* out) {
  out[0] = q0;
  out[1] = q0 * (1.0f / 3) + q1 * (2.0f / 3);
  out[2] = q1 * (2.0f / 3) + q2 * (1.0f / 3);
  out[3] = q2;
}

// Spherical interpolation of unit vectors a to b (Shoemake 1985), linear where they are
// nearly parallel; opposite vectors have no unique arc: the linear path is taken.
Vec3 slerp(Vec3 a, Vec3 b, float t) {
  const float c = std::clamp(dot(a, b), -1.0f, 1.0f), theta = std::acos(c), s = std::sin(theta);
  if (!(s > 1e-4f)) return normalize(lerp(t, a, b));
  return a * (std::sin((1 - t) * theta) / s) + b * (std::sin(t * theta) / s);
}

}  // namespace

std::size_t curve_segment_count(std::size_t point_count, CurveBasis basis, int degree) {
  if (degree != 2 && degree != 3)
    throw std::invalid_argument(fmt::format("degree {} is not supported: a curve has degree 2 or 3", degree));
  const std::size_t d = std::size_t(degree);
  if (basis == CurveBasis::Bezier) {
    if (point_count < d + 1 || (point_count - 1) % d != 0)
      throw std::invalid_argument(
          fmt::format("{} control points do not make a degree-{} Bézier curve: it needs {} + "
                      "n * {} (n >= 0)",
                      point_count, degree, d + 1, d));
    return (point_count - 1) / d;
  }
  if (point_count < d + 1)
    throw std::invalid_argument(fmt::format("{} control points do not make a degree-{} B-spline: it needs at least {}",
                                            point_count, degree, d + 1));
  return point_count - d;
}

CurveSegments curve_to_bezier_segments(const std::vector<Vec3>& points, CurveBasis basis, int degree, CurveKind kind,
                                       float width0, float width1, const std::vector<Vec3>& normals) {
  const std::size_t n = curve_segment_count(points.size(), basis, degree);
  if (kind == CurveKind::Ribbon && normals.size() != n + 1)
    throw std::invalid_argument(
        fmt::format("a ribbon curve of {} segments needs {} normals \"N\" (one per segment "
                    "end), got {}",
                    n, n + 1, normals.size()));
  CurveSegments c;
  c.kind = kind;
  c.points.resize(4 * n);
  c.widths.resize(4 * n);
  for (std::size_t k = 0; k < n; ++k) {
    Vec3* b = &c.points[4 * k];
    if (basis == CurveBasis::Bezier) {
      const Vec3* p = &points[k * std::size_t(degree)];
      if (degree == 3)
        for (int i = 0; i < 4; ++i) b[i] = p[i];
      else
        elevate_quadratic(p[0], p[1], p[2], b);
    } else if (degree == 2) {
      // Uniform quadratic B-spline to Bézier (Farin, ch. 7: the Bézier points of a uniform
      // B-spline segment are the midpoints of its legs and the middle de Boor point).
      const Vec3* p = &points[k];
      elevate_quadratic((p[0] + p[1]) * 0.5f, p[1], (p[1] + p[2]) * 0.5f, b);
    } else {
      // Uniform cubic B-spline to Bézier (Farin, ch. 7, the "one-third" rule):
      // b1, b2 at 1/3 and 2/3 of leg p1 p2; b0, b3 the mean of the adjacent 2/3 points.
      const Vec3* p = &points[k];
      b[1] = p[1] * (2.0f / 3) + p[2] * (1.0f / 3);
      b[2] = p[1] * (1.0f / 3) + p[2] * (2.0f / 3);
      b[0] = ((p[0] * (1.0f / 3) + p[1] * (2.0f / 3)) + b[1]) * 0.5f;
      b[3] = (b[2] + (p[2] * (2.0f / 3) + p[3] * (1.0f / 3))) * 0.5f;
    }
    // A linear function has Bézier coefficients at equal steps (linear precision), so the
    // width runs linearly from lerp(k/n) to lerp((k+1)/n) over the segment.
    const float w_start = width0 + (width1 - width0) * float(k) / float(n);
    const float w_end = width0 + (width1 - width0) * float(k + 1) / float(n);
    for (int i = 0; i < 4; ++i) c.widths[4 * k + std::size_t(i)] = w_start + (w_end - w_start) * float(i) / 3;
  }
  if (kind == CurveKind::Ribbon) {
    c.normals.resize(4 * n);
    for (std::size_t k = 0; k < n; ++k) {
      const float l0 = length(normals[k]), l1 = length(normals[k + 1]);
      if (!(l0 > 0) || !(l1 > 0))
        throw std::invalid_argument(fmt::format("normal {} of the ribbon is zero", l0 > 0 ? k + 1 : k));
      const Vec3 n0 = normals[k] / l0, n1 = normals[k + 1] / l1;
      // pbrt-v4 turns a ribbon's normal from n0 to n1 by spherical interpolation along the
      // segment; Embree interpolates the normals' control points as a cubic Bézier. The
      // inner two are chosen so that the Bézier passes through slerp at 1/3 and 2/3:
      // B(1/3) = (8 P0 + 12 P1 + 6 P2 + P3) / 27 and B(2/3) = (P0 + 6 P1 + 12 P2 + 8 P3) / 27.
      const Vec3 q1 = slerp(n0, n1, 1.0f / 3) * 27 - n0 * 8 - n1, q2 = slerp(n0, n1, 2.0f / 3) * 27 - n0 - n1 * 8;
      Vec3* cp = &c.normals[4 * k];
      cp[0] = n0;
      cp[1] = (q1 * 2 - q2) / 18;
      cp[2] = (q2 * 2 - q1) / 18;
      cp[3] = n1;
    }
  }
  return c;
}

Vec3 cubic_bezier_point(const Vec3* p, float t) {
  const Vec3 a = lerp(t, p[0], p[1]), b = lerp(t, p[1], p[2]), c = lerp(t, p[2], p[3]);
  const Vec3 d = lerp(t, a, b), e = lerp(t, b, c);
  return lerp(t, d, e);
}

}  // namespace dermis
