#include "dermis/render/subsurface/walk_method.h"

#include "dermis/materials/fresnel.h"

namespace dermis {

namespace {

sss::WalkSampling walk_sampling(SubsurfaceParams::WalkSampling s) {
  switch (s) {
    case SubsurfaceParams::WalkSampling::Classical: return sss::WalkSampling::Classical;
    case SubsurfaceParams::WalkSampling::Dwivedi: return sss::WalkSampling::Dwivedi;
    case SubsurfaceParams::WalkSampling::Mis: return sss::WalkSampling::Mis;
  }
  return sss::WalkSampling::Mis;
}

constexpr int kMaxInternalReflections = 256;

}  // namespace

WalkMethod::WalkMethod(const SubsurfaceParams& params, const Coefficients& k)
    : boundary_(params.boundary), eta_(params.eta) {
  medium_.sigma_s = k.sigma_s;
  medium_.sigma_t = k.sigma_a + k.sigma_s;
  medium_.g = params.g;
  settings_.sampling = walk_sampling(params.walk_sampling);
  settings_.backward_guiding = params.backward_guiding;
  step_ = std::make_unique<sss::MixtureWalkStep<3>>(sss::make_walk_step(medium_, settings_));
}

// Entry and exit 1/eta^2 radiance factors cancel and are omitted.
bool WalkMethod::sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const {
  using Boundary = SubsurfaceParams::Boundary;
  const SurfaceHit& in = entry.hit;
  Vec3 dir;
  if (boundary_ == Boundary::Matched) {
    dir = -entry.wo;
  } else {
    auto t = refract(entry.wo, in.ng, eta_);
    if (!t) return false;
    dir = *t;
  }
  Vec3 start = in.p, start_n = in.ng;
  auto tracer = [&](Vec3 o, Vec3 d) {
    sss::BoundaryHit b;
    Ray r{o, d};
    if (o == start) r.o = offset_ray_origin(start, start_n, d);  // leave the surface we stand on
    SurfaceHit h;
    if (!entry.tracer.first_hit(r, h)) return b;
    b.hit = true;
    b.p = h.p;
    b.n = h.ng;
    b.t = length(h.p - o);
    return b;
  };
  const sss::WalkGuide guide = sss::make_walk_guide(settings_, in.p, in.ng, tracer);
  RGB weight(1);
  for (int reflections = 0; reflections < kMaxInternalReflections; ++reflections) {
    sss::WalkResult res;
    if (!sss::random_walk(*step_, settings_, guide, start, dir, sampler, tracer, res, weight)) {
      out.truncated = res.truncated;
      return false;
    }
    weight = res.weight;  // includes what the earlier segments carried
    out.hit = in;
    out.hit.p = res.exit_p;
    out.hit.ng = out.hit.ns = res.exit_n;
    out.weight = weight;
    if (boundary_ == Boundary::Diffuse) {
      out.kind = SubsurfaceExit::Kind::ThroughLobe;
      return true;
    }
    const Vec3 d = res.exit_dir_in_medium;
    out.kind = SubsurfaceExit::Kind::Along;
    if (boundary_ == Boundary::Matched) {
      out.direction = d;
      return true;
    }
    const float F = fresnel_dielectric(dot(-d, res.exit_n), eta_);
    if (sampler.uniform() >= F) {
      auto t = refract(-d, res.exit_n, eta_);
      if (!t) return false;  // F = 1 under total internal reflection: not reached
      out.direction = *t;
      return true;
    }
    // Internal reflection: the walk goes on from the boundary.
    dir = d - res.exit_n * (2 * dot(d, res.exit_n));
    start = res.exit_p;
    start_n = res.exit_n;
  }
  out.truncated = true;
  return false;
}

}  // namespace dermis
