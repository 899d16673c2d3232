// Light sampled through a smooth dielectric boundary from a scattering event inside it
// (the walk's `dielectric` boundary). A smooth boundary refracts: a walk leaves along one
// direction, and light sampling at the exit point is impossible, so a small light or a
// sun is found only by the walks that happen to leave toward it. Here, at a scattering
// event y, a direction w toward a light is drawn as next-event estimation would draw it
// from y, and the flight direction v that refracts into w through a plane of normal
// n_ref is taken: the flat-boundary solution of the refracted path (Walter et al. 2009,
// "Single scattering in refractive media with triangle mesh boundaries", sec. 4, for a
// planar facet). The flight along v meets the real boundary at x; the light arriving
// there along the direction v actually refracts into is evaluated. This is a direction
// sampling technique at y with density p_light(w(v)) |dw/dv| for any n_ref (exact where
// the boundary near the walk is that plane, unbiased everywhere), weighed against the
// walk's own scattering by multiple importance sampling (Veach 1997, eq. 9.13, power
// heuristic): a walk that leaves right after a scattering event weighs the emission it
// meets next by the complement (SubsurfaceExit::emission_weight).
#pragma once

#include <optional>

#include "dermis/core/function_ref.h"
#include "dermis/core/rgb.h"
#include "dermis/core/vec.h"

namespace dermis {

// The scene's lights as seen from a point in the medium, from the integrator.
struct LightsFromInside {
  // A direction w toward a light drawn from y with (u1, u2) as next-event estimation in a
  // medium draws it, and the density of drawing w (every light along it); false: none.
  FunctionRef<bool(Vec3 y, float u1, float u2, Vec3& w, float& density)> sample;
  // The density with which `sample` draws w from y.
  FunctionRef<float(Vec3 y, Vec3 w)> density;
  // The emission reaching the boundary point x (outward normal n) from direction w
  // outside: the first surface along w if it emits, or the lights at infinity.
  FunctionRef<RGB(Vec3 x, Vec3 n, Vec3 w)> emission;
  // The unit direction from y toward the lights sampled, to aim the plane of refraction
  // (the finite lights' centre weighted by power, or an environment map's sun:
  // lights_from_inside.h, KeyLight); false where there is none.
  FunctionRef<bool(Vec3 y, Vec3& toward)> key_direction;
};

// Refraction through a plane of unit normal n pointing out of the medium (index eta) into
// index 1: v inside, toward the plane (dot(v, n) > 0), w outside, away from it
// (dot(w, n) > 0); Snell's law sin(w) = eta sin(v). `jacobian` is dw/dv, the ratio of their solid angles:
// eta^2 cos(v) / cos(w) (the invariance of n^2 cos dw: Veach 1997, sec. 5.2).
// Inside to outside; nullopt under total internal reflection or for dot(v, n) <= 0.
std::optional<Vec3> refracted_out(Vec3 v, Vec3 n, float eta, float* jacobian = nullptr);
// Outside to inside (always defined for dot(w, n) > 0); nullopt otherwise.
std::optional<Vec3> refracted_in(Vec3 w, Vec3 n, float eta, float* jacobian = nullptr);

// The technique for one walk: the lights and the boundary's index. At each scattering
// event y the caller gives the plane's normal n_ref, a function of y alone (never of the
// directions drawn there), so that the density of a direction is known both where the
// light is sampled and where the walk leaves.
class RefractedLight {
 public:
  RefractedLight(const LightsFromInside& lights, float eta) : lights_(lights), eta_(eta) {}

  const LightsFromInside& lights() const { return lights_; }

  // A flight direction v from y drawn by the technique about the plane of normal n_ref,
  // and its density; false: none.
  bool sample(Vec3 y, Vec3 n_ref, float u1, float u2, Vec3& v, float& density) const;
  // The density with which sample() draws v from y (0 where v cannot refract out).
  float density(Vec3 y, Vec3 n_ref, Vec3 v) const;
  // The multiple-importance weight of the walk's own flight from y along v (phase
  // function density `phase`) for the emission it meets next after leaving, against
  // sample() taken with probability `chance` at y.
  float walk_weight(Vec3 y, Vec3 n_ref, Vec3 v, float phase, float chance) const;

 private:
  const LightsFromInside& lights_;
  float eta_;
};

}  // namespace dermis
