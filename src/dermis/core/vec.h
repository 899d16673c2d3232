// Small fixed-size vectors: the geometry of the renderer (float) and of the
// simulators (double).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace dermis {

template <class T>
struct Vec2T {
  T x = 0, y = 0;
  constexpr Vec2T() = default;
  constexpr Vec2T(T x_, T y_) : x(x_), y(y_) {}
  constexpr T operator[](int i) const { return i == 0 ? x : y; }
  constexpr T& operator[](int i) { return i == 0 ? x : y; }
  constexpr Vec2T operator+(Vec2T b) const { return {x + b.x, y + b.y}; }
  constexpr Vec2T operator-(Vec2T b) const { return {x - b.x, y - b.y}; }
  constexpr Vec2T operator*(T s) const { return {x * s, y * s}; }
};

template <class T>
struct Vec3T {
  T x = 0, y = 0, z = 0;
  constexpr Vec3T() = default;
  constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  template <class U>
  constexpr explicit Vec3T(Vec3T<U> v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}
  constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3T operator-() const { return {-x, -y, -z}; }
  constexpr Vec3T operator+(Vec3T b) const { return {x + b.x, y + b.y, z + b.z}; }
  constexpr Vec3T operator-(Vec3T b) const { return {x - b.x, y - b.y, z - b.z}; }
  constexpr Vec3T operator*(T s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3T operator/(T s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3T& operator+=(Vec3T b) {
    x += b.x;
    y += b.y;
    z += b.z;
    return *this;
  }
  constexpr Vec3T& operator-=(Vec3T b) {
    x -= b.x;
    y -= b.y;
    z -= b.z;
    return *this;
  }
  constexpr Vec3T& operator*=(T s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3T&) const = default;
};

template <class T>
constexpr Vec3T<T> operator*(T s, Vec3T<T> v) {
  return v * s;
}
template <class T>
constexpr T dot(Vec3T<T> a, Vec3T<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
constexpr Vec3T<T> cross(Vec3T<T> a, Vec3T<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
inline T length_squared(Vec3T<T> v) {
  return dot(v, v);
}
template <class T>
inline T length(Vec3T<T> v) {
  return std::sqrt(dot(v, v));
}
template <class T>
inline Vec3T<T> normalize(Vec3T<T> v) {
  return v / length(v);
}
template <class T>
inline T distance(Vec3T<T> a, Vec3T<T> b) {
  return length(a - b);
}
template <class T>
inline Vec3T<T> min(Vec3T<T> a, Vec3T<T> b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <class T>
inline Vec3T<T> max(Vec3T<T> a, Vec3T<T> b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <class T>
inline Vec3T<T> abs(Vec3T<T> v) {
  return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}
template <class T>
inline T max_component(Vec3T<T> v) {
  return std::max(v.x, std::max(v.y, v.z));
}
// Flips v to the hemisphere of n.
template <class T>
inline Vec3T<T> face_forward(Vec3T<T> v, Vec3T<T> n) {
  return dot(v, n) < 0 ? -v : v;
}

using Vec2 = Vec2T<float>;
using Vec3 = Vec3T<float>;
using Vec2d = Vec2T<double>;
using Vec3d = Vec3T<double>;
using Point3 = Vec3;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr double kPiD = 3.14159265358979323846;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInv2Pi = 0.5f / kPi;
inline constexpr float kInv4Pi = 0.25f / kPi;

template <class T>
constexpr T sqr(T x) {
  return x * x;
}
inline float safe_sqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
inline double safe_sqrt(double x) { return std::sqrt(std::max(0.0, x)); }

}  // namespace dermis
