#include "dermis/sss/halfspace/halfspace.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "dermis/core/fresnel.h"
#include "dermis/core/microfacet.h"
#include "dermis/sss/halfspace/refraction.h"

namespace dermis::sss {

namespace {

// Paths per block: each block has its own Rng stream Rng(seed, block index).
constexpr uint64_t kPathsPerBlock = 1024;
// Blocks simulated in parallel per wave before the in-order reduction.
constexpr uint64_t kBlocksPerWave = 256;

// Per-block sums of per-path quantities and of their squares.
struct Tally {
  double exit = 0, exit_sq = 0;
  double absorbed = 0, absorbed_sq = 0;
  double truncated = 0, truncated_sq = 0;
  double beyond = 0, beyond_sq = 0;
  // Rough boundary only: per-path specular, entered and lost weights, and the sum of
  // exit x entered (the ratio albedo / entered's standard error).
  double specular = 0, specular_sq = 0;
  double entered = 0, entered_sq = 0, exit_entered = 0;
  double lost = 0, lost_sq = 0;
  uint64_t truncated_paths = 0, collisions = 0;
  std::vector<double> bin, bin_sq;

  void reset(size_t bins) {
    *this = Tally{};
    bin.assign(bins, 0.0);
    bin_sq.assign(bins, 0.0);
  }
  void add(const Tally& o) {
    exit += o.exit, exit_sq += o.exit_sq;
    absorbed += o.absorbed, absorbed_sq += o.absorbed_sq;
    truncated += o.truncated, truncated_sq += o.truncated_sq;
    beyond += o.beyond, beyond_sq += o.beyond_sq;
    specular += o.specular, specular_sq += o.specular_sq;
    entered += o.entered, entered_sq += o.entered_sq, exit_entered += o.exit_entered;
    lost += o.lost, lost_sq += o.lost_sq;
    truncated_paths += o.truncated_paths, collisions += o.collisions;
    for (size_t i = 0; i < bin.size(); ++i) bin[i] += o.bin[i], bin_sq[i] += o.bin_sq[i];
  }
};

// A cosine-weighted direction into the medium (z < 0): the cosine has density 2 mu on
// [0, 1], so mu = sqrt(xi).
Vec3d cosine_direction_down(Rng& rng) {
  const double mu = std::sqrt(rng.uniform_double());
  const double phi = 2 * kPiD * rng.uniform_double();
  const double sin_theta = std::sqrt(std::max(0.0, 1 - mu * mu));
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), -mu};
}

// Incident propagation direction (pointing into the medium, z < 0).
Vec3d sample_incident_direction(const HalfspaceConfig& c, Rng& rng) {
  switch (c.incidence) {
    case Incidence::Normal:
      return {0, 0, -1};
    case Incidence::Angle:
      return {std::sin(c.incidence_angle), 0, -std::cos(c.incidence_angle)};
    case Incidence::Diffuse:
      return cosine_direction_down(rng);
  }
  return {0, 0, -1};
}

bool is_rough(const HalfspaceConfig& c) {
  return c.eta != 1.0 && std::max(c.alpha_x, c.alpha_y) >= double(kSmoothAlpha);
}

// One scattering by the rough boundary: the renderer's sampling of the rough dielectric
// (core/microfacet.h), in the boundary's frame (normal +z, x along alpha_x).
struct RoughScattering {
  Vec3d direction;    // propagation direction after it
  double weight = 0;  // power weight G(wo, wi) / G1(wo) (the radiance scaling undone)
  bool transmitted = false;
  bool lost = true;  // reflected below the surface, or refracted back: the sample is lost
};

// `propagation`: the direction light arrives along (from either side).
RoughScattering scatter_at_rough_boundary(const TrowbridgeReitz& d, double eta, const Vec3d& propagation, Rng& rng) {
  RoughScattering r;
  const Vec3 wo(-propagation);  // points away from the boundary, on the side light comes from
  const float u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
  const auto s = rough_dielectric_sample(d, float(eta), wo, u_lobe, {u1, u2});
  if (!s) return r;
  // f |cos wi| / pdf of either lobe of the visible-normal sampler, times etap^2 for a
  // refraction: G(wo, wi) / G1(wo) (Heitz 2018, sec. 1; Walter et al. 2007, eqs. 20-21).
  r.weight = double(d.G(wo, s->wi)) / double(d.G1(wo));
  r.direction = normalize(Vec3d(s->wi));
  r.transmitted = s->transmission;
  r.lost = false;
  return r;
}

