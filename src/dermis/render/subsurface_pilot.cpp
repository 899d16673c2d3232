#include "dermis/render/subsurface_pilot.h"

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "dermis/core/rng.h"
#include "dermis/core/sampler.h"
#include "dermis/geometry/shading_normal.h"
#include "dermis/materials/bsdf.h"
#include "dermis/materials/material.h"
#include "dermis/render/integrator.h"

namespace dermis {

namespace {

// Per strategy measured, the pilot takes about this share of the samples the render takes
// where a subsurface object is in view (1/20 over the eight strategies it had before the
// ninth), within the bounds below, so that offering another strategy does not thin the
// others' measures: each pilot pixel measures every strategy with the same numbers, and
// their count, pixels and figures are those of fewer strategies.
constexpr double kPilotSharePerStrategy = 0.05 / 8;
// The floor and the ceiling are per strategy measured too (the floor: 96 pixels of two
// samples each, a little more than the 85 that a floor of 1024 samples gave six strategies).
constexpr int64_t kPilotMinSamplesPerStrategy = 192, kPilotMaxSamplesPerStrategy = 131072 / 8;
// Pixels probed for a subsurface object in view (one camera ray each), at most.
constexpr int64_t kPilotProbes = 262144;
// Samples per pilot pixel: their difference gives the variance of one sample.
constexpr int kPilotSamples = 2;
// The most smooth specular vertices (glass, mirrors) a pilot probe follows.
constexpr int kPilotChainVertices = 8;

// What the pilot's samples of one pixel did, for one strategy.
struct PilotPixel {
  std::array<int, kPilotSamples> material{-1, -1};
  std::array<RGB, kPilotSamples> radiance{};
  uint64_t rays = 0;
  bool finite = true;
};

}  // namespace

int best_strategy(const std::vector<StrategyMeasure>& measures, int64_t min_pixels, double sigmas) {
  if (measures.empty()) return 0;
  for (const StrategyMeasure& m : measures)
    if (m.pixels < min_pixels) return 0;
  const StrategyMeasure& d = measures[0];
  int best = 0;
  for (std::size_t v = 1; v < measures.size(); ++v) {
    const StrategyMeasure& m = measures[v];
    if (!(m.variance_cost() > 0) || !(m.variance_cost() < measures[std::size_t(best)].variance_cost())) continue;
    const double log_gain = std::log(d.variance_cost() / m.variance_cost());
    if (log_gain > sigmas * m.log_ratio_se) best = int(v);
  }
  return best;
}

bool no_strategy_can_gain(const std::vector<StrategyMeasure>& measures, int64_t min_pixels, double sigmas) {
  if (measures.empty()) return true;
  for (const StrategyMeasure& m : measures)
    if (m.pixels < min_pixels) return false;
  const double d = measures[0].variance_cost();
  if (!(d > 0)) return false;
  for (std::size_t v = 1; v < measures.size(); ++v) {
    const StrategyMeasure& m = measures[v];
    if (!(m.variance_cost() > 0) || !std::isfinite(m.log_ratio_se)) return false;
    if (std::log(d / m.variance_cost()) + sigmas * m.log_ratio_se >= std::log(kPilotWorthwhileGain)) return false;
  }
  return true;
}

namespace {
// Whether walk strategy `strategy` guides backward by the pilot's choice (not because the
// material gives `backwardguiding`): it carries kBackwardGuidingHandicap.
bool backward_by_choice(const SubsurfaceParams& params, int strategy) {
  return params.method == SubsurfaceParams::Method::RandomWalk && strategy > 0 &&
         strategy < int(kWalkStrategies.size()) && kWalkStrategies[std::size_t(strategy)].backward_guiding &&
         !params.backward_guiding_given;
}
}  // namespace

double pilot_handicap(const SubsurfaceParams& params, int strategy) {
  if (params.method == SubsurfaceParams::Method::Disk)  // fewer probes along T and B: heavier-tailed
    return strategy > 0 && strategy < int(kDiskNormalAxisShares.size()) &&
                   kDiskNormalAxisShares[std::size_t(strategy)] > kDiskNormalAxisShares[0]
               ? kHeavierStrategyHandicap
               : 1;
  if (params.method != SubsurfaceParams::Method::RandomWalk) return 1;
  if (strategy <= 0 || strategy >= int(kWalkStrategies.size())) return 1;
  // Backward guiding's far-side terms cost arithmetic at every step that the pilot's ray
  // count does not see, and its estimates read above what the strategy rendered with
  // (kBackwardGuidingHandicap).
  if (backward_by_choice(params, strategy)) return kBackwardGuidingHandicap;
  if (params.guided_share_pinned()) return 1;  // every strategy has the given share
  return kWalkStrategies[std::size_t(strategy)].p_guided > kWalkStrategies[0].p_guided ? kHeavierStrategyHandicap : 1;
}

bool subsurface_pilot_wanted(const RenderScene& sc) {
  if (!sc.settings.subsurface_pilot) return false;
  for (const auto& m : sc.subsurface)
    if (m && m->strategy_count() > 1) return true;
  return false;
}

// Whether the camera sees a subsurface object along `ray`: directly, or through smooth
// glass, mirrors and index-matched boundaries (the camera's path there, whose first
// subsurface entry is the camera's first entry: integrator.cpp, camera_chain). At glass
// the way on is the transmission, as the camera path's after its first hit's reflection
// is split off; under total internal reflection, the reflection.
bool camera_sees_subsurface(const RenderScene& sc, Ray ray) {
  for (int vertex = 0; vertex < kPilotChainVertices; ++vertex) {
    SurfaceHit hit;
    if (!sc.embree->intersect(ray, hit)) return false;
    const int index = sc.shapes[std::size_t(hit.shape)].material;
    if (index < 0) return false;
    const Vec3 wo = -ray.d;
    const Material& m = sc.materials[std::size_t(resolve_material(sc.materials, sc.textures, index, hit, wo, 0))];
    if (m.subsurface >= 0) return true;
    if (m.is_interface()) {
      ray = Ray{offset_ray_origin(hit.p, hit.ng, ray.d), ray.d};
      continue;
    }
    hit.ns = shading_normal_seen_from(hit, wo);
    const BSDF b = bsdf_at(m, sc.textures, hit);
    if (!b.is_specular() || b.type == BSDF::Type::Coated) return false;
    const auto bs = bsdf_sample(b, wo, 1.0f, Vec2{0.5f, 0.5f});
    if (!bs) return false;
    ray = Ray{offset_ray_origin(hit.p, hit.ng, bs->wi), bs->wi};
  }
  return false;
}

// Whether strategy v of material m renders its own image: every strategy of a method
// other than the walk; a walk's where it differs from another otherwise than in light-
// sampling a uniform sky at exits, or where the scene has one, and otherwise than in
// guiding backward, or where that changes the walks (WalkMethod::backward_strategies_differ).
bool strategy_differs(const RenderScene& sc, const SubsurfaceMaterial& m, int v) {
  if (v < 0 || v >= m.strategy_count()) return false;
  const auto* walk = std::get_if<WalkMethod>(&m.method);
  if (v == 0 || !walk) return true;
  const WalkStrategy& w = kWalkStrategies[std::size_t(v)];
  if (w.backward_guiding && !walk->backward_strategies_differ()) return false;
  return w.exit_sky_sampled || sc.light_selection.has_uniform_sky();
}

std::vector<int> offered_strategies(const RenderScene& sc, int count) {
  std::vector<int> offered;
  for (int v = 0; v < count; ++v) {
    bool differs = v == 0;
    for (const auto& m : sc.subsurface) differs = differs || (m && strategy_differs(sc, *m, v));
    if (differs) offered.push_back(v);
  }
  return offered;
}

namespace {

// The pixels whose centre sees a subsurface object, of at most kPilotProbes evenly spaced
// in raster order (indices into the rendered bounds): the pilot spends its samples there.
// `rendered` is the number of pixels rendered; `probes`, how many were probed.
std::vector<int64_t> pixels_seeing_subsurface(const RenderScene& sc, const PixelBounds& bounds, int64_t& probes) {
  const int64_t rendered = int64_t(bounds.width()) * bounds.height();
  probes = std::min(rendered, kPilotProbes);
  if (probes <= 0) return {};
  std::vector<uint8_t> sees(std::size_t(probes), 0);
  auto probe_pixel = [&](int64_t i) { return int64_t((double(i) + 0.5) * double(rendered) / double(probes)); };
  tbb::parallel_for(int64_t(0), probes, [&](int64_t i) {
    const int64_t index = probe_pixel(i);
    const Vec2 centre{float(bounds.x0 + index % bounds.width()) + 0.5f,
                      float(bounds.y0 + index / bounds.width()) + 0.5f};
    sees[std::size_t(i)] = camera_sees_subsurface(sc, sc.camera.generate_ray(centre, Vec2{0.5f, 0.5f})) ? 1 : 0;
  });
  std::vector<int64_t> candidates;
  for (int64_t i = 0; i < probes; ++i)
    if (sees[std::size_t(i)]) candidates.push_back(probe_pixel(i));
  return candidates;
}

// The pilot: every strategy offered rendered on pixels that see a subsurface object, and
// each material's strategies measured against its default.
class SubsurfacePilot {
 public:
  SubsurfacePilot(const RenderScene& sc, const SubsurfacePilotOptions& opt, std::vector<int> offered,
                  std::vector<int64_t> candidates, double object_pixels)
      : sc_(sc),
        opt_(opt),
        offered_(std::move(offered)),
        strategies_(int(offered_.size())),
        candidates_(std::move(candidates)),
        filter_(sc.film.filter),
        pilot_seed_(mix64(opt.seed ^ 0x5eb5a11f0ull)) {  // not the image's numbers
    const int64_t samples =
        std::clamp<int64_t>(int64_t(kPilotSharePerStrategy * strategies_ * double(opt.spp) * object_pixels),
                            kPilotMinSamplesPerStrategy * strategies_, kPilotMaxSamplesPerStrategy * strategies_);
    count_ = std::clamp<int64_t>(samples / (int64_t(kPilotSamples) * strategies_), 1, int64_t(candidates_.size()));
    pixels_.resize(std::size_t(count_) * std::size_t(strategies_));
    for (int v : offered_) every_material_.emplace_back(sc.subsurface.size(), v);
  }

