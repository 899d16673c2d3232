// Diffusion profiles sampled with probe rays (seed 002 and King et al. 2013): a
// segment or line is drawn near the entry point, its hits on the object are the
// candidate exits, one is chosen uniformly and weighted profile / area pdf. Probes:
// disk projection with axis and channel MIS ("disk"), the same along the normal only
// ("disk-single-axis"), random lines through a sphere ("sphere-lines"), and the Cycles
// page's retry-until-hit variant ("sphere-lines-retry").
#pragma once

#include <memory>

#include "dermis/scene/subsurface_params.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/sss/probe/disk_probe.h"
#include "dermis/sss/probe/sphere_lines.h"
#include "dermis/sss/profiles/profile.h"

namespace dermis {

class ProbeMethod {
 public:
  explicit ProbeMethod(const SubsurfaceParams& params);

  bool sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const;

  const sss::ProfileRGB& profile() const { return *profile_; }
  // The sphere-line sampler (sphere-lines, sphere-lines-retry), else null.
  const sss::SphereLineSampler* lines() const { return lines_.get(); }
  // The largest distance from the entry at which a probe can find an exit.
  double max_radius() const;

 private:
  using Method = SubsurfaceParams::Method;
  Method method_;
  std::unique_ptr<sss::ProfileRGB> profile_;
  std::unique_ptr<sss::DiskProbeSampler> disk_;                // disk, disk-single-axis
  std::unique_ptr<sss::SphereLineTablesRGB> line_tables_;      // sphere-lines(-retry)
  std::unique_ptr<sss::SphereLineSampler> lines_;
};

}  // namespace dermis
