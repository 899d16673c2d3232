#include "dermis/render/subsurface_method.h"

#include <cmath>
#include <vector>

#include "dermis/materials/bsdf.h"
#include "dermis/materials/fresnel.h"
#include "dermis/render/integrator.h"
#include "dermis/render/object_tracing.h"
#include "dermis/render/render_scene.h"
#include "dermis/sss/profiles/tabulated.h"
#include "dermis/sss/study/albedo_inversion.h"
#include "dermis/sss/walk/albedo_inversion.h"

#include <map>
#include <tuple>
#include <mutex>

namespace dermis {

namespace {

using Method = SubsurfaceParams::Method;
using Profile = SubsurfaceParams::Profile;

constexpr int kMaxProbeHits = 16;

// Surface albedo A and mean free path l per channel from what the user gave. With
// coefficients: l = 1/sigma_t' and A = 1 - H(1) sqrt(1 - alpha') (Chandrasekhar 1950,
// METHODS.md sec. 6), alpha' the similarity-reduced single-scattering albedo: the
// searchlight, index-matched configuration the Christensen-Burley fit was made for.
void albedo_and_mfp(const SubsurfaceParams& p, RGB& A, RGB& l) {
  if (p.reflectance) {
    A = *p.reflectance;
    l = *p.mfp;
    return;
  }
  for (int c = 0; c < 3; ++c) {
    double ss = (*p.sigma_s)[c] * (1 - p.g), st = (*p.sigma_a)[c] + ss;
    l[c] = float(1 / st);
    A[c] = float(sss::surface_albedo_index_matched(ss / st));
  }
}

// The exact albedo inversion of the random walk (sss/walk/albedo_inversion.h), one
// table per (eta, g), built once per process and cached on disk by the table itself.
const sss::AlbedoInversion& albedo_inversion(double eta, double g, bool exit_matched) {
  static std::mutex mutex;
  static std::map<std::tuple<double, double, bool>, std::unique_ptr<sss::AlbedoInversion>> tables;
  std::lock_guard<std::mutex> lock(mutex);
  auto& t = tables[{eta, g, exit_matched}];
  if (!t) {
    sss::AlbedoTableConfig config;
    config.eta = eta;
    config.g = g;
    config.exit_matched = exit_matched;
    t = std::make_unique<sss::AlbedoInversion>(config);
  }
  return *t;
}

}  // namespace

void resolve_coefficients(const SubsurfaceParams& p, RGB& sigma_a, RGB& sigma_s) {
  if (p.sigma_a) {
    sigma_a = *p.sigma_a;
    sigma_s = *p.sigma_s;
    return;
  }
  // From (A, mfp): sigma_t = 1 / mfp and alpha from the half-space table of the walk's
  // own boundary: the dielectric (Fresnel at entry and at every exit); the diffuse
  // boundary (refraction at entry, out at the first crossing through the exit lobe);
  // matched (eta = 1). A is per entering light under diffuse incidence.
  // "albedoinversion" "fit": van de Hulst's fit instead (g = 0, index-matched), for comparison.
  using Boundary = SubsurfaceParams::Boundary;
  const double table_eta = p.boundary == Boundary::Matched ? 1.0 : p.eta;
  const bool exit_matched = p.boundary == Boundary::Diffuse;
  const sss::AlbedoInversion* inv =
      p.albedo_inversion_fit ? nullptr : &albedo_inversion(table_eta, p.g, exit_matched);
  for (int c = 0; c < 3; ++c) {
    double st = 1.0 / (*p.mfp)[c];
    double A = (*p.reflectance)[c];
    double alpha = inv ? inv->single_scattering_albedo(A) : sss::van_de_hulst_single_scattering_albedo(A);
    sigma_s[c] = float(alpha * st);
    sigma_a[c] = float((1 - alpha) * st);
  }
}

namespace {

sss::ProfileRGB make_profile(const SubsurfaceParams& p, RGB A, RGB l) {
  switch (p.profile) {
    case Profile::Burley:
      return sss::make_burley_rgb(A, l, sss::BurleyParameterisation::VolumeMeanFreePath);
    case Profile::BurleyDiffuseMfp:
      return sss::make_burley_rgb(A, l, sss::BurleyParameterisation::DiffuseMeanFreePath);
    case Profile::Dipole:
      if (p.sigma_a) return sss::make_dipole_rgb_from_coefficients(*p.sigma_a, *p.sigma_s, p.g, p.eta);
      return sss::make_dipole_rgb(A, l, p.eta);
    case Profile::Gaussian:
    case Profile::Cubic: {
      // Matched to the Christensen-Burley profile of the same (A, l) by the mean squared
      // radius: Burley <r^2> = 14 d^2 (d = l/s); Gaussian <r^2> = 2v; cubic <r^2> = R^2/7.
      RGB v, R;
      for (int c = 0; c < 3; ++c) {
        double d = l[c] / sss::burley_scale(A[c], sss::BurleyParameterisation::VolumeMeanFreePath);
        v[c] = float(7 * d * d);
        R[c] = float(std::sqrt(98.0) * d);
      }
      return p.profile == Profile::Gaussian ? sss::make_gaussian_rgb(A, v) : sss::make_cubic_rgb(A, R);
    }
    case Profile::Skin6:
      // d'Eon & Luebke's variances are in mm; `scale` multiplies coefficients, i.e.
      // divides lengths, so scene units per mm = 1 / scale. Weights times the albedo
      // when reflectance is given.
      return sss::make_skin_rgb(1.0 / p.scale, p.reflectance ? *p.reflectance : RGB(1.0f));
    case Profile::Tabulated: {
      // The Cycles page's table: the (A, r/l) reparameterised dipole, at this eta.
      auto table = std::make_shared<const sss::ProfileTable>(sss::dipole_family(p.eta));
      return sss::make_tabulated_rgb(table, A, l);
    }
  }
  return sss::make_burley_rgb(A, l);
}

}  // namespace

std::unique_ptr<SubsurfaceMethod> make_subsurface_method(const SubsurfaceParams& params) {
  auto m = std::make_unique<SubsurfaceMethod>();
  m->params = params;
  m->sw_norm = subsurface_exit_normalization(params.eta);
  m->entry_eta = params.eta;
  switch (params.method) {
    case Method::Volumetric:
      break;
    case Method::Disk:
    case Method::DiskSingleAxis:
    case Method::SphereLines:
    case Method::SphereLinesRetry: {
      RGB A, l;
      albedo_and_mfp(params, A, l);
      m->profile = std::make_unique<sss::ProfileRGB>(make_profile(params, A, l));
      for (int c = 0; c < 3; ++c) m->albedo[c] = float(m->profile->channel[c].albedo());
      // Channels are chosen in proportion to their albedo (never zero, so that every
      // channel's hits can be found).
      RGB weights;
      for (int c = 0; c < 3; ++c) weights[c] = std::max(m->albedo[c], 1e-3f);
      if (params.method == Method::Disk || params.method == Method::DiskSingleAxis) {
        m->disk = std::make_unique<sss::DiskProbeSampler>(
            *m->profile, weights,
            params.method == Method::Disk ? sss::ProbeAxisProbabilities{} : sss::ProbeAxisProbabilities::single_axis());
      } else {
        m->line_tables = std::make_unique<sss::SphereLineTablesRGB>(*m->profile);
        m->lines = std::make_unique<sss::SphereLineSampler>(*m->line_tables, weights);
      }
      break;
    }
    case Method::PointCloud: {
      // The cloud itself needs the scene's geometry and lights: render/point_cloud_prepass.
      RGB A, l;
      albedo_and_mfp(params, A, l);
      m->profile = std::make_unique<sss::ProfileRGB>(make_profile(params, A, l));
      for (int c = 0; c < 3; ++c) m->albedo[c] = float(m->profile->channel[c].albedo());
      m->mean_free_path = l;
      break;
    }
    case Method::RandomWalk: {
      RGB sigma_a, sigma_s;
      resolve_coefficients(params, sigma_a, sigma_s);
      m->walk_medium.sigma_s = sigma_s;
      m->walk_medium.sigma_t = sigma_a + sigma_s;
      m->walk_medium.g = params.g;
      switch (params.walk_sampling) {
        case SubsurfaceParams::WalkSampling::Classical: m->walk_settings.sampling = sss::WalkSampling::Classical; break;
        case SubsurfaceParams::WalkSampling::Dwivedi: m->walk_settings.sampling = sss::WalkSampling::Dwivedi; break;
        case SubsurfaceParams::WalkSampling::Mis: m->walk_settings.sampling = sss::WalkSampling::Mis; break;
      }
      m->walk_settings.backward_guiding = params.backward_guiding;
      m->walk_step = std::make_unique<sss::MixtureWalkStep<3>>(sss::make_walk_step(m->walk_medium, m->walk_settings));
      if (params.boundary == SubsurfaceParams::Boundary::Matched) m->entry_eta = 1;
      break;
    }
  }
  return m;
}

namespace {

inline Vec3d to_d(Vec3 v) { return Vec3d(v); }

RGB profile_values(const sss::ProfileRGB& p, double r) {
  return {float(p.channel[0].eval(r)), float(p.channel[1].eval(r)), float(p.channel[2].eval(r))};
}

// One probe: candidates on the segment, one chosen uniformly, weight k R / pdf.
template <class Pdf>
bool pick_probe_hit(const RenderScene& sc, const SubsurfaceMethod& m, const SurfaceHit& entry,
                    const sss::ProbeSegment& seg, Sampler& sampler, PathCounters& counters, Pdf&& pdf_area,
                    SubsurfaceExit& out) {
  thread_local std::vector<SurfaceHit> hits;
  hits.clear();
  collect_object_hits(sc, entry, Vec3(seg.origin), Vec3(seg.direction), float(seg.length), kMaxProbeHits, hits,
                      counters);
  if (hits.empty()) return false;
  int k = int(hits.size());
  const SurfaceHit& h = hits[std::min(int(sampler.uniform() * k), k - 1)];
  double pdf = pdf_area(h);
  if (!(pdf > 0)) return false;
  double r = length(to_d(h.p) - to_d(entry.p));
  out.hit = h;
  out.weight = profile_values(*m.profile, r) * float(k / pdf);
  out.diffuse_exit = true;
  return true;
}

}  // namespace

namespace {

// Křivánek & d'Eon 2014 (sss/walk/): a volumetric random walk under the surface. The
// boundary decides how light leaves: `diffuse` through the exit lobe Sw at the first
// boundary crossing, `matched` straight through it, `dielectric` by Fresnel: internal
// reflection continues the walk, refraction leaves specularly. Entry and exit 1/eta^2
// radiance factors cancel and are omitted.
bool sample_walk_exit(const RenderScene& sc, const SubsurfaceMethod& m, const SurfaceHit& entry, Vec3 wo, Sampler& sampler,
                      PathCounters& counters, SubsurfaceExit& out) {
  using Boundary = SubsurfaceParams::Boundary;
  const Boundary boundary = m.params.boundary;
  Vec3 dir;
  if (boundary == Boundary::Matched) {
    dir = -wo;
  } else {
    auto t = refract(wo, entry.ng, m.params.eta);
    if (!t) return false;
    dir = *t;
  }
  Vec3 start = entry.p, start_n = entry.ng;
  auto tracer = [&](Vec3 o, Vec3 d) {
    sss::BoundaryHit b;
    Ray r{o, d};
    if (o == start) r.o = offset_ray_origin(start, start_n, d);  // leave the surface we stand on
    SurfaceHit h;
    if (!first_object_hit(sc, entry, r, h, counters)) return b;
    b.hit = true;
    b.p = h.p;
    b.n = h.ng;
    b.t = length(h.p - o);
    return b;
  };
  const sss::WalkGuide guide = sss::make_walk_guide(m.walk_settings, entry.p, entry.ng, tracer);
  RGB weight(1);
  for (int reflections = 0; reflections < 256; ++reflections) {
    sss::WalkResult res;
    if (!sss::random_walk(*m.walk_step, m.walk_settings, guide, start, dir, sampler, tracer, res, weight)) {
      out.truncated = res.truncated;
      return false;
    }
    weight = res.weight;  // includes what the earlier segments carried
    out.hit = entry;
    out.hit.p = res.exit_p;
    out.hit.ng = out.hit.ns = res.exit_n;
    out.weight = weight;
    if (boundary == Boundary::Diffuse) {
      out.diffuse_exit = true;
      return true;
    }
    Vec3 d = res.exit_dir_in_medium;
    out.diffuse_exit = false;
    if (boundary == Boundary::Matched) {
      out.direction = d;
      return true;
    }
    float F = fresnel_dielectric(dot(-d, res.exit_n), m.params.eta);
    if (sampler.uniform() >= F) {
      auto t = refract(-d, res.exit_n, m.params.eta);
      if (!t) return false;  // F = 1 under total internal reflection: not reached
      out.direction = *t;
      return true;
    }
    // Internal reflection: the walk goes on from the boundary.
    dir = d - res.exit_n * (2 * dot(d, res.exit_n));
    start = res.exit_p;
    start_n = res.exit_n;
  }
  ++counters.truncated;
  return false;
}

}  // namespace

bool sample_subsurface_exit(const RenderScene& sc, const SubsurfaceMethod& m, const SurfaceHit& entry, Vec3 wo,
                            Sampler& sampler, PathCounters& counters, SubsurfaceExit& out) {
  switch (m.params.method) {
    case Method::Volumetric:
      return false;  // rendered as a medium, never reaches here
    case Method::Disk:
    case Method::DiskSingleAxis: {
      sss::ProbeFrame frame = sss::ProbeFrame::around(to_d(entry.p), to_d(entry.ng));
      const float u_axis = sampler.get1d(), u_strategy = sampler.get1d();
      const Vec2 u_disk = sampler.get2d();  // radius and angle on the disk, stratified together
      sss::DiskProbeSample s = m.disk->sample(frame, u_axis, u_strategy, u_disk.x, u_disk.y);
      return pick_probe_hit(sc, m, entry, s.segment, sampler, counters,
                            [&](const SurfaceHit& h) { return m.disk->pdf_area(frame, to_d(h.p), to_d(h.ng)); }, out);
    }
    case Method::SphereLines: {
      Vec3d p = to_d(entry.p);
      const float u_channel = sampler.get1d(), u_radius = sampler.get1d();
      const Vec2 u_first = sampler.get2d(), u_second = sampler.get2d();
      sss::SphereLineSample s = m.lines->sample(p, u_channel, u_radius, {u_first.x, u_first.y}, {u_second.x, u_second.y});
      return pick_probe_hit(sc, m, entry, s.segment, sampler, counters,
                            [&](const SurfaceHit& h) { return m.lines->pdf_area(p, to_d(h.p)); }, out);
    }
    case Method::SphereLinesRetry: {
      // The Cycles page's scheme: retry up to 8 lines until one hits, else stay at P.
      Vec3d p = to_d(entry.p);
      thread_local std::vector<SurfaceHit> hits;
      auto count_hits = [&](const sss::ProbeSegment& seg) {
        hits.clear();
        collect_object_hits(sc, entry, Vec3(seg.origin), Vec3(seg.direction), float(seg.length), kMaxProbeHits, hits,
                            counters);
        return int(hits.size());
      };
      sss::SphereLineRetry r = m.lines->sample_retry(p, sampler, count_hits);
      if (r.hits == 0) {
        out.hit = entry;
        for (int c = 0; c < 3; ++c) out.weight[c] = float(m.lines->fallback_weight(c));
      } else {
        const SurfaceHit& h = hits[r.chosen];
        double d = length(to_d(h.p) - p);
        double pdf = m.lines->pdf_area(p, to_d(h.p));
        out.hit = h;
        for (int c = 0; c < 3; ++c)
          out.weight[c] = float(sss::SphereLineSampler::retry_weight(m.profile->channel[c].eval(d), r.hits, pdf));
      }
      out.diffuse_exit = true;
      return true;
    }
    case Method::RandomWalk:
      return sample_walk_exit(sc, m, entry, wo, sampler, counters, out);
    case Method::PointCloud:
      return false;  // not an exit sampler: the integrator asks the cloud for M(x)
  }
  return false;
}

}  // namespace dermis