// One path from entry at the origin to exit, termination or truncation.
template <class Policy>
void trace_path(const HalfspaceConfig& c, const Policy& policy, Rng& rng, Tally& t) {
  const bool matched = c.eta == 1.0;
  const bool rough = is_rough(c);
  const TrowbridgeReitz microfacets(float(c.alpha_x), float(c.alpha_y));
  const Vec3d incident = sample_incident_direction(c, rng);
  // Entry: the Fresnel-transmitted fraction enters (the reflected part is `specular`,
  // known exactly); weighting instead of sampling costs no variance at normal incidence.
  // Rough: the rough dielectric sampled from outside, as the renderer's entry does.
  Vec3d direction = incident;
  double weight = 1.0;
  double path_lost = 0;  // rough boundary: lost by the microfacet model, at entry and exits
  if (rough) {
    const RoughScattering entry = scatter_at_rough_boundary(microfacets, c.eta, incident, rng);
    // What the microfacet model loses: a lost sample, or the shadowed part 1 - G / G1 of
    // a kept one.
    path_lost = entry.lost ? 1.0 : 1.0 - entry.weight;
    if (!entry.lost && !entry.transmitted) t.specular += entry.weight, t.specular_sq += entry.weight * entry.weight;
    if (entry.lost || !entry.transmitted) {
      t.lost += path_lost, t.lost_sq += path_lost * path_lost;
      return;
    }
    weight = entry.weight;
    direction = entry.direction;
    t.entered += weight, t.entered_sq += weight * weight;
  } else if (!matched) {
    weight = 1.0 - fresnel_dielectric(-incident.z, c.eta);
    if (!refract_through_plane(incident, c.eta, direction)) return;  // total reflection
  }
  if (c.entry_lambertian) direction = cosine_direction_down(rng);  // a diffuse transmission
  const double entered = weight;
  const double roulette_weight = c.roulette_threshold * weight;
  double absorbed = 0;
  uint64_t collisions = 0;
  Vec3d position{0, 0, 0};
  Flight flight = policy.fly(direction, 0.0, rng);
  weight *= flight.weight;
  for (;;) {
    position += flight.direction * flight.distance;
    if (flight.reaches_boundary) {
      position.z = 0;
      const double cos_out = flight.direction.z;
      if (rough && !c.exit_matched) {
        // Exit through the rough dielectric sampled from inside: refraction leaves,
        // reflection walks on, a lost sample ends the path.
        const RoughScattering exit = scatter_at_rough_boundary(microfacets, c.eta, flight.direction, rng);
        path_lost += exit.lost ? weight : weight * (1.0 - exit.weight);
        if (exit.lost) break;
        weight *= exit.weight;
        if (!exit.transmitted) {
          flight = policy.fly(exit.direction, 0.0, rng);
          weight *= flight.weight;
          continue;
        }
      } else if (!matched && !c.exit_matched) {
        // Exit: reflect back inside with probability F (always under total internal
        // reflection), else refract out (Fresnel; the direction outside is not tallied).
        const double f = fresnel_dielectric(cos_out, 1.0 / c.eta);
        if (f >= 1.0 || rng.uniform_double() < f) {
          const Vec3d reflected{flight.direction.x, flight.direction.y, -cos_out};
          flight = policy.fly(reflected, 0.0, rng);
          weight *= flight.weight;
          continue;
        }
      }
      t.exit += weight, t.exit_sq += weight * weight;
      t.exit_entered += weight * entered;
      const int b = c.bins.index(std::hypot(position.x, position.y));
      if (b < 0) {
        t.beyond += weight, t.beyond_sq += weight * weight;
      } else {
        t.bin[b] += weight, t.bin_sq[b] += weight * weight;
      }
      break;
    }
    if (collisions == c.max_collisions) {
      t.truncated += weight, t.truncated_sq += weight * weight;
      ++t.truncated_paths;
      break;
    }
    ++collisions;
    absorbed += weight * (1.0 - c.albedo);  // the collision's absorbed fraction (implicit capture)
    flight = policy.scatter(flight.direction, -position.z, rng);
    weight *= flight.weight;
    if (weight < roulette_weight) {
      // Russian roulette: survive with probability weight / roulette_weight (unbiased).
      if (rng.uniform_double() * roulette_weight >= weight) break;
      weight = roulette_weight;
    }
  }
  t.absorbed += absorbed, t.absorbed_sq += absorbed * absorbed;
  t.lost += path_lost, t.lost_sq += path_lost * path_lost;
  t.collisions += collisions;
}