  // The two stages: the even pilot pixels, then the odd ones (each stage spread over the
  // whole object), both where the first did not settle every material.
  std::vector<SubsurfaceChoice> run() {
    render_stage(0);
    if (opt_.cancel && opt_.cancel->load()) return {};
    bool settled = true;  // every material's choice is the default after the first stage
    for (std::size_t m = 0; m < sc_.subsurface.size() && settled; ++m)
      if (!strategies_of(m).empty()) settled = no_strategy_can_gain(measure(m, 2), kMinPilotPixels, kPilotSignificance);
    if (!settled) {
      render_stage(1);
      if (opt_.cancel && opt_.cancel->load()) return {};
    }
    return choose(settled);
  }

 private:
  PilotPixel& pixel(int64_t k, int v) { return pixels_[std::size_t(k) * std::size_t(strategies_) + std::size_t(v)]; }
  const PilotPixel& pixel(int64_t k, int v) const {
    return pixels_[std::size_t(k) * std::size_t(strategies_) + std::size_t(v)];
  }

  // Pilot pixel k, every strategy offered: two samples each, with the same numbers.
  void render_pixel(int64_t k) {
    const int64_t index = candidates_[std::size_t((double(k) + 0.5) * double(candidates_.size()) / double(count_))];
    const PixelBounds& b = opt_.bounds;
    const int x = b.x0 + int(index % b.width()), y = b.y0 + int(index / b.width());
    const uint64_t image_pixel = uint64_t(y) * uint64_t(opt_.full_width) + uint64_t(x);
    for (int v = 0; v < strategies_; ++v) {
      PilotPixel& out = pixel(k, v);
      PathCounters counters;
      for (int s = 0; s < kPilotSamples; ++s) {
        // The same numbers for every strategy: their differences are measured, not the draws'.
        Sampler sampler(SamplerKind::Independent, pilot_seed_, image_pixel, uint32_t(s));
        const Vec2 offset = filter_.sample(sampler.get2d());
        const Vec2 film_pos{float(x) + 0.5f + offset.x, float(y) + 0.5f + offset.y};
        const Ray ray = sc_.camera.generate_ray(film_pos, sampler.get2d());
        SubsurfaceEntryRecord record;
        PathStart start;
        start.subsurface_strategies = &every_material_[std::size_t(v)];
        start.subsurface_record = &record;
        const RGB L = trace_path(sc_, ray, sc_.camera_medium, sampler, counters, start);
        out.finite = out.finite && L.is_finite();
        out.material[std::size_t(s)] = record.material;
        // Less the reflection split off at the camera's first hit, which every strategy
        // shares with the same numbers: a small light's highlight at a pixel's edge, seen by
        // one of its two samples, made the pixel's variance far larger than anything the
        // strategies change, the ratio of their variances near 1, and the strategy with the
        // fewest rays the choice (docs/rendering.md, "The subsurface pilot").
        out.radiance[std::size_t(s)] = L - record.camera_reflection;
      }
      out.rays = counters.rays;
    }
  }

