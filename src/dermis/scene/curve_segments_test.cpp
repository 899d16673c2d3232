// pbrt-v4's curve bases as cubic Bézier segments: each converted segment traces the same
// points as the curve written in its own basis, evaluated here from the basis functions
// themselves (independent of the conversion formulas).
#include "dermis/scene/curve_segments.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/core/vec.h"

namespace dermis {
namespace {

const std::vector<Vec3> kPoints = {{0, 0, 0}, {1, 2, 0}, {3, 2, 1}, {4, -1, 2}, {6, 0, 0}, {7, 3, -1}, {9, 1, 1}};

void expect_near(Vec3 a, Vec3 b, const char* what, float t) {
  EXPECT_NEAR(a.x, b.x, 1e-5f) << what << " t " << t;
  EXPECT_NEAR(a.y, b.y, 1e-5f) << what << " t " << t;
  EXPECT_NEAR(a.z, b.z, 1e-5f) << what << " t " << t;
}

TEST(CurveSegments, SegmentCountsAsPbrtV4) {
  EXPECT_EQ(curve_segment_count(4, CurveBasis::Bezier, 3), 1u);
  EXPECT_EQ(curve_segment_count(7, CurveBasis::Bezier, 3), 2u);
  EXPECT_EQ(curve_segment_count(7, CurveBasis::Bezier, 2), 3u);
  EXPECT_EQ(curve_segment_count(7, CurveBasis::BSpline, 3), 4u);
  EXPECT_EQ(curve_segment_count(7, CurveBasis::BSpline, 2), 5u);
  EXPECT_THROW(curve_segment_count(5, CurveBasis::Bezier, 3), std::invalid_argument);
  EXPECT_THROW(curve_segment_count(3, CurveBasis::BSpline, 3), std::invalid_argument);
  EXPECT_THROW(curve_segment_count(4, CurveBasis::Bezier, 4), std::invalid_argument);
}

TEST(CurveSegments, CubicBezierSegmentsAreTheControlPoints) {
  const CurveSegments c = curve_to_bezier_segments(kPoints, CurveBasis::Bezier, 3, CurveKind::Flat, 1, 1, {});
  ASSERT_EQ(c.segment_count(), 2u);
  for (int i = 0; i < 4; ++i) expect_near(c.points[4 + std::size_t(i)], kPoints[3 + std::size_t(i)], "point", 0);
}

TEST(CurveSegments, QuadraticBezierIsTheSameCurve) {
  const CurveSegments c = curve_to_bezier_segments(kPoints, CurveBasis::Bezier, 2, CurveKind::Flat, 1, 1, {});
  ASSERT_EQ(c.segment_count(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
    for (float t : {0.0f, 0.2f, 0.5f, 0.9f, 1.0f}) {
      const Vec3* p = &kPoints[2 * k];
      const Vec3 want = p[0] * ((1 - t) * (1 - t)) + p[1] * (2 * t * (1 - t)) + p[2] * (t * t);
      expect_near(cubic_bezier_point(&c.points[4 * k], t), want, "quadratic Bézier", t);
    }
}

TEST(CurveSegments, UniformBSplinesAreTheSameCurve) {
  const CurveSegments c3 = curve_to_bezier_segments(kPoints, CurveBasis::BSpline, 3, CurveKind::Flat, 1, 1, {});
  const CurveSegments c2 = curve_to_bezier_segments(kPoints, CurveBasis::BSpline, 2, CurveKind::Flat, 1, 1, {});
  for (float t : {0.0f, 0.3f, 0.5f, 0.8f, 1.0f}) {
    // Uniform B-spline basis functions (de Boor, A Practical Guide to Splines, ch. IX).
    const float s = 1 - t;
    for (std::size_t k = 0; k < c3.segment_count(); ++k) {
      const Vec3* p = &kPoints[k];
      const Vec3 want = (p[0] * (s * s * s) + p[1] * (3 * t * t * t - 6 * t * t + 4) +
                         p[2] * (-3 * t * t * t + 3 * t * t + 3 * t + 1) + p[3] * (t * t * t)) /
                        6.0f;
      expect_near(cubic_bezier_point(&c3.points[4 * k], t), want, "cubic B-spline", t);
    }
    for (std::size_t k = 0; k < c2.segment_count(); ++k) {
      const Vec3* p = &kPoints[k];
      const Vec3 want = (p[0] * (s * s) + p[1] * (-2 * t * t + 2 * t + 1) + p[2] * (t * t)) * 0.5f;
      expect_near(cubic_bezier_point(&c2.points[4 * k], t), want, "quadratic B-spline", t);
    }
  }
}

// pbrt-v4: segment k of n runs from width lerp(k/n) to lerp((k+1)/n) of width0, width1.
TEST(CurveSegments, WidthIsLinearFromWidth0ToWidth1) {
  const CurveSegments c = curve_to_bezier_segments(kPoints, CurveBasis::BSpline, 3, CurveKind::Flat, 2, 0.4f, {});
  const std::size_t n = c.segment_count();
  for (std::size_t k = 0; k < n; ++k)
    for (int i = 0; i < 4; ++i)
      EXPECT_NEAR(c.widths[4 * k + std::size_t(i)], 2 + (0.4f - 2) * (float(k) + float(i) / 3) / float(n), 1e-6f);
}

TEST(CurveSegments, RibbonsNeedOneNormalPerSegmentEnd) {
  const std::vector<Vec3> bezier(kPoints.begin(), kPoints.begin() + 4);
  EXPECT_THROW(curve_to_bezier_segments(bezier, CurveBasis::Bezier, 3, CurveKind::Ribbon, 1, 1, {{0, 0, 1}}),
               std::invalid_argument);
  EXPECT_THROW(curve_to_bezier_segments(bezier, CurveBasis::Bezier, 3, CurveKind::Ribbon, 1, 1, {{0, 0, 1}, {0, 0, 0}}),
               std::invalid_argument);
  const CurveSegments c =
      curve_to_bezier_segments(bezier, CurveBasis::Bezier, 3, CurveKind::Ribbon, 1, 1, {{0, 0, 2}, {0, 3, 0}});
  ASSERT_EQ(c.normals.size(), 4u);
  expect_near(c.normals[0], Vec3(0, 0, 1), "first normal", 0);
  expect_near(c.normals[3], Vec3(0, 1, 0), "last normal", 1);
}

// pbrt-v4's ribbon normal turns by spherical interpolation: the normal of Embree's cubic
// Bézier of the control normals follows slerp within 0.2 degrees over a 90-degree turn
// (0.08 computed: a cubic against a circular arc)
// (exactly at 0, 1/3, 2/3, 1; linear interpolation is 4 degrees off at 1/4).
TEST(CurveSegments, RibbonNormalsTurnAsSlerp) {
  const std::vector<Vec3> bezier(kPoints.begin(), kPoints.begin() + 4);
  const CurveSegments c =
      curve_to_bezier_segments(bezier, CurveBasis::Bezier, 3, CurveKind::Ribbon, 1, 1, {{0, 0, 1}, {0, 1, 0}});
  for (int i = 0; i <= 12; ++i) {
    const float u = float(i) / 12;
    const Vec3 n = normalize(cubic_bezier_point(c.normals.data(), u));
    const double angle = std::atan2(double(n.y), double(n.z)) * 180 / kPiD;  // from z toward y
    EXPECT_NEAR(angle, 90.0 * u, i % 4 == 0 ? 1e-3 : 0.2) << "u " << u;
  }
}

}  // namespace
}  // namespace dermis