template <class Policy>
void run_block(const HalfspaceConfig& c, const Policy& policy, uint64_t block, Tally& t) {
  Rng rng(c.seed, block);
  const uint64_t begin = block * kPathsPerBlock, end = std::min(begin + kPathsPerBlock, c.paths);
  for (uint64_t i = begin; i < end; ++i) trace_path(c, policy, rng, t);
}

template <class Policy>
Tally run_all(const HalfspaceConfig& c, const Policy& policy) {
  const size_t bins = size_t(c.bins.count());
  Tally total;
  total.reset(bins);
  const uint64_t blocks = (c.paths + kPathsPerBlock - 1) / kPathsPerBlock;
  std::vector<Tally> wave(std::min(blocks, kBlocksPerWave));
  for (uint64_t first = 0; first < blocks; first += kBlocksPerWave) {
    const uint64_t count = std::min(kBlocksPerWave, blocks - first);
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, count, 1), [&](const tbb::blocked_range<uint64_t>& r) {
      for (uint64_t k = r.begin(); k != r.end(); ++k) {
        wave[k].reset(bins);
        run_block(c, policy, first + k, wave[k]);
      }
    });
    for (uint64_t k = 0; k < count; ++k) total.add(wave[k]);  // block order: deterministic
  }
  return total;
}

// Mean and standard error sigma / sqrt(N) from the sums of x and x^2 over N paths.
void mean_and_stderr(double sum, double sum_sq, uint64_t n, double& mean, double& stderr_out) {
  mean = sum / double(n);
  const double variance = n > 1 ? std::max(0.0, (sum_sq / double(n) - mean * mean)) * double(n) / double(n - 1) : 0.0;
  stderr_out = std::sqrt(variance / double(n));
}

}  // namespace

void validate(const HalfspaceConfig& c) {
  auto fail = [](const std::string& m) { throw std::invalid_argument("halfspace: " + m); };
  if (!(c.albedo >= 0 && c.albedo <= 1))
    fail("single-scattering albedo must be in [0, 1], got " + std::to_string(c.albedo));
  if (!(c.sigma_t > 0 && std::isfinite(c.sigma_t)))
    fail("extinction sigma_t must be positive and finite, got " + std::to_string(c.sigma_t));
  if (!(c.g > -1 && c.g < 1)) fail("HG anisotropy g must be in (-1, 1), got " + std::to_string(c.g));
  if (!(c.eta > 0 && std::isfinite(c.eta)))
    fail("relative index of refraction eta must be positive and finite, got " + std::to_string(c.eta));
  if (c.incidence == Incidence::Angle && !(c.incidence_angle >= 0 && c.incidence_angle < kPiD / 2))
    fail("incidence angle must be in [0, 90) degrees");
  if (c.paths < 1) fail("need at least one path");
  if (!(c.p_guided >= 0 && c.p_guided <= 1))
    fail("guided sampling probability p_guided must be in [0, 1], got " + std::to_string(c.p_guided));
  if (c.max_collisions < 1) fail("max_collisions must be at least 1");
  if (!(c.alpha_x >= 0 && c.alpha_y >= 0 && std::isfinite(c.alpha_x) && std::isfinite(c.alpha_y)))
    fail("roughness alphas must be non-negative and finite");
  if (!(c.roulette_threshold > 0 && c.roulette_threshold <= 1))
    fail("roulette_threshold must be in (0, 1], got " + std::to_string(c.roulette_threshold));
}

