#include "dermis/sss/walk/random_walk.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dermis/sss/halfspace/chandrasekhar.h"
#include "dermis/sss/walk/analytic_boundaries.h"

namespace dermis::sss {
namespace {

struct ChannelStats {
  double sum[3] = {0, 0, 0}, sum_sq[3] = {0, 0, 0};
  int n = 0, truncated = 0, exits = 0;
  double mean(int c) const { return sum[c] / n; }
  double stderr_(int c) const { return std::sqrt(std::max(0.0, sum_sq[c] / n - mean(c) * mean(c)) / (n - 1)); }
};

template <class Tracer>
ChannelStats run_walks(const MixtureWalkStep<3>& step, const WalkSettings& settings, Vec3 p, Vec3 n, Vec3 dir,
                       int paths, uint64_t seed, const Tracer& tracer) {
  ChannelStats s;
  Rng rng(seed, uint64_t(settings.sampling));
  WalkResult out;
  for (int i = 0; i < paths; ++i) {
    const bool left = random_walk(step, settings, p, n, dir, rng, tracer, out);
    ++s.n;
    s.truncated += out.truncated;
    if (!left) continue;
    ++s.exits;
    for (int c = 0; c < 3; ++c) s.sum[c] += out.weight[c], s.sum_sq[c] += double(out.weight[c]) * out.weight[c];
  }
  return s;
}

template <class Tracer>
ChannelStats run_walks(const WalkMedium& medium, const WalkSettings& settings, Vec3 p, Vec3 n, Vec3 dir, int paths,
                       uint64_t seed, const Tracer& tracer) {
  return run_walks(make_walk_step(medium, settings), settings, p, n, dir, paths, seed, tracer);
}

WalkSettings settings_for(WalkSampling sampling) {
  WalkSettings s;
  s.sampling = sampling;
  s.max_steps = 100000;
  return s;
}

// Index-matched isotropic half-space, normal incidence: each channel's mean weight is
// Chandrasekhar's 1 - H(1) sqrt(1 - alpha_c), with a different sigma_t and alpha per
// channel (one-sample spectral MIS), for classical, Dwivedi and MIS sampling, with the
// channel chosen by throughput alone (k = 0) and with the default preference for the
// channels of least absorption (MixtureWalkStep::channel_probabilities).
TEST(RandomWalk, HalfspaceAlbedoMatchesChandrasekharPerChannel) {
  const RGB alpha(0.5f, 0.9f, 0.99f), sigma_t(1.0f, 2.0f, 0.5f);
  const WalkMedium medium{alpha * sigma_t, sigma_t, 0.0f};
  double reference[3];
  for (int c = 0; c < 3; ++c) reference[c] = halfspace_albedo_collimated(HFunction(alpha[c]), 1.0);
  for (float preference : {0.0f, WalkSettings{}.channel_preference})
    for (WalkSampling sampling : {WalkSampling::Classical, WalkSampling::Dwivedi, WalkSampling::Mis}) {
      WalkSettings settings = settings_for(sampling);
      settings.channel_preference = preference;
      const ChannelStats s =
          run_walks(medium, settings, {0, 0, 0}, {0, 0, 1}, {0, 0, -1}, 60000, 21, HalfspaceTracer{});
      EXPECT_EQ(s.truncated, 0);
      for (int c = 0; c < 3; ++c) {
        EXPECT_LT(s.stderr_(c), 6e-3);  // the test resolves a 2.4% error at 4 sigma
        EXPECT_NEAR(s.mean(c), reference[c], 4 * s.stderr_(c))
            << walk_sampling_name(sampling) << " preference " << preference << " channel " << c << " stderr "
            << s.stderr_(c);
      }
    }
}

// Guided shares that differ by channel (MixtureWalkStep::with_guided_shares: the flights
// drawn in channel c guided with probability P_g,c) keep every channel unbiased: the
// half-space of the test above against Chandrasekhar, within 4 sigma.
TEST(RandomWalk, GuidedSharesPerChannelKeepTheHalfspaceAlbedo) {
  const RGB alpha(0.5f, 0.9f, 0.99f), sigma_t(1.0f, 2.0f, 0.5f);
  const WalkMedium medium{alpha * sigma_t, sigma_t, 0.0f};
  const WalkSettings settings = settings_for(WalkSampling::Mis);
  const MixtureWalkStep<3> step = make_walk_step(medium, settings).with_guided_shares({0.2, 0.95, 0.6});
  EXPECT_EQ(step.p_guided(0), 0.2);
  EXPECT_EQ(step.p_guided(1), 0.95);
  const ChannelStats s = run_walks(step, settings, {0, 0, 0}, {0, 0, 1}, {0, 0, -1}, 60000, 23, HalfspaceTracer{});
  EXPECT_EQ(s.truncated, 0);
  for (int c = 0; c < 3; ++c) {
    const double reference = halfspace_albedo_collimated(HFunction(alpha[c]), 1.0);
    EXPECT_LT(s.stderr_(c), 6e-3);
    EXPECT_NEAR(s.mean(c), reference, 4 * s.stderr_(c)) << "channel " << c;
  }
  EXPECT_THROW((void)step.with_guided_shares({0.5, 1.5, 0.5}), std::invalid_argument);
  EXPECT_THROW((void)make_walk_step(medium, settings_for(WalkSampling::Classical)).with_guided_shares({0.5, 0.5, 0.5}),
               std::invalid_argument);
}

// A grey medium is the monochromatic case: all channels carry the same weight.
TEST(RandomWalk, GreyMediumHasEqualChannels) {
  const WalkMedium medium{RGB(0.9f), RGB(1.0f), 0.0f};
  const ChannelStats s =
      run_walks(medium, settings_for(WalkSampling::Mis), {0, 0, 0}, {0, 0, 1}, {0, 0, -1}, 2000, 4, HalfspaceTracer{});
  EXPECT_EQ(s.sum[0], s.sum[1]);
  EXPECT_EQ(s.sum[0], s.sum[2]);
}

// A ball without absorption returns all light: E[weight] = 1 in every channel, while
// the guiding axis (the entry normal) is wrong for most of the curved boundary.
TEST(RandomWalk, ConservativeSphereReturnsEverything) {
  const RGB sigma_t(1.0f, 3.0f, 0.3f);
  const WalkMedium medium{sigma_t, sigma_t, 0.5f};
  const SphereTracer sphere{2.0};
  const Vec3 p(0, 0, 2), n(0, 0, 1), dir = normalize(Vec3(0.3f, 0, -1));
  for (WalkSampling sampling : {WalkSampling::Classical, WalkSampling::Dwivedi, WalkSampling::Mis}) {
    const ChannelStats s = run_walks(medium, settings_for(sampling), p, n, dir, 20000, 8, sphere);
    EXPECT_EQ(s.truncated, 0);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.mean(c), 1.0, 4 * s.stderr_(c) + 1e-6) << walk_sampling_name(sampling) << " channel " << c;
  }
}

// A pure absorber: only the uncollided light crosses, exp(-sigma_t 2r) along a diameter.
TEST(RandomWalk, AbsorbingSphereTransmitsBeerLambert) {
  const RGB sigma_t(0.5f, 1.0f, 0.2f);
  const WalkMedium medium{RGB(0.0f), sigma_t, 0.0f};
  const SphereTracer sphere{1.0};
  for (WalkSampling sampling : {WalkSampling::Classical, WalkSampling::Dwivedi, WalkSampling::Mis}) {
    const ChannelStats s =
        run_walks(medium, settings_for(sampling), {0, 0, 1}, {0, 0, 1}, {0, 0, -1}, 20000, 9, sphere);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.mean(c), std::exp(-2.0 * sigma_t[c]), 4 * s.stderr_(c)) << walk_sampling_name(sampling) << c;
  }
}

