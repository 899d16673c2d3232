// Orthonormal frames: local shading coordinates with z along the normal.
#pragma once

#include "dermis/core/vec.h"

namespace dermis {

// Duff et al. 2017, "Building an Orthonormal Basis, Revisited", Listing 3.
template <class T>
inline void orthonormal_basis(Vec3T<T> n, Vec3T<T>& t, Vec3T<T>& b) {
  T sign = std::copysign(T(1), n.z);
  T a = T(-1) / (sign + n.z);
  T c = n.x * n.y * a;
  t = {T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

template <class T>
struct FrameT {
  Vec3T<T> s, t, n;  // tangent, bitangent, normal
  FrameT() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
  explicit FrameT(Vec3T<T> normal) : n(normal) { orthonormal_basis(n, s, t); }
  Vec3T<T> to_local(Vec3T<T> v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3T<T> to_world(Vec3T<T> v) const { return s * v.x + t * v.y + n * v.z; }
};

using Frame = FrameT<float>;
using Framed = FrameT<double>;

}  // namespace dermis
