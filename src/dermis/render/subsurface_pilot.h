// The render's pilot for its random-walk and disk materials: before the image, a few camera
// samples measure each material's sampling strategies (the walk's kWalkStrategies: the
// share of Dwivedi-guided flights and the channel choice; the disk's probe axes,
// kDiskNormalAxisShares), and each material takes the one with the least variance x
// cost. Every strategy is unbiased, so the choice changes the noise and the time, never
// the mean.
//
// Why: which strategy renders a scene fastest depends on the scene (docs/results/results-vs-cycles.md,
// the scene family): guiding toward the entry plane wins on thick, dense objects and loses
// where light crosses a thin one; k = 1/2 suits skin, k = 0 a milk-like medium under the
// sky; probes along the normal alone suit a surface flat at the profile's reach, and all
// three axes an object the profile wraps; no single setting wins everywhere. The pilot
// measures instead of guessing.
//
// Measured: per pilot pixel, two samples with the independent sampler (their difference
// gives the variance of one sample, R + G + B), the same numbers for every strategy;
// cost counted in rays traced, so that the choice is the same on every machine, thread
// count and process count. A sample counts toward the material its camera path entered
// first (pixels whose two samples disagree are left out). Deterministic: the pilot's
// pixels, samples and sums are fixed, and the same in every process of a group; a resumed
// render makes the same choice. Two stages, each on half of the pixels: the second only
// where the first leaves a strategy that could be worth a switch (no_strategy_can_gain).
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "dermis/render/film.h"
#include "dermis/render/render_scene.h"

namespace dermis {

// What the pilot measured of one strategy on one material.
struct StrategyMeasure {
  int64_t pixels = 0;   // pilot pixels whose samples both entered the material first
  double variance = 0;  // of one camera sample, R + G + B
  double rays = 0;      // per camera sample
  // The standard error of log(variance / the default's variance), from the pixels both
  // measured (paired: the strategies share their random numbers up to the walk, so
  // their estimates' common noise cancels). 0 for the default itself.
  double log_ratio_se = 0;
  // A factor on the measured variance x cost: kHeavierStrategyHandicap for a strategy whose
  // weights are more heavy-tailed than the default's, else 1.
  double handicap = 1;
  double variance_cost() const { return variance * rays * handicap; }  // the inverse of the efficiency
};

// The pilot's estimate of a strategy with more guided flights than the default (heavier-
// tailed weights: walk_method.h, kWalkStrategies) is divided by this before the choice.
// Such a strategy's estimated gain reads above the gain it renders with: a pilot of two
// independent samples per pixel misses the rare large weights that the mean holds, and
// Owen-scrambled Sobol' stratifies the default's lighter-tailed walks better. The
// estimates are precise, so the 2-sigma significance does not catch this, and a smaller
// handicap let through choices that then rendered slower (measured: docs/results/results-pilot.md,
// "A guided share of 0.8 with a handicap").
inline constexpr double kHeavierStrategyHandicap = 1.25;
// The pilot's estimate of a walk strategy that guides backward too (WalkStrategy::
// backward_guiding) is divided by this before the choice. Its far-side terms cost
// arithmetic at every step that the pilot's count of rays does not see, and its estimated
// gains over the choice without it read above what it rendered with: with this handicap
// the pilot keeps it on the fins under the sky alone, where it pays (measured:
// docs/results/results-pilot.md, "Backward guiding as a strategy").
inline constexpr double kBackwardGuidingHandicap = kHeavierStrategyHandicap;
// The handicap of walk strategy `strategy` (kWalkStrategies) for a material: the one above
// where it guides backward (unless the material gives `backwardguiding`: then every
// strategy does or none), kHeavierStrategyHandicap where it has more guided flights than
// the default, unless the material's parameters pin the share (every strategy then has
// it); else 1.
double pilot_handicap(const SubsurfaceParams& params, int strategy);

// Of the strategies whose estimated gain over the default (0) is significant (log(gain)
// above `sigmas` x log_ratio_se), the one with the least variance x cost; the default
// where none is, or where any strategy was measured on fewer than min_pixels pixels.
// (Not the least variance x cost, then tested: among eight strategies the noisiest
// estimate is often the least and not significant, and the default then stayed where
// another strategy's gain was clear.)
int best_strategy(const std::vector<StrategyMeasure>& measures, int64_t min_pixels, double sigmas);
// Of the pilot's choice: a switch needs a gain this many standard errors above 1.
inline constexpr double kPilotSignificance = 2;

// The pilot measures in two stages, each on half of its pixels (spread over the whole
// object). Where after the first no strategy of any material could be worth switching
// to, the second is not rendered and every material keeps its default: no strategy's
// gain, `sigmas` standard errors above its estimate, reaches kPilotWorthwhileGain. (A
// gain below that is not worth the second stage's cost, which is half the pilot's:
// docs/rendering.md, "The subsurface pilot".) False where any strategy was measured on fewer than
// min_pixels pixels or not comparably (infinite standard error).
bool no_strategy_can_gain(const std::vector<StrategyMeasure>& measures, int64_t min_pixels, double sigmas);
inline constexpr double kPilotWorthwhileGain = 1.05;

struct SubsurfaceChoice {
  int material = -1;              // RenderScene::subsurface index
  int strategy = 0;               // the walk's kWalkStrategies
  int pixels = 0;                 // pilot pixels that measured it
  double gain = 1;                // estimated efficiency of the choice over the default's (strategy 0)
  double gain_se = 0;             // its standard error
  bool first_stage_only = false;  // settled after the first of the pilot's two stages
  std::string description;        // for the user: describe_subsurface_choice
};

struct SubsurfacePilotOptions {
  uint64_t seed = 0;
  int spp = 16;                    // the render's: the pilot takes 1/160 of its subsurface samples per strategy
  PixelBounds bounds{0, 0, 0, 0};  // the pixels rendered (the crop window)
  int full_width = 0;              // of the image: pixel indices of the sampler
  const std::atomic<bool>* cancel = nullptr;
};

// A material's choice needs at least this many pilot pixels (else it keeps the default).
inline constexpr int64_t kMinPilotPixels = 32;

// The strategies the pilot measures, of the first `count`: those that render an image of
// their own for some material of the scene. A walk's strategies (kWalkStrategies) that
// differ from another only where a uniform sky is light-sampled at exits
// (WalkStrategy::exit_sky_sampled) do not, when the scene has none (their pilot samples
// would be wasted); every strategy of the disk (kDiskNormalAxisShares) does.
std::vector<int> offered_strategies(const RenderScene& scene, int count);

// Whether a material has strategies to choose from and the scene did not turn the pilot off.
bool subsurface_pilot_wanted(const RenderScene& scene);

// Measures and chooses (parallel over the pilot's pixels with the calling arena's
// threads). Empty when cancelled or when no subsurface object is in view.
std::vector<SubsurfaceChoice> run_subsurface_pilot(const RenderScene& scene, const SubsurfacePilotOptions& options);

// The strategy of each material (PathStart::subsurface_strategies): its choice, else the
// default (0).
std::vector<int> subsurface_strategies(const RenderScene& scene, const std::vector<SubsurfaceChoice>& choices);

// "material 1 (randomwalk): guided share 0, channel preference 0.5; 1.40x the default's
// efficiency (estimated on 512 pilot pixels)".
std::string describe_subsurface_choice(const RenderScene& scene, const SubsurfaceChoice& choice);

}  // namespace dermis
