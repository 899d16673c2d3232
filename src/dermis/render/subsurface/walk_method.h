// A volumetric random walk under the surface (Křivánek & d'Eon 2014; sss/walk/): the
// path refracts in at the entry and walks in the medium the material describes until
// it crosses the boundary. The boundary decides how light leaves: `diffuse` through the
// exit lobe Sw at the first crossing, `matched` straight through it, `dielectric` by
// Fresnel (internal reflection continues the walk, refraction leaves specularly).
// Textured parameters: the medium of a walk is the one at its entry point (its
// coefficients from the exact albedo inversion's table: a lookup, no simulation), kept
// for the whole walk, as in Cycles: a texture varying under the surface is blurred
// over the walk's extent, not followed. A textured roughness is the boundary's at each
// point the walk meets it (entry and exits); the albedo inversion takes the entry's.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "dermis/render/subsurface/boundary_roughness.h"
#include "dermis/render/subsurface/coefficients.h"
#include "dermis/render/subsurface/subsurface_exit.h"
#include "dermis/scene/subsurface_params.h"
#include "dermis/sss/walk/albedo_inversion.h"
#include "dermis/sss/walk/random_walk.h"

namespace dermis {

// The walk's sampling strategies, each unbiased (sss/walk/walk_step.h): the share of
// Dwivedi-guided flights (WalkSettings::p_guided) and the exponent k of the channel choice
// (WalkSettings::channel_preference). Which one renders a scene fastest at equal noise
// depends on the scene (docs/results/results-vs-cycles.md: guiding toward the entry plane wins on
// thick, dense objects and loses where light crosses a thin or translucent one; k = 1/2
// wins on skin, k = 0 on a milk-like medium lit by the sky): the render's pilot
// (render/subsurface_pilot.h) measures them and picks one per material. The first is
// the default. The others but the last have weights no more heavy-tailed than it (fewer
// guided flights, the channel weights bounded by the throughput): a short pilot
// underestimates the variance of a heavy-tailed estimator, so it may choose them on its
// estimate alone. The last, a guided share of 0.8, is more heavy-tailed: its shorter walks
// render thick, dense objects faster, its estimate reads high, and the pilot takes it only
// where its gain survives a handicap (subsurface_pilot.h, kHeavierStrategyHandicap). A
// share of 1 was not added (no classical flights under the mixture: no bound on a step's
// weight where a walk must cross a thin part), nor 0.9 (no clearer a gain than 0.8's).
// Measured: docs/results/results-pilot.md, "The strategies". A material whose `walksampling` is
// given keeps it, whatever the share.
// The fifth to the eighth give each of the camera's first entry's walks one colour channel
// (channel_per_walk below); their weights are each channel's own, no heavier.
struct WalkStrategy {
  float p_guided;
  float channel_preference;
  // At the camera's first entry (whose several exits the integrator averages, each going
  // on with its share: SubsurfaceMaterial::first_entry_exits), walk k carries colour
  // channel k mod 3 alone, every flight drawn in that channel: three walks per entry, so
  // that each channel has its own walk in every sample. One walk shared by channels whose
  // extinction differs has weights f_k / q that spread with the walk's length and
  // free paths (far more variance than the same medium with grey extinction:
  // docs/random-walk.md); a walk drawn in its own channel has the weight of a
  // grey medium's, the albedo to the power of its collisions. Where the channels' walks
  // are alike, or the noise is in finding the light (a backlit thin part), sharing wins:
  // the pilot measures which.
  bool channel_per_walk = false;
  // Whether uniform skies are light-sampled at the material's exits (SkyRule::Outweighed:
  // where the finite lights do not outweigh them), or never (SkyRule::GivesWay: the exit
  // lobe's sampled direction finds them at MIS weight one). Not a walk setting: the
  // integrator's, at the walk's exits (SubsurfaceMaterial::exit_sky_rule). Each light
  // sample is a shadow ray and a second estimate of what the lobe's direction sees: under a
  // uniform sky alone, with one channel per walk, leaving them out can pay (measured:
  // docs/results/results-pilot.md, "The strategies"). The pilot measures these two only where
  // the scene has a uniform sky (subsurface_pilot.cpp, offered_strategies).
  bool exit_sky_sampled = true;
  // Guided flights also follow the importance of the object's far side below the entry
  // point (sss/walk/random_walk.h, backward guiding; the material's `backwardguiding`).
  // Where light enters a thin part from both faces (a fin under the sky) a walk's way out
  // through either face is worth the same, and guiding toward the entry face alone fights
  // half of it; elsewhere the far side's terms cost time for nothing (measured for every
  // strategy: docs/results/results-pilot.md, "Backward guiding as a strategy"). So two strategies, the
  // channel-per-walk ones the pilot takes on fins under a sky, offered only where the far
  // side is within the walks' reach (WalkMethod::far_side_in_reach).
  bool backward_guiding = false;
};
inline constexpr std::array<WalkStrategy, 11> kWalkStrategies{{{0.5f, 0.5f},
                                                               {0.0f, 0.5f},
                                                               {0.5f, 0.0f},
                                                               {0.0f, 0.0f},
                                                               {0.5f, 0.0f, true},
                                                               {0.0f, 0.0f, true},
                                                               {0.5f, 0.0f, true, false},
                                                               {0.0f, 0.0f, true, false},
                                                               {0.8f, 0.5f},
                                                               {0.5f, 0.0f, true, true, true},
                                                               {0.5f, 0.0f, true, false, true}}};
// Walks per channel-per-walk entry: one per colour channel.
inline constexpr int kChannelWalks = 3;

// Guiding where the walks are short against the object. Dwivedi's guiding follows the
// importance of a half-space below the entry plane (Krivanek & d'Eon 2014), exact where
// the object is flat over the walks' reach; a curved or thin object bends away from that
// plane within it. So where every channel's importance length 1/(kappa sigma_t)
// (MixtureWalkStep::importance_length) is below kShortWalkChordFraction of the object's
// mean chord length 4V/S (geometry/mean_chord.h), strategies whose share is the
// default's (and not given by the material) guide with kShortWalkGuidedShare. Raising
// the short channels alone, where a long one shares the walk, did not pay. Measured in
// docs/results/results-pilot.md ("Guiding where the walks are short").
inline constexpr double kShortWalkGuidedShare = 0.8;
inline constexpr double kShortWalkChordFraction = 0.1;
// The guided share of each channel for a step whose share is the default's, inside an
// object of mean chord length `object_chord` (0: unknown): kShortWalkGuidedShare in
// every channel where all are short, else the step's own.
std::array<double, 3> short_walk_guided_shares(const sss::MixtureWalkStep<3>& step, double object_chord);

class WalkMethod {
 public:
  // textures: the scene's (outlives the method). Builds the albedo-inversion table the
  // parameters need (seconds the first time in a process; cached on disk).
  // object_chord: the mean chord length of the object the material fills (0: unknown;
  // short_walk_guided_shares).
  WalkMethod(const SubsurfaceParams& params, const std::vector<Texture>* textures, double object_chord = 0);

