// What a path counts as it goes: rays traced and paths stopped by a guard. One per
// thread; the renderer sums them.
#pragma once

#include <cstdint>
#include <vector>

#include "dermis/geometry/ray.h"

namespace dermis {

struct PathCounters {
  uint64_t rays = 0;  // closest-hit and shadow rays traced
  uint64_t truncated =
      0;  // paths stopped by the interface-crossing guard, a walk's step cap or a stalled medium tracking
  // When set, every ray traced (closest-hit, shadow, probe and walk rays) is appended
  // here; benchmarks replay them.
  std::vector<Ray>* recorded_rays = nullptr;

  void count(const Ray& r) {
    ++rays;
    if (recorded_rays) recorded_rays->push_back(r);
  }
};

}  // namespace dermis