HalfspaceResult simulate_halfspace(const HalfspaceConfig& c) {
  validate(c);
  const auto start = std::chrono::steady_clock::now();
  const HalfspaceMedium medium{c.albedo, c.sigma_t, c.g};
  Tally t;
  switch (c.sampling) {
    case WalkSampling::Classical:
      t = run_all(c, ClassicalSampling(medium));
      break;
    case WalkSampling::Dwivedi:
    case WalkSampling::Mis:
      t = run_all(c, GuidedSampling(medium, guided_choice_probability(c.sampling, c.p_guided)));
      break;
  }

  HalfspaceResult r;
  const uint64_t n = c.paths;
  r.paths = n;
  mean_and_stderr(t.exit, t.exit_sq, n, r.albedo, r.albedo_stderr);
  mean_and_stderr(t.absorbed, t.absorbed_sq, n, r.absorbed, r.absorbed_stderr);
  mean_and_stderr(t.truncated, t.truncated_sq, n, r.truncated_weight, r.truncated_weight_stderr);
  mean_and_stderr(t.beyond, t.beyond_sq, n, r.beyond_rmax, r.beyond_rmax_stderr);
  r.truncated = t.truncated_paths;
  r.mean_collisions = double(t.collisions) / double(n);
  if (is_rough(c)) {
    mean_and_stderr(t.specular, t.specular_sq, n, r.specular, r.specular_stderr);
    mean_and_stderr(t.entered, t.entered_sq, n, r.entered, r.entered_stderr);
    mean_and_stderr(t.lost, t.lost_sq, n, r.lost, r.lost_stderr);
    // A = mean(exit) / mean(entered); its standard error by the delta method (first order
    // in the two means): that of the mean per-path residual exit - A entered, / mean(entered).
    if (r.entered > 0) {
      const double A = r.albedo / r.entered, dn = double(n);
      const double residual_sq = t.exit_sq - 2 * A * t.exit_entered + A * A * t.entered_sq;
      const double variance = n > 1 ? std::max(0.0, residual_sq / (dn - 1)) : 0.0;
      r.per_entering_stderr = std::sqrt(variance / dn) / r.entered;
    }
  } else {
    if (c.eta != 1.0) {
      switch (c.incidence) {
        case Incidence::Normal:
          r.specular = fresnel_dielectric(1.0, c.eta);
          break;
        case Incidence::Angle:
          r.specular = fresnel_dielectric(std::cos(c.incidence_angle), c.eta);
          break;
        case Incidence::Diffuse:
          r.specular = fresnel_diffuse_reflectance(c.eta);
          break;
      }
    }
    r.entered = 1 - r.specular;
    r.per_entering_stderr = r.albedo_stderr / r.entered;
  }
  const int bins = c.bins.count();
  r.r_lo.resize(bins), r.r_hi.resize(bins), r.R.resize(bins), r.R_stderr.resize(bins);
  for (int i = 0; i < bins; ++i) {
    const double area = c.bins.annulus_area(i);
    double mean, err;
    mean_and_stderr(t.bin[i], t.bin_sq[i], n, mean, err);
    r.r_lo[i] = c.bins.lo(i), r.r_hi[i] = c.bins.hi(i);
    r.R[i] = mean / area, r.R_stderr[i] = err / area;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

void parse_incidence(const std::string& text, Incidence& incidence, double& angle_radians) {
  angle_radians = 0;
  if (text == "normal") {
    incidence = Incidence::Normal;
    return;
  }
  if (text == "diffuse") {
    incidence = Incidence::Diffuse;
    return;
  }
  const std::string prefix = "angle:";
  if (text.rfind(prefix, 0) == 0) {
    size_t used = 0;
    double degrees = 0;
    try {
      degrees = std::stod(text.substr(prefix.size()), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used > 0 && used == text.size() - prefix.size() && degrees >= 0 && degrees < 90) {
      incidence = Incidence::Angle;
      angle_radians = degrees * kPiD / 180;
      return;
    }
  }
  throw std::invalid_argument("incidence must be 'normal', 'diffuse' or 'angle:DEG' with DEG in [0, 90), got '" + text +
                              "'");
}

}  // namespace dermis::sss