  void render_stage(int stage) {
    tbb::parallel_for(int64_t(0), (count_ - stage + 1) / 2, [&](int64_t i) {
      if (opt_.cancel && opt_.cancel->load(std::memory_order_relaxed)) return;
      render_pixel(2 * i + stage);
    });
  }

  // A pilot pixel's variance of one sample (R + G + B) for strategy v and material m;
  // negative: the pixel does not measure the material.
  double pixel_variance(int64_t k, int v, std::size_t m) const {
    const PilotPixel& p = pixel(k, v);
    if (!p.finite || p.material[0] != int(m) || p.material[1] != int(m)) return -1.0;
    double variance = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = double(p.radiance[0][c]) - double(p.radiance[1][c]);
      variance += d * d / 2;  // the sample variance of two values
    }
    return variance;
  }

  // The places in `offered` of the strategies that differ for material m (the default's
  // first); empty: none to choose.
  std::vector<int> strategies_of(std::size_t m) const {
    std::vector<int> places;
    if (sc_.subsurface[m]->strategy_count() < 2) return places;
    for (int i = 0; i < strategies_; ++i)
      if (strategy_differs(sc_, *sc_.subsurface[m], offered_[std::size_t(i)])) places.push_back(i);
    return places;
  }

  // What material m's strategies measured on the pilot pixels k with k % step == 0 (in
  // the order of strategies_of(m)).
  std::vector<StrategyMeasure> measure(std::size_t m, int64_t step) const {
    const std::vector<int> places = strategies_of(m);
    std::vector<StrategyMeasure> e(places.size());
    for (int i = 0; i < int(e.size()); ++i) {
      const int v = places[std::size_t(i)];
      StrategyMeasure& s = e[std::size_t(i)];
      double sum_rays = 0, sum = 0;
      // Paired with the default: sums of a, b, a^2, b^2, ab over the pixels both measured.
      double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (int64_t k = 0; k < count_; k += step) {
        const double a = pixel_variance(k, v, m);
        if (a < 0) continue;
        ++s.pixels;
        sum += a;
        sum_rays += double(pixel(k, v).rays) / kPilotSamples;
        const double b = pixel_variance(k, 0, m);
        if (b < 0) continue;
        n += 1, sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
      }
      if (s.pixels == 0) continue;
      s.handicap = pilot_handicap(sc_.subsurface[m]->params, offered_[std::size_t(v)]);
      s.variance = sum / double(s.pixels);
      s.rays = sum_rays / double(s.pixels);
      if (i > 0 && n > 1 && sa > 0 && sb > 0) {
        // Delta method: var log(A/B) = (var a / A^2 + var b / B^2 - 2 cov(a, b) / (A B)) / n.
        const double A = sa / n, B = sb / n;
        const double var_a = saa / n - A * A, var_b = sbb / n - B * B, cov = sab / n - A * B;
        s.log_ratio_se = std::sqrt(std::max(0.0, var_a / (A * A) + var_b / (B * B) - 2 * cov / (A * B)) / n);
      } else if (i > 0) {
        s.log_ratio_se = std::numeric_limits<double>::infinity();  // not comparable: keep the default
      }
    }
    return e;
  }

