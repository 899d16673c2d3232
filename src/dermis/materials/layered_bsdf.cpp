#include "dermis/materials/layered_bsdf.h"

#include <bit>
#include <cmath>

#include "dermis/core/frame.h"
#include "dermis/core/fresnel.h"
#include "dermis/core/henyey_greenstein.h"
#include "dermis/core/rng.h"
#include "dermis/materials/bsdf.h"

namespace dermis {

namespace {

constexpr Vec3 kUp{0, 0, 1};

// What one walk computes.
enum class Estimate { Sample, Value, Density };

BSDF interface_bsdf(const CoatedLayer& c) {
  BSDF b;
  b.type = BSDF::Type::Dielectric;
  b.n = kUp;
  b.eta = c.eta;
  b.alpha_x = c.interface_alpha_x;
  b.alpha_y = c.interface_alpha_y;
  return b;
}

BSDF base_bsdf(const CoatedLayer& c) {
  BSDF b;
  b.n = kUp;
  if (c.base == CoatedLayer::Base::Diffuse) {
    b.type = BSDF::Type::Diffuse;
    b.albedo = c.base_reflectance;
  } else {
    b.type = BSDF::Type::Conductor;
    // The conductor meets the coating, not vacuum: its complex index relative to the
    // coating's, (eta + i k) / eta_coat (Fresnel's equations take the ratio of the indices; pbrt-v4 does the same).
    b.cond_eta = c.conductor_eta / c.eta;
    b.cond_k = c.conductor_k / c.eta;
    b.alpha_x = c.base_alpha_x;
    b.alpha_y = c.base_alpha_y;
  }
  return b;
}

// Transmittance of the slab over a height difference dz along w, extinction 1 per unit
// of height: exp(-|dz| / |w.z|), the vertical attenuation of the position-free
// formulation (Guo et al. 2018, sec. 4: a flight's length depends on its direction only).
float slab_transmittance(float dz, Vec3 w) {
  if (dz == 0) return 1;
  return std::exp(-std::abs(dz / w.z));
}

uint64_t direction_hash(Vec3 w) {
  const uint64_t xy = uint64_t(std::bit_cast<uint32_t>(w.x)) << 32 | std::bit_cast<uint32_t>(w.y);
  return mix64(xy ^ mix64(std::bit_cast<uint32_t>(w.z)));
}

// The streams of the queries: independent of one another for the same seed.
enum StreamTag : uint64_t { kEvalStream = 1, kPdfStream = 2, kSampleStream = 3 };

struct WalkResult {
  RGB sum{0, 0, 0};  // Value: f cos; Density: the density in every channel
  std::optional<CoatedSample> exit;
};

// One random walk through the stack entered from wo (wo.z > 0). Sample: the walk's exit.
// Value, Density: the sum of the connections to wi (wi.z > 0) along the walk.
WalkResult walk(const CoatedLayer& c, Vec3 wo, Vec3 wi, Estimate mode, float u_lobe, Vec2 u, Rng& rng) {
  const BSDF top = interface_bsdf(c), base = base_bsdf(c);
  const bool top_smooth = top.is_specular();
  const bool scattering = !c.albedo.is_black();
  WalkResult out;
  // Reflection at the interface, without entering.
  if (mode == Estimate::Value) out.sum = bsdf_eval(top, wo, wi);
  if (mode == Estimate::Density) out.sum = RGB(bsdf_pdf(top, wo, wi));

  // Through a smooth interface wi is reached from one inner direction only, v_exit
  // (pointing up). Integrating the delta of the refraction over the inner direction
  // leaves the solid-angle Jacobian d omega_v / d omega_wi = cos wi / (eta^2 cos v)
  // (Snell: n_o^2 cos_o d omega_o = n_i^2 cos_i d omega_i; Veach 1997, eq. 5.4 /
  // pbrt-v4 sec. 9.5.2). The radiance factor eta^2 of leaving (Veach 1997, sec. 5.2)
  // cancels the 1/eta^2 of the Jacobian in a value; a density keeps it.
  std::optional<Vec3> v_exit;
  float exit_value = 0, exit_density = 0;  // (1 - F) cos wi / cos v, and over eta^2
  if (mode != Estimate::Sample && top_smooth) {
    if (const auto t = refract(wi, kUp, c.eta)) {
      v_exit = -*t;
      const float T = 1 - fresnel_dielectric(wi.z, c.eta);
      exit_value = T * wi.z / v_exit->z;
      exit_density = exit_value / (c.eta * c.eta);
    }
  }
  // The probability (Density) or attenuation (Value) of flying from height z along v to
  // the interface unscattered. Without scattering the walk itself is weighted by the
  // transmittance rather than ended by absorption, so that a density does not see it.
  auto to_interface = [&](float z, Vec3 v) {
    return mode == Estimate::Value || scattering ? slab_transmittance(c.thickness - z, v) : 1.0f;
  };
  // Connections to wi through a rough interface, in a value by two strategies weighted by
  // the power heuristic (Veach 1997, sec. 9.2; as pbrt-v4's LayeredBxDF::f), because a
  // nearly smooth interface's lobe is a narrow spike that the vertex's own sampling finds
  // only rarely (fireflies at alpha 0.01):
  //  (a) along the walk's next direction v, sampled by the vertex (connect_rough);
  //  (b) along v_nee, sampled once per walk by the interface from wi into the slab
  //      (connect_nee, at every vertex: unbiased at each, as pbrt-v4 does).
  // A density keeps the one strategy (a): only the integrator's MIS weights see it.
  std::optional<Vec3> v_nee;  // (b): pointing up, the direction the walk would leave along
  float pdf_nee = 0;          // its density from wi (lobe choice included)
  RGB value_nee{0};           // f_top(-v_nee, wi) |cos wi| / pdf_nee
  const bool two_strategies = mode == Estimate::Value && !top_smooth;
  if (two_strategies) {
    const float ul = rng.uniform();
    const Vec2 un{rng.uniform(), rng.uniform()};
    if (const auto s = bsdf_sample(top, wi, ul, un); s && s->transmission && s->wi.z < 0 && s->pdf > 0) {
      v_nee = -s->wi;
      pdf_nee = s->pdf;
      value_nee = bsdf_eval(top, s->wi, wi) * (1 / pdf_nee);
    }
  }
  auto power = [](float a, float b) { return a * a / (a * a + b * b); };
  // (a): the walk's weight `beta` already includes the scattering into v, sampled with
  // density pdf_v (infinite for a specular event, which (b) cannot produce).
  auto connect_rough = [&](RGB beta, float z, Vec3 v, float pdf_v, bool specular_v) {
    if (top_smooth || v.z <= 0) return;
    if (mode == Estimate::Value) {
      const float weight = two_strategies && !specular_v ? power(pdf_v, bsdf_pdf(top, wi, -v)) : 1.0f;
      out.sum += beta * to_interface(z, v) * bsdf_eval(top, -v, wi) * weight;
    }
    if (mode == Estimate::Density) out.sum += RGB(to_interface(z, v) * bsdf_pdf(top, -v, wi));
  };
  // (b) at a vertex that scatters with value f_v (phase function, or f |cos|) and
  // samples with density pdf_v into v_nee.
  auto connect_nee = [&](RGB beta, float z, RGB f_v, float pdf_v) {
    if (!v_nee) return;
    out.sum += beta * f_v * value_nee * (to_interface(z, *v_nee) * power(pdf_nee, pdf_v));
  };

  // Entering.
  const auto entry = bsdf_sample(top, wo, u_lobe, u);
  if (!entry) return out;
  if (!entry->transmission) {
    if (mode == Estimate::Sample) out.exit = CoatedSample{entry->wi, entry->weight, entry->specular};
    return out;
  }
  RGB beta = entry->weight;  // includes the 1 / eta^2 of entering
  bool specular = entry->specular;
  Vec3 w = entry->wi;  // direction of travel
  float z = c.thickness;
  int events = 0;
  for (;;) {
    const float z_boundary = w.z > 0 ? c.thickness : 0;
    if (scattering) {
      // Free flight, extinction 1: the height travelled is an exponential of rate 1 / |w.z|.
      const float dz = -std::log(1 - rng.uniform()) * std::abs(w.z);
      if (dz < std::abs(z_boundary - z)) {
        if (events++ == c.max_depth) return out;
        z += w.z > 0 ? dz : -dz;
        beta *= c.albedo;  // analog flight: sigma_s / sigma_t, the phase function sampled exactly
        specular = false;
        if (v_exit)  // through the smooth interface: the phase function into v_exit
          out.sum += (mode == Estimate::Value ? beta : RGB(1)) * henyey_greenstein(dot(w, *v_exit), c.g) *
                     to_interface(z, *v_exit) * (mode == Estimate::Value ? exit_value : exit_density);
        if (v_nee) {
          const float p = henyey_greenstein(dot(w, *v_nee), c.g);
          connect_nee(beta, z, RGB(p), p);
        }
        const Vec2 up{rng.uniform(), rng.uniform()};
        const float cos_theta = sample_henyey_greenstein_cos(up.x, c.g);
        const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
        const float phi = 2 * kPi * up.y;
        w = Frame(w).to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
        if (w.z == 0) return out;
        connect_rough(beta, z, w, henyey_greenstein(cos_theta, c.g), false);
        continue;
      }
    } else {
      beta *= slab_transmittance(c.thickness, w);
    }
    z = z_boundary;
    if (w.z < 0) {
      // At the base.
      if (events++ == c.max_depth) return out;
      if (v_exit) {
        if (mode == Estimate::Value)
          out.sum += beta * bsdf_eval(base, -w, *v_exit) * to_interface(0, *v_exit) * exit_value;
        if (mode == Estimate::Density)
          out.sum += RGB(bsdf_pdf(base, -w, *v_exit) * to_interface(0, *v_exit) * exit_density);
      }
      if (v_nee) connect_nee(beta, 0, bsdf_eval(base, -w, *v_nee), bsdf_pdf(base, -w, *v_nee));
      const float ub = rng.uniform();
      const auto b = bsdf_sample(base, -w, ub, {rng.uniform(), rng.uniform()});
      if (!b) return out;
      beta *= b->weight;
      specular = specular && b->specular;
      w = b->wi;
      connect_rough(beta, 0, w, b->pdf, b->specular);
      continue;
    }
    // At the interface, from inside: leave, or reflect back into the slab.
    const float ut = rng.uniform();
    const auto t = bsdf_sample(top, -w, ut, {rng.uniform(), rng.uniform()});
    if (!t) return out;
    if (t->transmission) {
      // Value and Density counted this exit by their connections, in expectation.
      if (mode == Estimate::Sample) out.exit = CoatedSample{t->wi, beta * t->weight, specular && t->specular};
      return out;
    }
    if (events++ == c.max_depth) return out;
    beta *= t->weight;
    specular = specular && t->specular;
    w = t->wi;
  }
}

}  // namespace

bool CoatedLayer::is_specular() const {
  return std::max(interface_alpha_x, interface_alpha_y) < kSmoothAlpha && base == Base::Conductor &&
         std::max(base_alpha_x, base_alpha_y) < kSmoothAlpha && albedo.is_black();
}

RGB coated_eval(const CoatedLayer& c, Vec3 wo, Vec3 wi, uint64_t seed) {
  if (wo.z < 0) wo = -wo, wi = -wi;  // two-sided
  if (wo.z == 0 || wi.z <= 0 || c.is_specular()) return RGB(0);
  Rng rng(seed, kEvalStream, direction_hash(wi));
  RGB sum(0);
  for (int s = 0; s < c.n_samples; ++s)
    sum += walk(c, wo, wi, Estimate::Value, rng.uniform(), {rng.uniform(), rng.uniform()}, rng).sum;
  return sum / float(c.n_samples);
}

float coated_pdf(const CoatedLayer& c, Vec3 wo, Vec3 wi, uint64_t seed) {
  if (wo.z < 0) wo = -wo, wi = -wi;
  if (wo.z == 0 || wi.z <= 0 || c.is_specular()) return 0;
  Rng rng(seed, kPdfStream, direction_hash(wi));
  float sum = 0;
  for (int s = 0; s < c.n_samples; ++s)
    sum += walk(c, wo, wi, Estimate::Density, rng.uniform(), {rng.uniform(), rng.uniform()}, rng).sum[0];
  return sum / float(c.n_samples);
}

std::optional<CoatedSample> coated_sample(const CoatedLayer& c, Vec3 wo, float u_lobe, Vec2 u, uint64_t seed) {
  const bool below = wo.z < 0;
  if (below) wo = -wo;
  if (wo.z == 0) return std::nullopt;
  Rng rng(seed, kSampleStream);
  auto s = walk(c, wo, wo, Estimate::Sample, u_lobe, u, rng).exit;
  if (!s || s->wi.z <= 0 || !s->weight.is_finite()) return std::nullopt;
  if (below) s->wi = -s->wi;
  return s;
}

}  // namespace dermis
