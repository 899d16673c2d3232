#include "dermis/render/subsurface/walk_method.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>

#include "dermis/core/frame.h"
#include "dermis/core/henyey_greenstein.h"
#include "dermis/core/microfacet.h"
#include "dermis/core/warp.h"
#include "dermis/geometry/shading_normal.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/fresnel.h"
#include "dermis/materials/null_scattering.h"
#include "dermis/render/subsurface/heterogeneous_walk.h"

namespace dermis {

namespace {

sss::WalkSampling walk_sampling(SubsurfaceParams::WalkSampling s) {
  switch (s) {
    case SubsurfaceParams::WalkSampling::Classical:
      return sss::WalkSampling::Classical;
    case SubsurfaceParams::WalkSampling::Dwivedi:
      return sss::WalkSampling::Dwivedi;
    case SubsurfaceParams::WalkSampling::Mis:
      return sss::WalkSampling::Mis;
  }
  return sss::WalkSampling::Mis;
}

constexpr int kMaxInternalReflections = 256;
// Light sampled through the smooth boundary (WalkMethod::refracted_light_at): always taken
// where the flight's transmittance to the entry plane is above this, less often below.
constexpr float kRefractedLightFullTransmittance = 0.2f;
constexpr float kRefractedLightLeastChance = 0.05f;

// The chance that light is sampled through the boundary at the scattering event y: the
// flight's transmittance to the entry plane (`plane`: the entry point, its outward
// normal) in the most transmissive channel, over kRefractedLightFullTransmittance, at
// least kRefractedLightLeastChance. A function of y alone; deep in the medium few samples
// would reach the boundary. Russian roulette: the sample, when taken, is weighed by its
// inverse (unbiased for any chance above zero).
float refracted_light_chance(const sss::MixtureWalkStep<3>& step, const SurfaceHit& plane, Vec3 y) {
  const double depth = std::max(0.0f, dot(plane.p - y, plane.ng));
  double transmittance = 0;
  for (std::size_t c = 0; c < 3; ++c) transmittance = std::max(transmittance, std::exp(-step.sigma_t()[c] * depth));
  return std::clamp(float(transmittance) / kRefractedLightFullTransmittance, kRefractedLightLeastChance, 1.0f);
}
// In a grid interior the medium between y and the plane is not one sigma_t: light is sampled
// at every scattering event (a chance of one).
float refracted_light_chance(const SubsurfaceEntry& entry, const sss::MixtureWalkStep<3>& step, const SurfaceHit& plane,
                             Vec3 y) {
  return entry.interior ? 1.0f : refracted_light_chance(step, plane, y);
}

// The Henyey-Greenstein anisotropy the walk scatters with: the grid interior's, or the step's.
float phase_g(const SubsurfaceEntry& entry, const sss::MixtureWalkStep<3>& step) {
  return entry.interior ? entry.interior->g : float(step.g());
}

// The plane light is refracted through at the scattering event y, a function of y alone:
// - toward the key light (lights_from_inside.h, KeyLight): a ray from y toward it finds the
//   boundary that faces it (normal n0); the flight that refracts toward it through that
//   plane finds where it really leaves, whose normal is taken: one step of the search for
//   the point where the path from y refracts toward the light (Walter et al. 2009, sec. 4,
//   which solves it by Newton's method); on a curved object it turns the plane toward the
//   part of the boundary the light comes through;
// - without a key light: the boundary's normal where a ray along the entry normal leaves;
// - else (no such boundary ahead) the entry normal.
Vec3 refracted_light_normal(const SubsurfaceEntry& entry, Vec3 y, float eta) {
  Vec3 toward = entry.hit.ng;
  const bool key = entry.lights_from_inside->key_direction(y, toward);
  SurfaceHit exit;
  if (!entry.tracer.first_boundary(Ray{y, toward}, exit) || !entry.tracer.contains(exit) || !(dot(exit.ng, toward) > 0))
    return entry.hit.ng;
  const Vec3 n0 = normalize(exit.ng);
  if (!key) return n0;
  const std::optional<Vec3> flight = refracted_in(toward, n0, eta);
  if (flight && entry.tracer.first_boundary(Ray{y, *flight}, exit) && entry.tracer.contains(exit) &&
      dot(exit.ng, *flight) > 0 && dot(exit.ng, toward) > 0)
    return normalize(exit.ng);
  return n0;
}
// A walk leaving the surface at a smaller cosine to its normal starts off the surface
// (WalkMethod::walk): along its line, the surface offset's depth lies up to ten offsets on.
constexpr float kGrazingCos = 0.1f;

std::atomic<uint64_t> g_next_method_id{0};

// The step sampler a thread built last for a textured medium, and what it was built
// from: the textures' values at the entry and the boundary's alpha there. The camera's
// first entry takes two or more walks from one point (one medium), and a texture
// repeats its values over whole regions. The medium needs the albedo inversion in each
// channel, and the step Dwivedi's eigenvalue in each (sss/walk/); reusing them is exact.
struct LastTexturedStep {
  uint64_t method = ~uint64_t(0);
  std::size_t strategy = 0;
  MediumAt at;
  float boundary_alpha = 0;
  bool walkable = false;  // every channel has a positive, finite extinction
  std::optional<sss::MixtureWalkStep<3>> step;
  bool matches(uint64_t m, std::size_t s, const MediumAt& a, float alpha) const {
    return method == m && strategy == s && boundary_alpha == alpha && at.sigma_a == a.sigma_a &&
           at.sigma_s == a.sigma_s && at.reflectance == a.reflectance && at.mfp == a.mfp && at.scale == a.scale;
  }
};
thread_local LastTexturedStep t_last_textured_step;

sss::WalkMedium walk_medium(const Coefficients& k, float g) {
  sss::WalkMedium m;
  m.sigma_s = k.sigma_s;
  m.sigma_t = k.sigma_a + k.sigma_s;
  m.g = g;
  return m;
}

// The step of a strategy: short_walk_guided_shares where the rule applies.
sss::MixtureWalkStep<3> strategy_step(const sss::WalkMedium& medium, const sss::WalkSettings& settings,
                                      bool short_walk_rule, double object_chord) {
  sss::MixtureWalkStep<3> step = sss::make_walk_step(medium, settings);
  if (!short_walk_rule || !(object_chord > 0)) return step;
  const std::array<double, 3> shares = short_walk_guided_shares(step, object_chord);
  for (int c = 0; c < 3; ++c)
    if (shares[std::size_t(c)] != step.p_guided(c)) return step.with_guided_shares(shares);
  return step;
}

}  // namespace

std::array<double, 3> short_walk_guided_shares(const sss::MixtureWalkStep<3>& step, double object_chord) {
  std::array<double, 3> shares{step.p_guided(0), step.p_guided(1), step.p_guided(2)};
  if (!(object_chord > 0)) return shares;
  for (int c = 0; c < 3; ++c)  // every channel's walks' reach against the object's thickness
    if (!(step.p_guided(c) > 0 && step.importance_length(c) < kShortWalkChordFraction * object_chord)) return shares;
  shares.fill(kShortWalkGuidedShare);
  return shares;
}

WalkMethod::WalkMethod(const SubsurfaceParams& params, const std::vector<Texture>* textures, double object_chord)
    : params_(params),
      textures_(textures),
      inversions_(params),
      boundary_(params.boundary),
      eta_(params.eta),
      roughness_(params, params.boundary == SubsurfaceParams::Boundary::Matched, textures),
      lambertian_entry_(params.lambertian_entry && params.boundary == SubsurfaceParams::Boundary::Diffuse),
      object_chord_(object_chord),
      id_(g_next_method_id++) {
  medium_per_entry_ =
      textures_ && (params.textured() || (roughness_.textured() && !inversions_.single() && !inversions_.empty()));
  medium_ = walk_medium(coefficients_from(medium_at(params), inversions_, roughness_.constant().x), params.g);
  for (std::size_t i = 0; i < kWalkStrategies.size(); ++i) {
    sss::WalkSettings& s = settings_[i];
    s.sampling = walk_sampling(params.walk_sampling);
    s.backward_guiding = params.backward_guiding_given ? params.backward_guiding : kWalkStrategies[i].backward_guiding;
    s.p_guided = params.guided_share_pinned() ? params.guided_share : kWalkStrategies[i].p_guided;
    s.channel_preference =
        params.channel_preference_given ? params.channel_preference : kWalkStrategies[i].channel_preference;
    short_walk_rule_[i] = !params.guided_share_pinned() && s.sampling == sss::WalkSampling::Mis &&
                          kWalkStrategies[i].p_guided == kWalkStrategies[0].p_guided;
    steps_.push_back(strategy_step(medium_, s, short_walk_rule_[i], object_chord_));
    channel_per_walk_[i] =
        params.channel_per_walk_given ? params.channel_per_walk : kWalkStrategies[i].channel_per_walk;
  }
  // Every channel's importance length against the object's chord (short_walk_guided_shares'
  // test; infinite for an unguided step: its walks are not pulled back toward the entry).
  if (object_chord_ > 0) {
    const sss::MixtureWalkStep<3> guided = sss::make_walk_step(medium_, sss::WalkSettings{});
    bool all_short = true;
    for (int c = 0; c < 3; ++c)
      all_short = all_short && guided.importance_length(c) < kShortWalkChordFraction * object_chord_;
    far_side_in_reach_ = !all_short;
  }
  bool guided = false;
  for (std::size_t i = 0; i < kWalkStrategies.size(); ++i)
    for (int c = 0; c < 3; ++c)
      guided = guided || (kWalkStrategies[i].backward_guiding &&
                          settings_[i].sampling != sss::WalkSampling::Classical && steps_[i].p_guided(c) > 0);
  backward_strategies_differ_ = !params.backward_guiding_given && guided && far_side_in_reach_;
}

bool WalkMethod::sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const {
  const std::size_t strategy = std::size_t(entry.strategy) < kWalkStrategies.size() ? std::size_t(entry.strategy) : 0;
  // One colour channel per walk (WalkStrategy::channel_per_walk): walk k carries channel
  // k mod 3 alone, and as the integrator averages the entry's 3m exits, each channel's m
  // walks count kChannelWalks times: their mean is the channel's estimate.
  const int channel = channel_per_walk_[strategy] && entry.exit_index >= 0 ? entry.exit_index % kChannelWalks : -1;
  RGB initial(1);
  if (channel >= 0) {
    initial = RGB(0);
    initial[channel] = 1;
  }
  bool exited = false;
  if (entry.interior || (!medium_per_entry_ && !entry.wavelengths)) {  // a grid interior: its own coefficients
    exited = walk(entry, settings_[strategy], steps_[strategy], initial, sampler, out);
  } else {
    // The entry point's own medium, at the path's wavelengths on a spectral path: the
    // albedo inverted and the step made per wavelength, each channel's walk its own
    // wavelength's (the walk's channel MIS is then MIS over the path's wavelengths).
    MediumAt at = medium_at(params_, textures_, texture_context(entry.hit));
    if (entry.wavelengths) at = medium_at_wavelengths(params_, at, *entry.wavelengths);
    const float boundary_alpha = medium_per_entry_ ? roughness_.at(entry.hit).x : roughness_.constant().x;
    LastTexturedStep& last = t_last_textured_step;
    if (!last.matches(id_, strategy, at, boundary_alpha)) {
      last.method = ~uint64_t(0);  // until the new one is built (make_walk_step may throw)
      last.step.reset();
      const sss::WalkMedium m = walk_medium(coefficients_from(at, inversions_, boundary_alpha), params_.g);
      last.walkable = true;
      for (int c = 0; c < 3; ++c)
        if (!(m.sigma_t[c] > 0) || !std::isfinite(m.sigma_t[c])) last.walkable = false;  // a texture without extinction
      if (last.walkable)
        last.step.emplace(strategy_step(m, settings_[strategy], short_walk_rule_[strategy], object_chord_));
      last.method = id_, last.strategy = strategy, last.at = at, last.boundary_alpha = boundary_alpha;
    }
    if (!last.walkable) return false;
    exited = walk(entry, settings_[strategy], *last.step, initial, sampler, out);
  }
  if (channel >= 0) {
    out.weight *= float(kChannelWalks);
    out.gathered *= float(kChannelWalks);
  }
  return exited;
}

bool WalkMethod::samples_refracted_light(const SubsurfaceEntry& entry) const {
  return entry.lights_from_inside && boundary_ == SubsurfaceParams::Boundary::Dielectric && !roughness_.textured() &&
         !roughness_.constant().rough();
}

RGB WalkMethod::refracted_light_at(const SubsurfaceEntry& entry, const RefractedLight& light,
                                   const sss::MixtureWalkStep<3>& step, const SurfaceHit& plane, Vec3 y, Vec3 incoming,
                                   const std::array<double, 3>& throughput, Sampler& sampler) const {
  const float chance = refracted_light_chance(entry, step, plane, y);
  if (chance < 1 && !(sampler.uniform() < chance)) return RGB(0);
  const float u1 = sampler.uniform(), u2 = sampler.uniform();
  const Vec3 n_ref = refracted_light_normal(entry, y, eta_);
  Vec3 v;
  float p_light = 0;
  if (!light.sample(y, n_ref, u1, u2, v, p_light)) return RGB(0);
  // The flight along v to the boundary, and out through it as the walk leaves
  // (WalkMethod::walk): Fresnel's transmission about the shading normal there.
  SurfaceHit x;
  if (!entry.tracer.first_boundary(Ray{y, v}, x) || !entry.tracer.contains(x)) return RGB(0);
  const Vec3 ns = shading_normal_seen_from(x, -v);
  const auto out = refract(-v, ns, eta_);
  if (!out || !shading_side_agrees(x.ng, ns, *out)) return RGB(0);
  const RGB Le = light.lights().emission(x.p, x.ng, *out);
  if (Le.is_black()) return RGB(0);
  const float transmitted = 1 - fresnel_dielectric(dot(-v, ns), eta_);
  const float phase = henyey_greenstein(dot(incoming, v), phase_g(entry, step));
  const float p = p_light * chance;                 // the technique's density, taken or not
  const float w = p * p / (p * p + phase * phase);  // Veach 1997, eq. 9.13
  const double t = length(x.p - y);
  RGB sum;
  if (entry.interior) {
    // A grid interior: the scattering event's sigma_s is in the throughput already
    // (heterogeneous_walk.h), and the flight's transmittance is ratio tracking's unbiased
    // estimate (null_scattering.h).
    const Ray flight{y, v};
    Rng rng = tracking_rng(sampler.uniform(), flight);
    const RGB tr = ratio_tracking_transmittance(*entry.interior, flight, float(t), rng);
    for (std::size_t c = 0; c < 3; ++c) sum[int(c)] = float(throughput[c] * tr[int(c)]);
  } else {
    // The scattering event's albedo (the walk applies it with the flight that follows:
    // walk_step.h, F_k) and the flight's transmittance, exp(-sigma_t t), per channel.
    for (std::size_t c = 0; c < 3; ++c)
      sum[int(c)] = float(throughput[c] * step.albedo()[c] * std::exp(-step.sigma_t()[c] * t));
  }
  return sum * Le * (phase * transmitted * w / p);
}

bool WalkMethod::entry_direction(const SubsurfaceEntry& entry, Sampler& sampler, Vec3& dir) const {
  const SurfaceHit& in = entry.hit;
  if (lambertian_entry_) {
    // A diffuse transmission (Chiang, Kutz & Burley 2016, sec. 4): a cosine lobe under
    // the surface, whatever the boundary's refraction; the entry's weight is the
    // boundary's transmission as for the refracted entry. A direction above the geometric
    // surface is no light (geometry/shading_normal.h).
    const float u1 = sampler.uniform(), u2 = sampler.uniform();
    dir = Frame(-in.ns).to_world(sample_cosine_hemisphere({u1, u2}));
    return dot(dir, in.ng) < 0;
  }
  if (entry.refracted) {
    dir = *entry.refracted;  // through a rough entry
    return true;
  }
  if (boundary_ == SubsurfaceParams::Boundary::Matched) {
    dir = -entry.wo;
    return true;
  }
  // About the shading normal; a refraction that would leave the surface again is no
  // light (geometry/shading_normal.h).
  const auto t = refract(entry.wo, in.ns, eta_);
  if (!t || !shading_side_agrees(in, *t)) return false;
  dir = *t;
  return true;
}

// A rough boundary: the rough dielectric seen from inside. The lights outside are sampled
// through it here (at every crossing, internal reflections included), and it is sampled
// for the way on: out, weighed against those light samples (direction_pdf), or back in.
// Its 1/eta^2 radiance factor is omitted as at the entry: a transmission from inside
// carries eta^2 (Veach 1997, sec. 5.2), times eta_scale = 1/eta^2.
WalkMethod::RoughCrossing WalkMethod::cross_rough_boundary(const SubsurfaceEntry& entry, const sss::WalkResult& res,
                                                           Vec3 ns, BoundaryAlphas alpha, RGB& weight, Sampler& sampler,
                                                           SubsurfaceExit& out) const {
  const Vec3 d = res.exit_dir_in_medium;
  BSDF b;
  b.type = BSDF::Type::Dielectric;
  b.n = ns;
  b.eta = eta_;
  b.alpha_x = alpha.x;
  b.alpha_y = alpha.y;
  out.gathered += weight * entry.light_through(res.exit_p, res.exit_n, b, -d, sampler) / (eta_ * eta_);
  const float u_lobe = sampler.uniform(), u1 = sampler.uniform(), u2 = sampler.uniform();
  const auto bs = bsdf_sample(b, -d, u_lobe, {u1, u2});
  if (!bs) return RoughCrossing::Lost;  // a microfacet sample lost below the surface
  if (!shading_side_agrees(res.exit_n, ns, bs->wi)) return RoughCrossing::Lost;
  weight *= bs->weight * bs->eta_scale;
  if (!weight.is_finite() || weight.is_black()) return RoughCrossing::Lost;
  out.direction = bs->wi;
  if (!bs->transmission) return RoughCrossing::Back;
  out.weight = weight;
  out.direction_pdf = bs->pdf;
  return RoughCrossing::Out;
}

// Entry and exit 1/eta^2 radiance factors cancel and are omitted.
bool WalkMethod::walk(const SubsurfaceEntry& entry, const sss::WalkSettings& settings,
                      const sss::MixtureWalkStep<3>& step, const RGB& initial, Sampler& sampler,
                      SubsurfaceExit& out) const {
  using Boundary = SubsurfaceParams::Boundary;
  const SurfaceHit& in = entry.hit;
  Vec3 dir;
  if (!entry_direction(entry, sampler, dir)) return false;
  Vec3 start = in.p, start_n = in.ng;
  SurfaceHit last;  // the boundary the latest flight was traced to: where a walk ends
  auto tracer = [&](Vec3 o, Vec3 d, double max_t) {
    sss::BoundaryHit b;
    Ray r{o, d};
    // Leave the surface we stand on along the flight's own line, to the depth at which
    // offset_ray_origin would start it (the walk's first flight; the far side's ray).
    // From that point moved along the normal instead, the ray follows a line parallel to
    // the walk's, which meets the far side farther on where the flight grazes the surface
    // (the chord of a convex part grows as the line moves in), and a collision between
    // the two crossings fell outside the object, where the walk wandered until its step
    // cap (docs/random-walk.md, "Leaving the surface";
    // WalkMethodOnItsOwn.StaysInsideTheObjectAtAGrazingEntry).
    if (o == start) r.o = start + d * (surface_offset(start) / std::abs(dot(d, start_n)));
    // Bounded by the flight's distance (random_walk.h), padded so that every crossing
    // within max_t of o is found from the offset origin: the walk compares t itself.
    if (std::isfinite(max_t)) r.tmax = float(max_t) * 1.0001f + length(r.o - o);
    if (!entry.tracer.first_boundary(r, last)) return b;
    b.hit = true;
    b.p = last.p;
    b.n = last.ng;
    b.t = length(last.p - o);
    return b;
  };
  // The far side's ray, once per entry (SubsurfaceEntry::far_side).
  auto far_side_tracer = [&](Vec3 o, Vec3 d, double max_t) {
    if (!entry.far_side) entry.far_side = tracer(o, d, max_t);
    return *entry.far_side;
  };
  const sss::WalkGuide guide = sss::make_walk_guide(settings, in.p, in.ng, far_side_tracer);
  // Light sampled through the smooth boundary at every scattering event (refracted_light.h),
  // about the plane of the entry point.
  const bool refracted_light = samples_refracted_light(entry);
  std::optional<RefractedLight> light;
  if (refracted_light) light.emplace(*entry.lights_from_inside, eta_);
  auto at_collision = [&](const Vec3d& y, const Vec3d& incoming, const std::array<double, 3>& throughput) {
    if (refracted_light)
      out.gathered += refracted_light_at(entry, *light, step, in, Vec3(y), Vec3(incoming), throughput, sampler);
  };
  RGB weight = initial;  // a channel that starts at 0 stays 0 (random_walk.h: its flights are never drawn)
  for (int reflections = 0; reflections < kMaxInternalReflections; ++reflections) {
    sss::WalkResult res;
    // A flight that all but grazes the surface (|cos| < kGrazingCos) would reach that
    // depth only beyond the far side of a convex part as thin as depth / cos^2: that
    // walk starts where its ray does, moved off the surface along the normal (its
    // lines agree; it starts that depth below the surface, a bias of the order of that
    // depth over the mean free path for the few walks that graze).
    const bool grazing = std::abs(dot(dir, start_n)) < kGrazingCos;
    const Vec3 walk_start = grazing ? offset_ray_origin(start, start_n, dir) : start;
    const bool walked = entry.interior ? heterogeneous_walk(*entry.interior, settings, walk_start, dir, sampler, tracer,
                                                            res, weight, out.gathered, at_collision)
                                       : sss::random_walk(step, settings, guide, walk_start, dir, sampler, tracer, res,
                                                          weight, at_collision);
    if (!walked) {
      out.truncated = res.truncated;
      return false;
    }
    weight = res.weight;  // includes what the earlier segments carried
    if (!entry.tracer.contains(last)) {
      // An interior boundary (another object inside this one): diffuse reflection back
      // into the medium with its albedo, as the volumetric path tracer does there
      // (cosine-sampled: the weight is the albedo); the walk goes on.
      weight *= entry.interior_albedo(last);
      if (weight.is_black()) return false;
      const Vec3 n = dot(res.exit_dir_in_medium, last.ng) < 0 ? last.ng : -last.ng;
      const float u1 = sampler.uniform(), u2 = sampler.uniform();
      dir = Frame(n).to_world(sample_cosine_hemisphere({u1, u2}));
      start = res.exit_p;
      start_n = n;
      continue;
    }
    out.hit = last;  // the exit's own shape and surface coordinates (a textured roughness there)
    out.hit.p = res.exit_p;
    out.hit.ng = res.exit_n;  // out.hit.ns: the exit's shading normal, on the same side
    out.weight = weight;
    if (boundary_ == Boundary::Diffuse) {
      out.kind = SubsurfaceExit::Kind::ThroughLobe;
      return true;
    }
    const Vec3 d = res.exit_dir_in_medium;
    // The boundary scatters about the shading normal, or the geometric one where the walk
    // meets the back of the shading hemisphere; a direction on the wrong geometric side of
    // it is no light (geometry/shading_normal.h).
    const Vec3 ns = shading_normal_seen_from(out.hit, -d);
    out.kind = SubsurfaceExit::Kind::Along;
    if (boundary_ == Boundary::Matched) {
      out.direction = d;
      return true;
    }
    if (const BoundaryAlphas alpha = roughness_.at(last); boundary_ == Boundary::Dielectric && alpha.rough()) {
      const RoughCrossing crossing = cross_rough_boundary(entry, res, ns, alpha, weight, sampler, out);
      if (crossing != RoughCrossing::Back) return crossing == RoughCrossing::Out;
      dir = out.direction;
      start = res.exit_p;
      start_n = res.exit_n;
      continue;
    }
    const float F = fresnel_dielectric(dot(-d, ns), eta_);
    if (sampler.uniform() >= F) {
      auto t = refract(-d, ns, eta_);
      if (!t) return false;  // F = 1 under total internal reflection: not reached
      if (!shading_side_agrees(res.exit_n, ns, *t)) return false;
      out.direction = *t;
      // Right after a scattering event whose light was sampled through the boundary: the
      // emission met next is weighed against that sample.
      if (refracted_light && res.from_collision)
        out.emission_weight =
            light->walk_weight(res.last_collision, refracted_light_normal(entry, res.last_collision, eta_), d,
                               henyey_greenstein(dot(res.last_incoming, d), phase_g(entry, step)),
                               refracted_light_chance(entry, step, in, res.last_collision));
      return true;
    }
    // Internal reflection: the walk goes on from the boundary.
    dir = d - ns * (2 * dot(d, ns));
    if (!shading_side_agrees(res.exit_n, ns, dir)) return false;
    start = res.exit_p;
    start_n = res.exit_n;
  }
  out.truncated = true;
  return false;
}

}  // namespace dermis