  // Each material's choice, from the pixels of the stages rendered.
  std::vector<SubsurfaceChoice> choose(bool settled) const {
    const int64_t step = settled ? 2 : 1;
    std::vector<SubsurfaceChoice> choices;
    for (std::size_t m = 0; m < sc_.subsurface.size(); ++m) {
      const std::vector<int> places = strategies_of(m);
      if (places.empty()) continue;
      const std::vector<StrategyMeasure> e = measure(m, step);
      if (e[0].pixels < kMinPilotPixels) continue;
      SubsurfaceChoice choice;
      choice.material = int(m);
      const int best = settled ? 0 : best_strategy(e, kMinPilotPixels, kPilotSignificance);
      choice.strategy = offered_[std::size_t(places[std::size_t(best)])];
      const StrategyMeasure& chosen = e[std::size_t(best)];
      choice.pixels = int(chosen.pixels);
      choice.gain = chosen.variance_cost() > 0 ? e[0].variance_cost() / chosen.variance_cost() : 1;
      choice.gain_se = choice.gain * chosen.log_ratio_se;
      choice.first_stage_only = settled;
      choice.description = describe_subsurface_choice(sc_, choice);
      choices.push_back(choice);
    }
    return choices;
  }

  const RenderScene& sc_;
  const SubsurfacePilotOptions& opt_;
  const std::vector<int> offered_;  // the strategies measured, indexed by their place here
  const int strategies_;
  const std::vector<int64_t> candidates_;
  FilterSampler filter_;
  const uint64_t pilot_seed_;
  int64_t count_ = 0;                             // pilot pixels
  std::vector<PilotPixel> pixels_;                // per pilot pixel, per strategy
  std::vector<std::vector<int>> every_material_;  // strategy offered[i] for every material
};

}  // namespace

