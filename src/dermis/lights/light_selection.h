// Which light next-event estimation samples at a shading point.
//
// With few lights (at most kPointwiseLightLimit), each light is chosen in proportion to a
// bound on the irradiance it can bring to the point — its emitted radiance, its solid
// angle and the cosines at both ends, bounded over the light's bounding sphere (the
// light importance of Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights
// with Adaptive Tree Splitting", eq. 3, for one light per cluster; pbrt-v4's
// ExhaustiveLightSampler). The bound is conservative: a light that can reach the point
// (or the hemisphere of its normal) never has probability zero, so the estimator stays
// unbiased; one that cannot (behind the surface, outside a spot's cone) is never
// chosen. A small key light near a skin-like object thus gets the samples it deserves
// instead of half of them going to a dim sky.
// When a scene has both lights at infinity (sky, sun) and finite lights, the two groups
// are sampled separately, one light from each (stratification over the groups): a choice
// between them makes each sample carry one group's light scaled up, and when the sky's
// light sample is mostly weighted away by MIS (a cosine-like BSDF finds a constant sky by
// itself) that choice alone multiplied the variance of a Lambertian sphere twenty-fold.
// A uniform sky (an `infinite` light without an image) gives way to the other lights where
// they outweigh it: it is not chosen, its probability is zero in pmf() too, and its
// emission is found by the sampled scattering directions at MIS weight one. In a medium
// that is where the other lights' importances sum to more than its own (4 pi L); at a
// surface point where the caller asks for it (SkyRule::Outweighed: the integrator's subsurface
// exits), where the lights at infinity are a group of their own and all uniform skies,
// where the finite lights' importances sum to more than theirs (pi L). Its light samples
// draw directions as the scattering nearly does (uniformly over the sphere in a medium,
// by the cosine at a surface), so MIS keeps about half of each (against a technique that
// covers it, a constant emitter's compensated density is zero: Karlik et al. 2019, "MIS
// compensation"), and each is a shadow ray that costs as much as the key light's and a
// sample the brighter lights lose (in a medium, where one light is chosen among all).
// What its light samples add is the transmittance computed instead of flown through,
// which deep in a dense medium under a bright sky is most of the light, and their
// stratification against an unoccluded sky: where the sky outweighs the others it keeps
// its share: in a medium the variance falls at the same time, and under a sky that
// outweighs the key light the images are unchanged. At surfaces it paid at subsurface
// exits only, not on a Lambertian sphere (the sky's stratified light sample and the BSDF's
// direction are two samples of what the cosine lobe covers), so not at other surfaces
// (measured: docs/results/results-rendering.md, "Light selection"). SkyRule::GivesWay goes further where the caller
// asks: the uniform skies are never chosen (the probe methods' exits, and walk strategies
// the render's pilot may choose: render/subsurface/subsurface_method.h, exit_sky_rule).
// With more lights, a point-independent distribution in proportion to power (lights at
// infinity and finite lights as two groups, each chosen with probability 1/2).
#pragma once

#include <cstddef>
#include <vector>

#include "dermis/core/distribution.h"
#include "dermis/core/vec.h"
#include "dermis/lights/light.h"

namespace dermis {

inline constexpr std::size_t kPointwiseLightLimit = 32;

// Whether uniform skies are light-sampled at a surface point (the header's rule; in a
// medium the rule always applies).
enum class SkyRule : unsigned char {
  Sampled,     // they are (every surface point but a subsurface exit)
  Outweighed,  // they give way where the finite lights outweigh them (subsurface exits)
  // They always give way: never chosen, probability zero, their emission found by the
  // scattered directions at MIS weight one. A walk strategy the render's pilot may choose
  // at subsurface exits (render/subsurface/walk_method.h, WalkStrategy::exit_sky_sampled).
  GivesWay,
};

class LightSelection {
 public:
  LightSelection() = default;
  // `scene_radius` bounds the power of lights at infinity (power distribution only).
  // outweighed_sky_gives_way: the rule above (tests turn it off to compare).
  LightSelection(const std::vector<Light>& lights, float scene_radius, bool outweighed_sky_gives_way = true);

  bool pointwise() const { return pointwise_; }
  std::size_t size() const { return count_; }
  // 2 when finite lights and lights at infinity are sampled separately (group 0 and 1) at
  // a point with normal n, else 1 (group 0: every light). Only surface points split: in a
  // medium (n zero) the sky's light sample is not weighted away by a cosine-like lobe, and
  // a second shadow ray through the medium cost about what it saved (docs/rendering.md,
  // "Light selection").
  int groups(Vec3 n) const { return split_ && surface(n) ? 2 : 1; }