// With absorption and anisotropy on the sphere there is no closed form: the guided
// and MIS walks agree with the classical (analog) walk within 4 combined sigma.
TEST(RandomWalk, AbsorbingSphereAgreesWithClassical) {
  const RGB sigma_t(1.0f, 2.0f, 4.0f), alpha(0.95f, 0.8f, 0.99f);
  const WalkMedium medium{alpha * sigma_t, sigma_t, 0.7f};
  const SphereTracer sphere{1.5};
  const Vec3 p(0, 0, 1.5), n(0, 0, 1), dir = normalize(Vec3(0.5f, 0.2f, -1));
  const ChannelStats classical = run_walks(medium, settings_for(WalkSampling::Classical), p, n, dir, 30000, 10, sphere);
  for (WalkSampling sampling : {WalkSampling::Dwivedi, WalkSampling::Mis}) {
    const ChannelStats s = run_walks(medium, settings_for(sampling), p, n, dir, 30000, 11, sphere);
    for (int c = 0; c < 3; ++c) {
      const double sigma = std::hypot(classical.stderr_(c), s.stderr_(c));
      EXPECT_NEAR(s.mean(c), classical.mean(c), 4 * sigma) << walk_sampling_name(sampling) << " channel " << c;
    }
  }
}

// The guide finds the far side below the entry point where there is one.
TEST(RandomWalk, GuideFindsTheFarSide) {
  WalkSettings settings = settings_for(WalkSampling::Mis);
  settings.backward_guiding = true;
  const WalkGuide slab = make_walk_guide(settings, {0.5f, 0, 0}, {0, 0, 1}, SlabTracer{2.5});
  ASSERT_TRUE(slab.has_far);
  EXPECT_NEAR(slab.far_p.z, -2.5, 1e-6);
  EXPECT_NEAR(slab.far_p.x, 0.5, 1e-6);
  EXPECT_EQ(slab.far_n, Vec3d(0, 0, -1));
  EXPECT_FALSE(make_walk_guide(settings, {0, 0, 0}, {0, 0, 1}, HalfspaceTracer{}).has_far);
  const WalkGuide ball = make_walk_guide(settings, {0, 0, 2}, {0, 0, 1}, SphereTracer{2.0});
  ASSERT_TRUE(ball.has_far);
  EXPECT_NEAR(ball.far_p.z, -2.0, 1e-5);
  settings.backward_guiding = false;
  EXPECT_FALSE(make_walk_guide(settings, {0, 0, 0}, {0, 0, 1}, SlabTracer{2.5}).has_far);
  settings.backward_guiding = true;
  settings.sampling = WalkSampling::Classical;  // nothing to guide
  EXPECT_FALSE(make_walk_guide(settings, {0, 0, 0}, {0, 0, 1}, SlabTracer{2.5}).has_far);
}