std::vector<SubsurfaceChoice> run_subsurface_pilot(const RenderScene& sc, const SubsurfacePilotOptions& opt) {
  int most = 1;
  for (const auto& m : sc.subsurface)
    if (m) most = std::max(most, m->strategy_count());
  int64_t probes = 0;
  std::vector<int64_t> candidates = pixels_seeing_subsurface(sc, opt.bounds, probes);
  if (candidates.empty()) return {};
  // The pilot's pixels: evenly spaced among those.
  const int64_t rendered = int64_t(opt.bounds.width()) * opt.bounds.height();
  const double object_pixels = double(candidates.size()) * double(rendered) / double(probes);
  return SubsurfacePilot(sc, opt, offered_strategies(sc, most), std::move(candidates), object_pixels).run();
}

std::vector<int> subsurface_strategies(const RenderScene& sc, const std::vector<SubsurfaceChoice>& choices) {
  std::vector<int> strategies(sc.subsurface.size(), 0);
  for (const SubsurfaceChoice& c : choices) strategies[std::size_t(c.material)] = c.strategy;
  return strategies;
}

namespace {
// A gain whose standard error exceeds this share of it is described as rough.
constexpr double kRoughGainShare = 0.5;
}  // namespace

namespace {
// What the choice's strategy is, for a probe material: "probe axes N 0.95, T 0.025, B 0.025".
std::string describe_probe_strategy(const ProbeMethod& probe, int strategy) {
  const sss::ProbeAxisProbabilities a = probe.axes(strategy);
  return fmt::format("probe axes N {:g}, T {:g}, B {:g}", a.normal, a.tangent, a.bitangent);
}

// The sentence about the choice's gain (or the default's standing), after what it is.
std::string describe_gain(const SubsurfaceChoice& c, const std::string& method, const std::string& what,
                          double handicap, const char* handicap_reason = "its heavier-tailed weights") {
  if (c.strategy == 0 && c.first_stage_only)
    return fmt::format(
        "material {} ({}): {} (the default: no other strategy can be {:.0f} % faster, measured on "
        "{} pilot pixels, the first of two stages)",
        c.material, method, what, (kPilotWorthwhileGain - 1) * 100, c.pixels);
  if (c.strategy == 0)
    return fmt::format(
        "material {} ({}): {} (the default: no other strategy is significantly faster on {} pilot "
        "pixels)",
        c.material, method, what, c.pixels);
  // A standard error above half the gain: the default's pilot samples held a few very
  // large values (a heavy-tailed estimator); the choice stands (its gain is significant),
  // the figure is rough.
  const bool rough = c.gain_se > kRoughGainShare * c.gain;
  const std::string handicapped =
      handicap > 1 ? fmt::format(", divided by {:g} for {}", handicap, handicap_reason) : "";
  return fmt::format(
      "material {} ({}): {}; {:.2f}x the default's efficiency (+- {:.2f}, estimated on {} pilot pixels{}{})",
      c.material, method, what, c.gain, c.gain_se, c.pixels, handicapped,
      rough ? "; a rough figure: the default's samples there are heavy-tailed" : "");
}
}  // namespace