  // Chooses a light for the point p whose scattering sees only the hemisphere about the
  // unit normal n (zero for a point in a medium). Returns -1 (pmf 0) when no light can
  // reach the point. `u_remapped`, when given, receives u rescaled to [0, 1) within the
  // chosen light's interval: uniform and independent of the choice, so that it can serve
  // as one coordinate of the light's 2D sample, which then stays stratified within each
  // light (as Cycles' light_distribution_sample reuses its number).
  // `group_importance`, when given, receives the sum of the group's importances at (p, n)
  // (0 when the selection is not pointwise).
  // `sky`: at a surface point, whether the rule above applies there (SkyRule: the
  // integrator lets it at subsurface exits only); in a medium it always does.
  int sample(float u, Vec3 p, Vec3 n, float* pmf, float* u_remapped = nullptr, int group = 0,
             float* group_importance = nullptr, SkyRule sky = SkyRule::Sampled) const;
  // The probability that sample() for the light's group chooses `light` at (p, n), with
  // the same rule.
  float pmf(int light, Vec3 p, Vec3 n, SkyRule sky = SkyRule::Sampled) const;

  // At a surface point where the lights at infinity are sampled as a group of their own
  // (groups(n) == 2): true when the rule above leaves them out at a point that asks for it
  // (SkyRule::Outweighed), that is when all of them are uniform skies and the finite lights'
  // importances, `finite_importance` (sample()'s group_importance for group 0), sum to
  // more than theirs. sample() for group 1 with that rule then chooses none; a caller
  // that has the sum may skip that call.
  bool uniform_sky_outweighed(float finite_importance) const {
    return outweighed_sky_gives_way_ && infinite_all_uniform_ && finite_importance > uniform_sky_importance_;
  }

  // Whether SkyRule::GivesWay may change what sample() chooses: a uniform sky among the
  // lights, chosen pointwise.
  bool has_uniform_sky() const {
    for (const Bounds& b : bounds_)
      if (b.uniform_sky) return true;
    return false;
  }

  // Whether sample() with SkyRule::GivesWay chooses no light anywhere: there is none, or
  // every light is a uniform sky (known where the bounds are kept: pointwise selection).
  // Asked at every subsurface entry: known from construction.
  bool gives_way_leaves_none() const { return gives_way_leaves_none_; }

  // Whether a ray from o along the unit direction d may meet a finite emitter (an area
  // light: its bounding sphere in front of o, with a margin for round-off); conservative:
  // true whenever the bounds are not kept (more than kPointwiseLightLimit lights).
  bool may_meet_finite_emitter(Vec3 o, Vec3 d) const;

  // The unnormalised importance of light i at (p, n) (emissions relative to the brightest
  // light's); zero only where it cannot contribute. Exposed for tests. (The uniform-sky
  // rule above is applied over all lights, in sample() and pmf(), not here.)
  float importance(std::size_t i, Vec3 p, Vec3 n) const;

 private:
  static bool surface(Vec3 n) { return n.x != 0 || n.y != 0 || n.z != 0; }
  // The weights sample() chooses from for the group at (p, n), their sum returned.
  float weights(Vec3 p, Vec3 n, int group, float* w, SkyRule sky) const;
  // The group light i is sampled in at a point with normal n.
  int group_of(std::size_t i, Vec3 n) const { return groups(n) == 2 ? group_[i] : 0; }

  struct Bounds {
    Light::Type type;
    Vec3 center;  // bounding sphere of an area light; position of point and spot
    float radius = 0;
    Vec3 normal;         // triangle's unit normal (either side); spot axis; toward a distant light
    float emission = 0;  // average radiance (area, infinite), intensity (point, spot), irradiance (distant),
                         // divided by the largest of them
    float area = 0;      // triangle: area; sphere: its cross-section
    float cos_falloff_end = -1;
    bool uniform_sky = false;  // an infinite light of constant radiance (no image)
  };

  std::vector<Bounds> bounds_;
  Distribution1D power_;
  std::vector<char> group_;  // per light: 1 for lights at infinity when split_, else 0
  std::size_t count_ = 0;
  bool pointwise_ = false;
  bool split_ = false;
  bool outweighed_sky_gives_way_ = true;
  bool infinite_all_uniform_ = false;  // split_, and every light at infinity is a uniform sky
  float uniform_sky_importance_ = 0;   // their importances at a surface point, summed
  bool gives_way_leaves_none_ = true;  // no light, or uniform skies alone (pointwise)
};

}  // namespace dermis
