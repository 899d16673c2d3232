// The boundary of a walk's medium seen from inside: the first hit of a ray (a walk's
// Tracer answers with it; random_walk.h).
#pragma once

#include "dermis/core/vec.h"

namespace dermis::sss {

// The first hit of a ray, n the OUTWARD normal there.
struct BoundaryHit {
  bool hit = false;
  float t = 0;
  Vec3 p, n;
};

}  // namespace dermis::sss
