#include "dermis/core/transform.h"

#include <cmath>
#include <stdexcept>

namespace dermis {

Mat4 Mat4::identity() {
  Mat4 r;
  for (int i = 0; i < 4; ++i) r.m[i][i] = 1;
  return r;
}

Mat4 Mat4::operator*(const Mat4& b) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

Mat4 Mat4::transposed() const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
  return r;
}

bool Mat4::invert(Mat4& out) const {
  // Gauss-Jordan elimination with partial pivoting.
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = m[i][j];
      a[i][j + 4] = i == j ? 1 : 0;
    }
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (std::abs(a[p][c]) < 1e-300) return false;
    if (p != c)
      for (int j = 0; j < 8; ++j) std::swap(a[p][j], a[c][j]);
    double inv = 1.0 / a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      double f = a[r][c];
      if (f == 0) continue;
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out.m[i][j] = a[i][j + 4];
  return true;
}

Transform::Transform(const Mat4& m) : m_(m) {
  if (!m.invert(inv_)) throw std::invalid_argument("singular transformation matrix");
}

Transform Transform::translate(Vec3d d) {
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  m.m[0][3] = d.x;
  m.m[1][3] = d.y;
  m.m[2][3] = d.z;
  inv.m[0][3] = -d.x;
  inv.m[1][3] = -d.y;
  inv.m[2][3] = -d.z;
  return {m, inv};
}

Transform Transform::scale(Vec3d s) {
  if (s.x == 0 || s.y == 0 || s.z == 0) throw std::invalid_argument("scale by zero is singular");
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  m.m[0][0] = s.x;
  m.m[1][1] = s.y;
  m.m[2][2] = s.z;
  inv.m[0][0] = 1 / s.x;
  inv.m[1][1] = 1 / s.y;
  inv.m[2][2] = 1 / s.z;
  return {m, inv};
}

Transform Transform::rotate(double angle_degrees, Vec3d axis) {
  double len = length(axis);
  if (len == 0) throw std::invalid_argument("rotation axis has zero length");
  Vec3d a = axis / len;
  double th = angle_degrees * kPiD / 180.0;
  double s = std::sin(th), c = std::cos(th);
  Mat4 m = Mat4::identity();
  // Rodrigues' rotation formula, as in pbrt-v4's Rotate().
  m.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
  m.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
  m.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
  m.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
  m.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
  m.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
  m.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
  m.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
  m.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
  return {m, m.transposed()};
}

Transform Transform::look_at(Vec3d eye, Vec3d look, Vec3d up) {
  Vec3d dir = look - eye;
  if (length(dir) == 0) throw std::invalid_argument("LookAt: eye and look-at point coincide");
  dir = normalize(dir);
  if (length(up) == 0) throw std::invalid_argument("LookAt: up vector has zero length");
  Vec3d right = cross(normalize(up), dir);
  if (length(right) < 1e-12) throw std::invalid_argument("LookAt: up vector is parallel to the viewing direction");
  right = normalize(right);
  Vec3d new_up = cross(dir, right);
  Mat4 world_from_camera = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    world_from_camera.m[i][0] = right[i];
    world_from_camera.m[i][1] = new_up[i];
    world_from_camera.m[i][2] = dir[i];
    world_from_camera.m[i][3] = eye[i];
  }
  Mat4 camera_from_world;
  world_from_camera.invert(camera_from_world);
  return {camera_from_world, world_from_camera};
}

bool Transform::swaps_handedness() const {
  const auto& a = m_.m;
  double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  return det < 0;
}

Vec3d Transform::point(Vec3d p) const {
  const auto& a = m_.m;
  double x = a[0][0] * p.x + a[0][1] * p.y + a[0][2] * p.z + a[0][3];
  double y = a[1][0] * p.x + a[1][1] * p.y + a[1][2] * p.z + a[1][3];
  double z = a[2][0] * p.x + a[2][1] * p.y + a[2][2] * p.z + a[2][3];
  double w = a[3][0] * p.x + a[3][1] * p.y + a[3][2] * p.z + a[3][3];
  return w == 1 ? Vec3d(x, y, z) : Vec3d(x, y, z) / w;
}

Vec3d Transform::vector(Vec3d v) const {
  const auto& a = m_.m;
  return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
          a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

Vec3 Transform::point(Vec3 p) const { return Vec3(point(Vec3d(p))); }
Vec3 Transform::vector(Vec3 v) const { return Vec3(vector(Vec3d(v))); }

Vec3 Transform::normal(Vec3 n) const {
  const auto& a = inv_.m;
  return Vec3(float(a[0][0] * n.x + a[1][0] * n.y + a[2][0] * n.z),
              float(a[0][1] * n.x + a[1][1] * n.y + a[2][1] * n.z),
              float(a[0][2] * n.x + a[1][2] * n.y + a[2][2] * n.z));
}

Transform Transform::perspective(double fov_degrees, double n, double f) {
  Mat4 persp{};
  persp.m[0][0] = 1;
  persp.m[1][1] = 1;
  persp.m[2][2] = f / (f - n);
  persp.m[2][3] = -f * n / (f - n);
  persp.m[3][2] = 1;
  double inv_tan = 1.0 / std::tan(fov_degrees * kPiD / 360.0);
  return Transform::scale({inv_tan, inv_tan, 1}) * Transform(persp);
}

}  // namespace dermis