  // With the strategy entry.strategy (an index into kWalkStrategies; 0 the default).
  bool sample_exit(const SubsurfaceEntry& entry, Sampler& sampler, SubsurfaceExit& out) const;

  const sss::WalkMedium& medium() const { return medium_; }
  // The constant medium's step sampler of a strategy (its per-channel guided shares).
  const sss::MixtureWalkStep<3>& step(int strategy) const { return steps_.at(std::size_t(strategy)); }
  // Whether the strategy's walks carry one colour channel each at the camera's first
  // entry (WalkStrategy::channel_per_walk, or the material's `channelperwalk`).
  bool channel_per_walk(int strategy) const {
    return strategy >= 0 && strategy < int(kWalkStrategies.size()) && channel_per_walk_[std::size_t(strategy)];
  }
  // Whether the strategy's guided flights also follow the object's far side
  // (WalkStrategy::backward_guiding, or the material's `backwardguiding`).
  bool backward_guiding(int strategy) const {
    return strategy >= 0 && strategy < int(kWalkStrategies.size()) && settings_[std::size_t(strategy)].backward_guiding;
  }
  // Whether a walk may reach the object's far side: not where every channel's importance
  // length is below kShortWalkChordFraction of the object's mean chord (the walks are
  // short against the object: short_walk_guided_shares), measured on the material's
  // constant parameters; true where the chord is unknown.
  bool far_side_in_reach() const { return far_side_in_reach_; }
  // Whether the strategies that guide backward (WalkStrategy::backward_guiding) render
  // images of their own: the material leaves backward guiding to the pilot, their walks
  // are guided, and the far side is within reach. Else they are their twins' images.
  bool backward_strategies_differ() const { return backward_strategies_differ_; }

