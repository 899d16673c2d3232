// Diffusion profiles sampled with probe rays (seed 002 and King et al. 2013): a
// segment or line is drawn near the entry point, its hits on the object are the
// candidate exits, one is chosen in proportion to its profile / area pdf and weighted so
// that the estimate is their sum (pick_probe_hit, probe_method.cpp; the retry variant
// chooses uniformly, as the Cycles page does). Probes:
// disk projection with axis and channel MIS ("disk"), the same along the normal only
// ("disk-single-axis"), random lines through a sphere ("sphere-lines"), and the Cycles
// page's retry-until-hit variant ("sphere-lines-retry").
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "dermis/materials/texture.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/scene/subsurface_params.h"
#include "dermis/sss/probe/disk_probe.h"
#include "dermis/sss/probe/sphere_lines.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/profiles/tabulated.h"

namespace dermis {

// The probability weights of the probe's channels (disk and sphere-line samplers):
// albedo x sqrt(reach / the largest channel's reach), reach the radius the channel's
// sampling is truncated at, at least 1e-3 (the Neyman allocation; probe_method.cpp).
RGB probe_channel_weights(const sss::ProfileRGB& profile);

// The disk's sampling strategies (SubsurfaceEntry::strategy): the probability of probing
// along the normal, the tangent and the bitangent sharing the rest. Strategy 0, the
// default, probes along the normal with 0.75; the render's pilot (render/subsurface_pilot.h)
// measures the others: 0.95, and King et al. 2013's 0.5, 0.25, 0.25 (as Cycles). Why: a
// probe along T or B runs parallel to a surface that is flat at the profile's reach and
// misses it, so half of King et al.'s probes find nothing there, while an object that the
// profile's reach wraps (a sphere smaller than the mean free path) needs them
// (docs/probe-sampling.md, "The probes' axes"). Any probabilities keep the estimate
// unbiased: the area density sums over the axes with them.
inline constexpr std::array<double, 3> kDiskNormalAxisShares{0.75, 0.95, 0.5};

// Textured parameters, and every spectral path (at its wavelengths): the profile and its
// probe sampler are made at each entry point from the parameters there, on the stack (no
// allocation for the closed-form profiles), and the exit is weighted with that profile. The disk sampler is
// closed-form; the sphere lines stretch the tables of the textures' mean to the entry profile's reach (sphere_lines.h).
class ProbeMethod {
 public:
  // textures: the scene's (outlives the method).
  ProbeMethod(const SubsurfaceParams& params, const std::vector<Texture>* textures);

  bool sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const;

  // The sampling strategies the render's pilot may choose among: the disk's axis
  // probabilities (kDiskNormalAxisShares), unless its parameters give them; one for the
  // other probes.
  int strategy_count() const {
    return method_ == Method::Disk && !params_.normal_axis_given ? int(kDiskNormalAxisShares.size()) : 1;
  }
  // The probe axes' probabilities of a strategy (its index clamped to the default, 0;
  // the given `normalaxis` for every strategy).
  sss::ProbeAxisProbabilities axes(int strategy) const;

  const sss::ProfileRGB& profile() const { return *profile_; }
  // The sphere-line sampler (sphere-lines, sphere-lines-retry), else null.
  const sss::SphereLineSampler* lines() const { return lines_.get(); }
  // The largest distance from the entry at which a probe can find an exit.
  double max_radius() const;
  // The same at an entry point whose (textured) parameters give `entry_profile`.
  double max_radius(const sss::ProfileRGB& entry_profile) const;

 private:
  using Method = SubsurfaceParams::Method;
  bool sample_disk(const sss::ProfileRGB& profile, const sss::DiskProbeSampler& disk, const SubsurfaceEntry& entry,
                   Sampler& sampler, SubsurfaceExit& out) const;
  bool sample_lines(const sss::ProfileRGB& profile, const sss::SphereLineSampler& lines, const SubsurfaceEntry& entry,
                    Sampler& sampler, SubsurfaceExit& out) const;
  // The sphere-line sampler for an entry point's profile (textured parameters).
  sss::SphereLineSampler lines_at(const sss::ProfileRGB& profile) const;

  Method method_;
  SubsurfaceParams params_;
  const std::vector<Texture>* textures_;
  std::shared_ptr<const sss::ProfileTable> table_;  // the tabulated profile's
  std::unique_ptr<sss::ProfileRGB> profile_;        // the constant parameters' profile
  // disk (one per strategy), disk-single-axis (one): empty for the sphere lines.
  std::vector<std::unique_ptr<sss::DiskProbeSampler>> disks_;
  std::unique_ptr<sss::SphereLineTablesRGB> line_tables_;  // sphere-lines(-retry)
  std::unique_ptr<sss::SphereLineSampler> lines_;
};

}  // namespace dermis
