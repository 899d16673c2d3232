// pbrt-v4's `curve` shape as cubic Bézier segments: its control points in the "bezier" or
// "bspline" basis, degree 2 or 3, turned into one cubic Bézier per segment (what Embree's
// curve primitives take), with the width and, for ribbons, the normal of each control point.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "dermis/core/vec.h"

namespace dermis {

enum class CurveBasis { Bezier, BSpline };
enum class CurveKind { Flat, Cylinder, Ribbon };  // pbrt-v4's "type": flat, cylinder, ribbon

// A curve as cubic Bézier segments, 4 control points each (segment k: points[4k .. 4k+3]).
struct CurveSegments {
  CurveKind kind = CurveKind::Flat;
  std::vector<Vec3> points;
  std::vector<float> widths;  // per control point: the width along the curve is linear
  std::vector<Vec3> normals;  // ribbons: per control point (unit), else empty
  std::size_t segment_count() const { return points.size() / 4; }
};

// The segment count pbrt-v4 reads from `point_count` control points: Bézier: degree + 1 for
// the first segment and `degree` more for each next one (they share their end points);
// B-spline: point_count - degree. Throws std::invalid_argument (the message says what
// counts are valid) when the count does not fit.
std::size_t curve_segment_count(std::size_t point_count, CurveBasis basis, int degree);

// The cubic Bézier segments of a pbrt-v4 curve. `points` in `basis`, `degree` 2 or 3;
// widths from width0 at the curve's start to width1 at its end, linear in the segment
// index (pbrt-v4: segment k of n runs from lerp(k/n) to lerp((k+1)/n)); `normals`: one per
// segment end (segment_count + 1) for ribbons, normalised here. Throws
// std::invalid_argument on a bad count or a zero normal.
CurveSegments curve_to_bezier_segments(const std::vector<Vec3>& points, CurveBasis basis, int degree, CurveKind kind,
                                       float width0, float width1, const std::vector<Vec3>& normals);

// Point of the cubic Bézier p[0..3] at t (de Casteljau).
Vec3 cubic_bezier_point(const Vec3* p, float t);

}  // namespace dermis
