#include "dermis/render/subsurface/probe_method.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "dermis/render/subsurface/profile_from_params.h"
#include "dermis/sss/profiles/quadrature.h"

namespace dermis {

namespace {

constexpr int kMaxProbeHits = 16;
// Exit light at every candidate: candidates whose share of the probe's contribution is
// below 1 / this are kept by Russian roulette (pick_probe_hit).
constexpr double kExitLightShares = 4;

inline Vec3d to_d(Vec3 v) { return Vec3d(v); }

RGB profile_values(const sss::ProfileRGB& p, double r) {
  return {float(p.channel[0].eval(r)), float(p.channel[1].eval(r)), float(p.channel[2].eval(r))};
}

// The hits of a probe segment on the object (a per-thread buffer: no allocation per sample).
std::vector<SurfaceHit>& probe_hits(const SubsurfaceEntry& entry, const sss::ProbeSegment& seg) {
  thread_local std::vector<SurfaceHit> hits;
  hits.clear();
  entry.tracer.collect_hits(Vec3(seg.origin), Vec3(seg.direction), float(seg.length), kMaxProbeHits, hits);
  return hits;
}

// One probe: the candidates on the segment, one chosen in proportion to its contribution
// w_i = R(r_i) / pdf(h_i) (mean over the channels), with weight w_i / q_i = w_i S / s_i
// (s_i its mean, S the sum): an unbiased estimate of sum_i w_i, as uniform choice with
// weight k w_i is, but a probe that crosses the object many times (a long red probe
// through a head: 14 hits) no longer multiplies a near hit's contribution by k when it
// picks it, nor spends itself on far hits whose R is almost 0 (selection in proportion to
// the integrand among candidates: Talbot et al. 2005, "Importance Resampling for Global
// Illumination", with the candidates' exact contributions).
template <class Pdf>
bool pick_probe_hit(const sss::ProfileRGB& profile, const SubsurfaceEntry& entry, const sss::ProbeSegment& seg,
                    Sampler& sampler, Pdf&& pdf_area, SubsurfaceExit& out) {
  const std::vector<SurfaceHit>& hits = probe_hits(entry, seg);
  const float u = sampler.uniform();
  if (hits.empty()) return false;
  // The selection's running sum by hand: Distribution1D would allocate on this hot path.
  std::array<RGB, kMaxProbeHits> w;
  std::array<double, kMaxProbeHits> s;
  double total = 0;
  const std::size_t k = std::min(hits.size(), std::size_t(kMaxProbeHits));
  for (std::size_t i = 0; i < k; ++i) {
    const double pdf = pdf_area(hits[i]);
    const double r = length(to_d(hits[i].p) - to_d(entry.hit.p));
    w[i] = pdf > 0 ? profile_values(profile, r) * float(1 / pdf) : RGB(0);
    s[i] = (double(w[i][0]) + w[i][1] + w[i][2]) / 3;
    if (!std::isfinite(s[i])) return false;
    total += s[i];
  }
  if (!(total > 0)) return false;
  std::size_t chosen = k - 1;
  double below = 0;
  for (std::size_t i = 0; i < k; ++i) {
    below += s[i];
    if (double(u) * total < below) {
      chosen = i;
      break;
    }
  }
  while (s[chosen] <= 0) --chosen;  // u at the very top: the last hit with a share
  out.kind = SubsurfaceExit::Kind::ThroughLobe;
  out.hit = hits[chosen];
  out.weight = w[chosen] * float(total / s[chosen]);
  // The exit's direct light is taken at every candidate with its own w_i: the expected
  // value over the choice (sum_i (s_i / S) (w_i S / s_i) L_i), so that which candidate the
  // path leaves from adds no variance to it. A probe through a thin part (an ear, a nose)
  // meets a lit and an unlit side: chosen by R/pdf, either was the whole direct light.
  // Candidates with a small share are kept by Russian roulette with probability
  // min(1, kExitLightShares s_i / S), weighted by its inverse (unbiased): a probe costs
  // at most about kExitLightShares light samples however many times it crosses.
  // Each candidate draws from a region of its own.
  out.exit_light_gathered = true;
  if (entry.exit_light_none) return true;  // under a uniform sky alone: nothing to sample
  const uint64_t base = sampler.dimension();
  const Sampler::Position resume = sampler.position();
  for (std::size_t i = 0; i < k; ++i) {
    if (!(s[i] > 0)) continue;
    sampler.set_dimension(Sampler::region(base, 0xe117u + uint32_t(i)));
    const double keep = std::min(1.0, kExitLightShares * s[i] / total);
    if (keep < 1 && double(sampler.get1d()) >= keep) continue;
    out.gathered += w[i] * entry.exit_light(hits[i], sampler) * float(1 / keep);
  }
  sampler.restore(resume);
  return true;
}

// int_0^rho R(r) 2 pi r dr: what a plane through the entry returns (the retry's
// fallback for a textured entry; rare, so by quadrature).
double energy_within(const sss::RadialProfile& profile, double rho) {
  return sss::integrate([&](double r) { return profile.eval(r) * 2 * kPiD * r; }, 0, rho, 1e-7);
}

}  // namespace

// Channels are chosen in proportion to their albedo times the square root of their
// reach, the radius their sampling is truncated at, relative to the largest channel's
// (so that the floor, which lets every channel's hits be found, means the same at any
// scene unit). A channel's estimate is its albedo times the exit light averaged over its
// footprint, whose variance grows with the footprint; choosing channels as the square
// roots of their variances minimises the sum (Neyman allocation, as the walk's channel
// choice: sss/walk/walk_step.h channel_probabilities), and A_c sqrt(r_c) is that square
// root for a variance of A_c^2 r_c. Against the albedo alone: docs/probe-sampling.md.
RGB probe_channel_weights(const sss::ProfileRGB& profile) {
  double reach[3], largest = 0;
  for (int c = 0; c < 3; ++c) {
    reach[c] = profile.channel[c].r_max();
    if (!(reach[c] > 0) || !std::isfinite(reach[c])) reach[c] = 0;
    largest = std::max(largest, reach[c]);
  }
  RGB weights;
  for (int c = 0; c < 3; ++c) {
    const double relative = largest > 0 ? std::sqrt(reach[c] / largest) : 1.0;
    weights[c] = std::max(float(profile.channel[c].albedo() * relative), 1e-3f);
  }
  return weights;
}

ProbeMethod::ProbeMethod(const SubsurfaceParams& params, const std::vector<Texture>* textures)
    : method_(params.method),
      params_(params),
      textures_(textures),
      table_(profile_table(params)),
      profile_(std::make_unique<sss::ProfileRGB>(make_profile(params, medium_at(params), table_))) {
  if (method_ == Method::Disk || method_ == Method::DiskSingleAxis) {
    for (int v = 0; v < strategy_count(); ++v)
      disks_.push_back(std::make_unique<sss::DiskProbeSampler>(*profile_, probe_channel_weights(*profile_), axes(v)));
  } else {
    // With textured parameters these are the tables of the textures' mean, stretched
    // per entry point (sphere_lines.h, radius_scale).
    line_tables_ = std::make_unique<sss::SphereLineTablesRGB>(*profile_);
    lines_ = std::make_unique<sss::SphereLineSampler>(*line_tables_, probe_channel_weights(*profile_));
  }
}

sss::ProbeAxisProbabilities ProbeMethod::axes(int strategy) const {
  if (method_ != Method::Disk) return sss::ProbeAxisProbabilities::single_axis();
  const double normal =
      params_.normal_axis_given
          ? double(params_.normal_axis)
          : kDiskNormalAxisShares[std::size_t(strategy >= 0 && strategy < strategy_count() ? strategy : 0)];
  return {normal, (1 - normal) / 2, (1 - normal) / 2};
}

double ProbeMethod::max_radius() const { return !disks_.empty() ? disks_[0]->max_radius() : lines_->max_radius(); }

double ProbeMethod::max_radius(const sss::ProfileRGB& entry_profile) const {
  if (!params_.textured()) return max_radius();
  return !disks_.empty()
             ? sss::DiskProbeSampler(entry_profile, probe_channel_weights(entry_profile), axes(0)).max_radius()
             : lines_at(entry_profile).max_radius();
}

sss::SphereLineSampler ProbeMethod::lines_at(const sss::ProfileRGB& profile) const {
  // Each channel's table stretched to the entry profile's reach: exact for the profiles
  // that one length scales (Burley, Gaussian, cubic), unbiased for the others.
  std::array<double, 3> scale{1, 1, 1};
  for (int c = 0; c < 3; ++c) {
    const double mean_reach = profile_->channel[c].r_max(), reach = profile[c].r_max();
    if (mean_reach > 0 && reach > 0 && std::isfinite(reach)) scale[c] = reach / mean_reach;
  }
  return sss::SphereLineSampler(*line_tables_, probe_channel_weights(profile), scale);
}

bool ProbeMethod::sample_disk(const sss::ProfileRGB& profile, const sss::DiskProbeSampler& disk,
                              const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const {
  const sss::ProbeFrame frame = sss::ProbeFrame::around(to_d(entry.hit.p), to_d(entry.hit.ng));
  // One number for the axis, the strategy and the radius, cut in turn, and the angle: over
  // a pixel's samples each (axis, strategy)'s radii and angles are stratified together.
  // Against a number for each choice (the sampler's dimensions are independent of one
  // another) the variance falls (docs/probe-sampling.md, "One number for the choices").
  // With independent numbers (the render's pilot) both forms have one
  // distribution, and a number per choice keeps what the pilot's strategies share: the
  // same radius and angle for the same draw whatever their axis probabilities, which its
  // paired comparison of them needs (cut from one number, 0.95's radius is not 0.75's).
  sss::DiskProbeSample s;
  if (sampler.kind() == SamplerKind::Independent) {
    const float u_axis = sampler.get1d(), u_strategy = sampler.get1d();
    const Vec2 u_disk = sampler.get2d();
    s = disk.sample(frame, u_axis, u_strategy, u_disk.x, u_disk.y);
  } else {
    const Vec2d u = sampler.get2d_double();
    s = disk.sample(frame, u.x, u.y);
  }
  return pick_probe_hit(
      profile, entry, s.segment, sampler,
      [&](const SurfaceHit& h) { return disk.pdf_area(frame, to_d(h.p), to_d(h.ng)); }, out);
}

bool ProbeMethod::sample_lines(const sss::ProfileRGB& profile, const sss::SphereLineSampler& lines,
                               const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const {
  const Vec3d p = to_d(entry.hit.p);
  if (method_ == Method::SphereLines) {
    const double u = sampler.uniform_double();  // the channel and the radius (as the disk's)
    const Vec2 u_first = sampler.get2d(), u_second = sampler.get2d();
    sss::SphereLineSample s = lines.sample(p, u, {u_first.x, u_first.y}, {u_second.x, u_second.y});
    return pick_probe_hit(
        profile, entry, s.segment, sampler, [&](const SurfaceHit& h) { return lines.pdf_area(p, to_d(h.p)); }, out);
  }
  // The Cycles page's scheme: retry up to 8 lines until one hits, else stay at P.
  const std::vector<SurfaceHit>* hits = nullptr;
  auto count_hits = [&](const sss::ProbeSegment& seg) {
    hits = &probe_hits(entry, seg);
    return int(hits->size());
  };
  sss::SphereLineRetry r = lines.sample_retry(p, sampler, count_hits);
  out.kind = SubsurfaceExit::Kind::ThroughLobe;
  if (r.hits == 0) {
    out.hit = entry.hit;  // the fallback's weight: the tables' own, or the entry profile's
    for (int c = 0; c < 3; ++c)
      out.weight[c] =
          float(&profile != profile_.get() ? energy_within(profile[c], lines.max_radius()) : lines.fallback_weight(c));
    return true;
  }
  const SurfaceHit& h = (*hits)[r.chosen];
  double d = length(to_d(h.p) - p);
  double pdf = lines.pdf_area(p, to_d(h.p));
  out.hit = h;
  for (int c = 0; c < 3; ++c)
    out.weight[c] = float(sss::SphereLineSampler::retry_weight(profile.channel[c].eval(d), r.hits, pdf));
  return true;
}

bool ProbeMethod::sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const {
  const int strategy = entry.strategy >= 0 && entry.strategy < strategy_count() ? entry.strategy : 0;
  if (!params_.textured() && !entry.wavelengths)
    return !disks_.empty() ? sample_disk(*profile_, *disks_[std::size_t(strategy)], entry, sampler, out)
                           : sample_lines(*profile_, *lines_, entry, sampler, out);
  // The entry point's own parameters, at the path's wavelengths on a spectral path: its
  // profile (per wavelength) and probe sampler on the stack. The channel MIS of the probes
  // is then MIS over the path's wavelengths.
  MediumAt at = medium_at(params_, textures_, texture_context(entry.hit));
  if (entry.wavelengths) at = medium_at_wavelengths(params_, at, *entry.wavelengths);
  const sss::ProfileRGB profile = make_profile(params_, at, table_);
  if (!disks_.empty()) {
    const sss::DiskProbeSampler disk(profile, probe_channel_weights(profile), axes(strategy));
    return sample_disk(profile, disk, entry, sampler, out);
  }
  return sample_lines(profile, lines_at(profile), entry, sampler, out);
}

}  // namespace dermis