std::string describe_subsurface_choice(const RenderScene& sc, const SubsurfaceChoice& c) {
  const SubsurfaceMaterial& m = *sc.subsurface[std::size_t(c.material)];
  if (const auto* probe = std::get_if<ProbeMethod>(&m.method))
    return describe_gain(c, to_string(m.params.method), describe_probe_strategy(*probe, c.strategy),
                         pilot_handicap(m.params, c.strategy));
  const WalkStrategy& w = kWalkStrategies[std::size_t(c.strategy)];
  const SubsurfaceParams& p = m.params;
  const bool share_given = p.guided_share_pinned();
  // The step's shares per channel (short_walk_guided_shares may raise some).
  std::string share = fmt::format("{:g}{}", share_given ? p.guided_share : w.p_guided, share_given ? " (given)" : "");
  const auto* walk = std::get_if<WalkMethod>(&m.method);
  if (walk) {
    const sss::MixtureWalkStep<3>& step = walk->step(c.strategy);
    const bool alike = step.p_guided(0) == step.p_guided(1) && step.p_guided(1) == step.p_guided(2);
    if (alike && step.p_guided(0) != w.p_guided)
      share = fmt::format("{:g} (not {:g}: the walks are short against the object)", step.p_guided(0), w.p_guided);
    else if (!alike)
      share = fmt::format("{:g}, {:g}, {:g} (R, G, B)", step.p_guided(0), step.p_guided(1), step.p_guided(2));
  }
  const bool walk_guides_backward = walk && walk->backward_guiding(c.strategy);
  const std::string what =
      fmt::format("guided share {}, {}{}{}", share,
                  m.channel_per_walk(c.strategy)
                      ? fmt::format("one colour channel per walk at the camera's first entry{}",
                                    p.channel_per_walk_given ? " (given)" : "")
                      : fmt::format("channel preference {:g}{}",
                                    p.channel_preference_given ? p.channel_preference : w.channel_preference,
                                    p.channel_preference_given ? " (given)" : ""),
                  w.exit_sky_sampled ? "" : ", uniform skies not light-sampled at exits",
                  walk_guides_backward
                      ? fmt::format(", guided toward the far side too{}", p.backward_guiding_given ? " (given)" : "")
                      : "");
  return describe_gain(
      c, to_string(m.params.method), what, pilot_handicap(p, c.strategy),
      backward_by_choice(p, c.strategy) ? "what its far-side terms cost per ray" : "its heavier-tailed weights");
}

}  // namespace dermis