 private:
  // initial: the throughput the walk starts with (1, or one channel's).
  bool walk(const SubsurfaceEntry& entry, const sss::WalkSettings& settings, const sss::MixtureWalkStep<3>& step,
            const RGB& initial, Sampler& sampler, SubsurfaceExit& out) const;
  // The walk's first direction into the medium; false: none (no light).
  bool entry_direction(const SubsurfaceEntry& entry, Sampler& sampler, Vec3& dir) const;
  // A walk that met a rough `dielectric` boundary (res): it left (out: direction, weight,
  // direction_pdf), reflected back in (out.direction: the way on), or was lost; `weight`
  // is the walk's, updated.
  enum class RoughCrossing { Out, Back, Lost };
  RoughCrossing cross_rough_boundary(const SubsurfaceEntry& entry, const sss::WalkResult& res, Vec3 ns,
                                     BoundaryAlphas alpha, RGB& weight, Sampler& sampler, SubsurfaceExit& out) const;
  // Whether the walks of this entry sample light through the smooth `dielectric` boundary
  // at their scattering events (refracted_light.h): the boundary is smooth everywhere and
  // the integrator offers the lights.
  bool samples_refracted_light(const SubsurfaceEntry& entry) const;
  // Light sampled through the boundary at the walk's scattering event y (the flight
  // arrived along `incoming`), with the walk's throughput there; `plane` is the entry
  // point's (refracted_light.h).
  RGB refracted_light_at(const SubsurfaceEntry& entry, const RefractedLight& light, const sss::MixtureWalkStep<3>& step,
                         const SurfaceHit& plane, Vec3 y, Vec3 incoming, const std::array<double, 3>& throughput,
                         Sampler& sampler) const;

  SubsurfaceParams params_;
  const std::vector<Texture>* textures_;
  AlbedoInversions inversions_;  // (reflectance, mfp) -> coefficients; empty: given, or the fit
  SubsurfaceParams::Boundary boundary_;
  float eta_;
  BoundaryRoughness roughness_;
  bool lambertian_entry_;  // SubsurfaceParams::lambertian_entry  // the boundary's alphas per point (the `dielectric`
                           // boundary's exits)
  // The medium differs from one entry point to another: textured parameters, or a
  // textured roughness that the albedo inversion depends on.
  bool medium_per_entry_ = false;
  sss::WalkMedium medium_;  // the constant parameters' medium
  // Per strategy (kWalkStrategies): the settings and the constant medium's step sampler.
  std::array<sss::WalkSettings, kWalkStrategies.size()> settings_;
  std::array<bool, kWalkStrategies.size()> channel_per_walk_{};
  std::vector<sss::MixtureWalkStep<3>> steps_;
  double object_chord_ = 0;
  bool far_side_in_reach_ = true;
  bool backward_strategies_differ_ = false;
  // Per strategy: its guided share is the default's, not the material's (the step takes
  // short_walk_guided_shares).
  std::array<bool, kWalkStrategies.size()> short_walk_rule_{};
  // This method among all made in the process: the key of a thread's last textured step
  // (walk_method.cpp), which an address, reused by a later method, could not be.
  uint64_t id_;
};

}  // namespace dermis
