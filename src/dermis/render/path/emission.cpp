#include "dermis/render/path/emission.h"

#include "dermis/render/path/direct_light.h"

namespace dermis {

void add_emission_at_infinity(const PathContext& ctx, PathState& st) {
  const RenderScene& sc = ctx.sc;
  for (int li : sc.infinite_lights) {
    const Light& light = sc.lights[li];
    float light_density;
    RGB Le = infinite_light_radiance(light, st.ray.d, st.prev_n, &light_density);
    if (Le.is_black()) continue;
    Le = path_emission(Le, light, sc, ctx.start.wavelengths);
    float w = st.specular ? 1.0f
                          : power_heuristic(st.prev_pdf, sc.light_selection.pmf(li, st.prev_p, st.prev_n, st.prev_sky) *
                                                             light_density);
    st.L += st.beta * Le * (w * st.emission_weight);
  }
}

void add_area_emission(const PathContext& ctx, PathState& st, const Shape& s, const SurfaceHit& hit) {
  const RenderScene& sc = ctx.sc;
  int li = s.first_light + (s.type == Shape::Type::Mesh ? hit.prim : 0);
  const Light& light = sc.lights[li];
  RGB Le = area_light_radiance(light, hit.ng, -st.ray.d);
  if (Le.is_black()) return;
  Le = path_emission(Le, light, sc, ctx.start.wavelengths);
  float w = st.specular ? 1.0f
                        : power_heuristic(st.prev_pdf, sc.light_selection.pmf(li, st.prev_p, st.prev_n, st.prev_sky) *
                                                           light_pdf(light, st.prev_p, st.ray.d, hit.p, hit.ng));
  st.L += st.beta * Le * (w * st.emission_weight);
}

RGB emission_seen(const RenderScene& sc, const Ray& ray, PathCounters& counters, const SampledWavelengths* wavelengths,
                  RGB* rgb) {
  SurfaceHit hit;
  counters.count(ray);
  RGB Le(0), in_rgb(0);
  if (!sc.embree->intersect(ray, hit)) {
    for (int li : sc.infinite_lights) {
      const RGB e = infinite_light_radiance(sc.lights[li], ray.d);
      in_rgb += e;
      Le += path_emission(e, sc.lights[li], sc, wavelengths);
    }
  } else if (const Shape& s = sc.shapes[hit.shape]; s.first_light >= 0) {
    const int li = s.first_light + (s.type == Shape::Type::Mesh ? hit.prim : 0);
    in_rgb = area_light_radiance(sc.lights[li], hit.ng, -ray.d);
    Le = path_emission(in_rgb, sc.lights[li], sc, wavelengths);
  }
  if (rgb) *rgb = in_rgb;
  return Le;
}

float mean_sky_luminance(const RenderScene& sc) {
  float sum = 0;
  for (int li : sc.infinite_lights) {
    const Light& l = sc.lights[li];
    sum += l.environment ? l.environment->average_luminance() : l.emission.luminance();
  }
  return sum;
}

bool may_see_bright_emission(const RenderScene& sc, const Ray& ray) {
  if (sc.light_selection.may_meet_finite_emitter(ray.o, ray.d)) return true;
  RGB Le(0);
  for (int li : sc.infinite_lights) Le += infinite_light_radiance(sc.lights[li], ray.d);
  return Le.luminance() > 2 * mean_sky_luminance(sc);
}

bool add_bright_emission_seen(const RenderScene& sc, const Ray& ray, RGB weight, PathCounters& counters,
                              const SampledWavelengths* wavelengths, RGB& L) {
  if (!may_see_bright_emission(sc, ray)) return false;
  RGB in_rgb;  // the choice is made in RGB
  const RGB Le = emission_seen(sc, ray, counters, wavelengths, &in_rgb);
  if (!(in_rgb.luminance() > 2 * mean_sky_luminance(sc))) return false;
  L += weight * Le;
  return true;
}

}  // namespace dermis
