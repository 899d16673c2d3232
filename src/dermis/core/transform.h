// Affine transforms as 4x4 matrices with their inverses (pbrt's conventions:
// column vectors, M * p).
#pragma once

#include <array>

#include "dermis/core/vec.h"

namespace dermis {

struct Mat4 {
  // m[row][col]
  std::array<std::array<double, 4>, 4> m{};
  static Mat4 identity();
  Mat4 operator*(const Mat4& b) const;
  Mat4 transposed() const;
  // Returns false when singular.
  bool invert(Mat4& out) const;
  bool operator==(const Mat4&) const = default;
};

class Transform {
 public:
  Transform() : m_(Mat4::identity()), inv_(Mat4::identity()) {}
  Transform(const Mat4& m, const Mat4& inv) : m_(m), inv_(inv) {}
  // Throws std::invalid_argument when m is singular.
  explicit Transform(const Mat4& m);

  static Transform translate(Vec3d d);
  static Transform scale(Vec3d s);
  // Rotation by angle_degrees about axis (pbrt's Rotate directive).
  static Transform rotate(double angle_degrees, Vec3d axis);
  // pbrt's LookAt: returns camera-from-world. Throws on degenerate input.
  static Transform look_at(Vec3d eye, Vec3d look, Vec3d up);
  static Transform perspective(double fov_degrees, double near, double far);

  Transform operator*(const Transform& b) const { return {m_ * b.m_, b.inv_ * inv_}; }
  Transform inverse() const { return {inv_, m_}; }
  const Mat4& matrix() const { return m_; }
  const Mat4& inverse_matrix() const { return inv_; }
  bool is_identity() const { return m_ == Mat4::identity(); }
  // True when the transform flips orientation (negative determinant of the 3x3 part).
  bool swaps_handedness() const;

  Vec3 point(Vec3 p) const;
  Vec3 vector(Vec3 v) const;
  // Normals transform with the inverse transpose.
  Vec3 normal(Vec3 n) const;
  Vec3d point(Vec3d p) const;
  Vec3d vector(Vec3d v) const;

  bool operator==(const Transform& o) const { return m_ == o.m_; }

 private:
  Mat4 m_, inv_;
};

}  // namespace dermis
