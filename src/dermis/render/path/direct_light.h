// Next-event estimation (light sampling) for the integrator's vertices, weighed against the
// scattering that finds the same light by multiple importance sampling (Veach 1997, ch. 9;
// pbrt-v4's SampleLd), and the small geometric helpers the vertices share.
#pragma once

#include <cmath>
#include <limits>
#include <utility>

#include "dermis/core/frame.h"
#include "dermis/core/rgb.h"
#include "dermis/core/sampler.h"
#include "dermis/render/integrator.h"
#include "dermis/render/path_counters.h"
#include "dermis/render/render_scene.h"
#include "dermis/spectral/spectrum_at.h"

namespace dermis {

inline constexpr float kInfiniteDistance = std::numeric_limits<float>::infinity();
// Index-matched boundaries a path or a shadow ray may cross before it is stopped (counted
// as truncated).
inline constexpr int kMaxInterfaceCrossings = 256;

// Veach 1997, eq. 9.13 (power heuristic, beta = 2).
inline float power_heuristic(float f, float g) {
  if (f == kInfiniteDistance) return 1;
  float f2 = f * f, g2 = g * g;
  return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.0f;
}

// The medium on the side of shape s that direction dir (against its geometric normal ng)
// leads into, crossing it from `current`.
inline int medium_after_crossing(const Shape& s, Vec3 dir, Vec3 ng, int current) {
  if (!s.has_medium_interface) return current;
  return dot(dir, ng) > 0 ? s.outside_medium : s.inside_medium;
}

// Direction with cosine `cos_theta` to `axis`, azimuth 2 pi u.
inline Vec3 direction_about(Vec3 axis, float cos_theta, float u) {
  float sin_theta = safe_sqrt(1 - cos_theta * cos_theta);
  float phi = 2 * kPi * u;
  return Frame(axis).to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
}

// An emission Le of `light` as the path carries it: at its wavelengths when it has them,
// from the light's spectrum where the scene gave one (Le is its colour times a factor:
// the same factor on the spectrum), else as pbrt-v4 reads an RGB emission.
inline RGB path_emission(RGB Le, const Light& light, const RenderScene& sc, const SampledWavelengths* wavelengths) {
  if (!wavelengths) return Le;
  if (light.spectrum_data >= 0) {
    const RGB& colour = light.spectrum_data_rgb;
    const int c = colour[0] >= colour[1] ? (colour[0] >= colour[2] ? 0 : 2) : (colour[1] >= colour[2] ? 1 : 2);
    if (colour[c] > 0)
      return tabulated_at(sc.spectra[std::size_t(light.spectrum_data)], *wavelengths) * (Le[c] / colour[c]);
  }
  return illuminant_at(Le, *wavelengths);
}

// Next-event estimation from point p (already offset for surfaces) in `medium`.
// `scatter(wi)` returns f(wo, wi)|cos| (or the phase function) and its sampling pdf.
// n: the unit normal of the hemisphere the scattering at p sees (zero in a medium), for
// the light selection; a path that finds a light by scattering from here weighs itself
// against this estimate with the same (p, n). Takes two dimensions whether or not it
// returns early, so that the dimensions after it do not shift. The light is chosen with the
// first number of a pair and the number, rescaled within the chosen light's share, is reused
// with the second as the light's 2D sample: each light's samples stay stratified (a separate
// number for the choice would scatter them).
template <class Scatter>
RGB estimate_direct_group(const RenderScene& sc, Vec3 p, Vec3 n, int medium, Sampler& sampler, PathCounters& counters,
                          const SampledWavelengths* wavelengths, Scatter&& scatter, int group,
                          float* group_importance = nullptr, SkyRule sky = SkyRule::Sampled) {
  const Vec2 u = sampler.get2d();
  float pmf, u_reused = 0;
  const int li = sc.light_selection.sample(u.x, p, n, &pmf, &u_reused, group, group_importance, sky);
  if (li < 0 || pmf <= 0) return RGB(0);
  const Vec2 u_position{u_reused, u.y};
  const Light& light = sc.lights[li];
  LightSample ls;
  if (!light_sample(light, sc.shapes, p, u_position, ls, n) || ls.pdf <= 0) return RGB(0);
  auto [f, scatter_pdf] = scatter(ls.wi);
  if (f.is_black()) return RGB(0);
  float dist = ls.delta && std::isinf(ls.distance) ? kInfiniteDistance : ls.distance * (1 - 1e-4f);
  RGB tr = shadow_transmittance(sc, p, ls.wi, dist, medium, counters, wavelengths);
  if (tr.is_black()) return RGB(0);
  float light_pdf = pmf * ls.pdf;
  float w = ls.delta ? 1.0f : power_heuristic(light_pdf, scatter_pdf);
  return f * tr * path_emission(ls.L, light, sc, wavelengths) * (w / light_pdf);
}

// One light sample from each group of the light selection (finite lights, lights at
// infinity: lights/light_selection.h), two dimensions each. With SkyRule::Outweighed (the
// subsurface exits), where the finite lights outweigh a uniform sky
// (LightSelection::uniform_sky_outweighed, from the importance sum the first choice
// computes), the sky's sample is not taken (its two dimensions are): the scattered
// direction, whose vertex says the same rule, finds it at MIS weight one. With
// SkyRule::GivesWay (the probes' exits, some walk strategies') no uniform sky is chosen.
template <class Scatter>
RGB estimate_direct(const RenderScene& sc, Vec3 p, Vec3 n, int medium, Sampler& sampler, PathCounters& counters,
                    const SampledWavelengths* wavelengths, Scatter&& scatter, SkyRule sky = SkyRule::Sampled) {
  float finite_importance = 0;
  RGB L = estimate_direct_group(sc, p, n, medium, sampler, counters, wavelengths, scatter, 0, &finite_importance, sky);
  if (sc.light_selection.groups(n) == 2) {
    if (sky != SkyRule::Outweighed || !sc.light_selection.uniform_sky_outweighed(finite_importance))
      L += estimate_direct_group(sc, p, n, medium, sampler, counters, wavelengths, scatter, 1, nullptr, sky);
    else
      sampler.get2d();
  }
  return L;
}

}  // namespace dermis