// Reflectance and transmittance of a slab, each per channel: with backward guiding the
// guided and MIS walks agree with the classical (analog) walk within 4 combined sigma,
// for a slab one to a few mean free paths thick, chromatic and anisotropic, oblique entry.
TEST(RandomWalk, SlabWithBackwardGuidingAgreesWithClassical) {
  const RGB sigma_t(1.0f, 2.0f, 0.5f), alpha(0.9f, 0.99f, 0.7f);
  const SlabTracer slab{1.5};
  const Vec3 p(0, 0, 0), n(0, 0, 1), dir = normalize(Vec3(0.4f, 0, -1));
  struct SideStats {
    ChannelStats top, bottom;
  };
  auto run = [&](WalkSampling sampling, bool backward, float g, uint64_t seed) {
    WalkSettings settings = settings_for(sampling);
    settings.backward_guiding = backward;
    const MixtureWalkStep<3> step = make_walk_step({alpha * sigma_t, sigma_t, g}, settings);
    SideStats s;
    Rng rng(seed, 7);
    WalkResult out;
    for (int i = 0; i < 40000; ++i) {
      const bool left = random_walk(step, settings, p, n, dir, rng, slab, out);
      ++s.top.n, ++s.bottom.n;
      if (!left) continue;
      ChannelStats& side = out.exit_n.z > 0 ? s.top : s.bottom;
      for (int c = 0; c < 3; ++c) side.sum[c] += out.weight[c], side.sum_sq[c] += double(out.weight[c]) * out.weight[c];
    }
    return s;
  };
  for (float g : {0.0f, 0.5f}) {
    const SideStats classical = run(WalkSampling::Classical, false, g, 30);
    for (WalkSampling sampling : {WalkSampling::Dwivedi, WalkSampling::Mis}) {
      const SideStats s = run(sampling, true, g, 31);
      for (int c = 0; c < 3; ++c) {
        const double sigma_r = std::hypot(classical.top.stderr_(c), s.top.stderr_(c));
        const double sigma_t_ = std::hypot(classical.bottom.stderr_(c), s.bottom.stderr_(c));
        EXPECT_NEAR(s.top.mean(c), classical.top.mean(c), 4 * sigma_r)
            << walk_sampling_name(sampling) << " g " << g << " reflectance, channel " << c;
        EXPECT_NEAR(s.bottom.mean(c), classical.bottom.mean(c), 4 * sigma_t_)
            << walk_sampling_name(sampling) << " g " << g << " transmittance, channel " << c;
        EXPECT_GT(s.bottom.mean(c), 0.02);  // the far side matters in this slab
      }
    }
  }
}

// The step cap: every walk that needs more scattering events is reported as truncated.
TEST(RandomWalk, StepCapTruncates) {
  const WalkMedium medium{RGB(1.0f), RGB(1.0f), 0.0f};
  WalkSettings settings = settings_for(WalkSampling::Classical);
  settings.max_steps = 3;
  const MixtureWalkStep<3> step = make_walk_step(medium, settings);
  Rng rng(1, 2);
  WalkResult out;
  int truncated = 0, exits = 0;
  for (int i = 0; i < 2000; ++i) {
    const bool left = random_walk(step, settings, {0, 0, 0}, {0, 0, 1}, {0, 0, -1}, rng, HalfspaceTracer{}, out);
    EXPECT_LE(out.steps, 3);
    if (left) {
      ++exits;
      EXPECT_NEAR(out.exit_p.z, 0.0f, 1e-6f);
      EXPECT_GT(out.exit_dir_in_medium.z, 0.0f);
      EXPECT_EQ(out.exit_n, Vec3(0, 0, 1));
    }
    truncated += out.truncated;
    EXPECT_EQ(out.truncated, !left);  // no absorption, no roulette at weight 1: out or truncated
  }
  EXPECT_GT(truncated, 500);
  EXPECT_GT(exits, 500);
}

TEST(RandomWalk, RejectsBadMedia) {
  EXPECT_THROW(make_walk_step({RGB(1.0f), RGB(0.5f), 0.0f}, {}), std::invalid_argument);  // sigma_s > sigma_t
  EXPECT_THROW(make_walk_step({RGB(0.0f), RGB(0.0f), 0.0f}, {}), std::invalid_argument);  // sigma_t = 0
  EXPECT_THROW(make_walk_step({RGB(0.5f), RGB(1.0f), 1.0f}, {}), std::invalid_argument);  // g = 1
  WalkSettings bad;
  bad.p_guided = 2;
  EXPECT_THROW(make_walk_step({RGB(0.5f), RGB(1.0f), 0.0f}, bad), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
