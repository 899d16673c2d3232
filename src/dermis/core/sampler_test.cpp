// Tests of the Sobol' sequence, its Owen scrambling and the pixel sampler: net
// properties (exact, they cannot hold by chance), uniformity and independence of
// dimensions across pixels (chi-square), the variance of an integral (Owen-scrambled
// Sobol' against independent samples), determinism.
#include "dermis/core/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/chi_square.h"

namespace dermis {
namespace {

using testing::chi_square;
using testing::kChiSquareAlpha;

// True when the 2^m points, as 32-bit fractions, put exactly one point in every
// elementary interval [a 2^-k, (a+1) 2^-k) x [b 2^-(m-k), (b+1) 2^-(m-k)) for k = 0..m:
// a (0,m,2)-net in base 2.
bool is_02_net(const std::vector<uint32_t>& x, const std::vector<uint32_t>& y, int m) {
  for (int k = 0; k <= m; ++k) {
    std::vector<int> count(std::size_t(1) << m, 0);
    for (std::size_t i = 0; i < x.size(); ++i) {
      const uint32_t a = k == 0 ? 0 : x[i] >> (32 - k), b = m - k == 0 ? 0 : y[i] >> (32 - (m - k));
      if (++count[(a << (m - k)) | b] > 1) return false;
    }
  }
  return true;
}

// Exactly one of the 2^m values in each interval [j 2^-m, (j+1) 2^-m).
bool is_stratified(const std::vector<uint32_t>& x, int m) {
  std::vector<int> count(std::size_t(1) << m, 0);
  for (uint32_t v : x)
    if (++count[m == 0 ? 0 : v >> (32 - m)] > 1) return false;
  return true;
}

TEST(Sobol, FirstDimensionIsTheVanDerCorputSequence) {
  EXPECT_EQ(sobol_sample(0, 0), 0u);
  EXPECT_EQ(sobol_sample(1, 0), 0x80000000u);
  EXPECT_EQ(sobol_sample(2, 0), 0x40000000u);
  EXPECT_EQ(sobol_sample(3, 0), 0xc0000000u);
  for (uint32_t i = 0; i < 1000; ++i) EXPECT_EQ(sobol_sample(i, 0), reverse_bits(i));
}

// Joe & Kuo's dimension 2 (polynomial x + 1, m = 1, 3, 5, 15, ...): direction numbers
// 1/2, 3/4, 5/8, so points 1..4 (in index order, not Gray-code order) are 1/2, 3/4,
// 1/2 xor 3/4 = 1/4, and 5/8.
TEST(Sobol, SecondDimensionMatchesThePublishedSequence) {
  EXPECT_EQ(sobol_sample(1, 1), 0x80000000u);
  EXPECT_EQ(sobol_sample(2, 1), 0xc0000000u);
  EXPECT_EQ(sobol_sample(3, 1), 0x40000000u);
  EXPECT_EQ(sobol_sample(4, 1), 0xa0000000u);
  EXPECT_EQ(sobol_sample(8, 1), 15u << 28);  // m_4 / 16
}

TEST(Sobol, TableLookUpEqualsTheDefinition) {
  Rng rng(1, 2);
  for (int k = 0; k < 20000; ++k) {
    const uint32_t i = rng.next_u32();
    for (int d = 0; d < kSobolDimensions; ++d) {
      ASSERT_EQ(sobol_sample(i, d), sobol_sample_reference(i, d)) << i << " " << d;
      ASSERT_EQ(sobol_sample_reversed(i, d), reverse_bits(sobol_sample_reference(i, d))) << i << " " << d;
    }
  }
}

TEST(Sobol, EveryDimensionIsStratifiedAndTheFirstPairIsA02Net) {
  for (int m = 0; m <= 12; ++m) {
    const uint32_t n = 1u << m;
    std::vector<std::vector<uint32_t>> d(kSobolDimensions);
    for (uint32_t i = 0; i < n; ++i)
      for (int j = 0; j < kSobolDimensions; ++j) d[j].push_back(sobol_sample(i, j));
    for (int j = 0; j < kSobolDimensions; ++j) EXPECT_TRUE(is_stratified(d[j], m)) << "dim " << j << " m " << m;
    EXPECT_TRUE(is_02_net(d[0], d[1], m)) << "m " << m;
  }
}

// Owen scrambling keeps nets nets (Owen 1995), and shuffling the index by a nested
// uniform scramble takes an aligned block of 2^m points (Burley 2020, sec. 4).
TEST(Sobol, ScrambledAndShuffledPointsStayA02Net) {
  for (uint32_t seed : {1u, 0xdeadbeefu, 12345u})
    for (int m : {4, 8, 11}) {
      std::vector<uint32_t> x, y;
      for (uint32_t i = 0; i < (1u << m); ++i) {
        const uint32_t j = nested_uniform_scramble(i, seed);
        x.push_back(nested_uniform_scramble(sobol_sample(j, 0), seed * 3 + 1));
        y.push_back(nested_uniform_scramble(sobol_sample(j, 1), seed * 7 + 5));
      }
      EXPECT_TRUE(is_02_net(x, y, m)) << "seed " << seed << " m " << m;
    }
}

TEST(Sobol, NestedUniformScrambleIsAPermutationOfEachBlock) {
  // 2^12 consecutive values map onto 2^12 distinct values of one aligned block.
  const uint32_t seed = 0x1234567u;
  std::vector<int> seen(1 << 12, 0);
  const uint32_t block = nested_uniform_scramble(0, seed) >> 12;
  for (uint32_t i = 0; i < (1u << 12); ++i) {
    const uint32_t v = nested_uniform_scramble(i, seed);
    EXPECT_EQ(v >> 12, block);
    ++seen[v & 0xfff];
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

// The first 2^m samples of one pixel: every 1D dimension stratified, every get2d pair a
// (0,m,2)-net, in low dimensions and in a hashed region alike.
TEST(Sampler, SobolPixelSamplesAreStratifiedInEveryDimension) {
  const int m = 8;
  for (uint64_t pixel : {0ull, 7ull, 123456ull}) {
    for (uint64_t first : {uint64_t(0), uint64_t(37), Sampler::region(100, 0x55e1u)}) {
      std::vector<uint32_t> a, b, x, y;
      for (uint32_t i = 0; i < (1u << m); ++i) {
        Sampler s(SamplerKind::Sobol, 42, pixel, i);
        s.set_dimension(first);
        a.push_back(s.next_fraction());
        b.push_back(s.next_fraction());
        const Vec2 u = s.get2d();
        // back to 32-bit fractions (24 significant bits are enough for m = 8)
        x.push_back(uint32_t(double(u.x) * 0x1p32));
        y.push_back(uint32_t(double(u.y) * 0x1p32));
      }
      EXPECT_TRUE(is_stratified(a, m)) << pixel << " " << first;
      EXPECT_TRUE(is_stratified(b, m)) << pixel << " " << first;
      EXPECT_TRUE(is_02_net(x, y, m)) << pixel << " " << first;
    }
  }
}

// The exits of a subsurface entry draw as one sequence (Sampler::set_split): draw k of K of
// the pixel's sample i is Sobol' index K i + k, so the K 2^m draws of 2^m samples are a
// (0, m + log2 K, 2)-net, as 2^m samples would be alone; set_split(0, 1) gives the
// sample's own numbers back, and its stream and hash never change.
TEST(Sampler, SplitDrawsOfAPixelsSamplesFormOneNet) {
  const int m = 6;
  const uint64_t first = Sampler::region(100, 0x5e170002u);
  for (uint64_t pixel : {0ull, 123456ull}) {
    for (uint32_t count : {2u, 4u}) {
      std::vector<uint32_t> x, y;
      for (uint32_t i = 0; i < (1u << m); ++i) {
        Sampler s(SamplerKind::Sobol, 42, pixel, i);
        for (uint32_t k = 0; k < count; ++k) {
          s.set_dimension(first);
          s.set_split(k, count);
          const Vec2d u = s.get2d_double();  // (x + 1/2) 2^-32: back to the 32-bit fraction
          x.push_back(uint32_t(u.x * 0x1p32));
          y.push_back(uint32_t(u.y * 0x1p32));
        }
        s.set_split(0, 1);
        Sampler fresh(SamplerKind::Sobol, 42, pixel, i);
        s.set_dimension(first), fresh.set_dimension(first);
        EXPECT_EQ(s.next_fraction(), fresh.next_fraction());
        EXPECT_EQ(s.sample_hash(7), fresh.sample_hash(7));
      }
      EXPECT_TRUE(is_02_net(x, y, m + (count == 2 ? 1 : 2))) << pixel << " " << count;
    }
  }
  // Each draw alone is uniform across pixels (the scrambles' randomness): the first of two
  // falls below 1/2 in half of 40000 pixels, within 4 sigma.
  int below = 0;
  const int pixels = 40000;
  for (int p = 0; p < pixels; ++p) {
    Sampler s(SamplerKind::Sobol, 42, uint64_t(p), 3);
    s.set_dimension(first);
    s.set_split(0, 2);
    below += s.get2d_double().x < 0.5;
  }
  EXPECT_NEAR(below, pixels / 2, 4 * std::sqrt(pixels * 0.25));
  // The split leaves the sample's PCG32 stream alone.
  Sampler a(SamplerKind::Sobol, 3, 11, 5), b(SamplerKind::Sobol, 3, 11, 5);
  a.set_dimension(1000, 0), b.set_dimension(1000, 0);
  a.set_split(1, 2);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(a.next_fraction(), b.next_fraction());
}

// Across pixels, one sample's dimensions a and b are independent uniforms: a 2D
// histogram of (dim a, dim b) over 40000 pixels, chi-square against uniform.
TEST(Sampler, DimensionsAndPixelsAreDecorrelated) {
  const int bins = 16, n = 40000;
  for (auto [da, db] : {std::pair<uint64_t, uint64_t>{0, 1}, {0, 2}, {4, 36}, {5, 5 + (uint64_t(1) << 32)}}) {
    for (uint32_t sample : {0u, 3u}) {
      std::vector<double> obs(bins * bins, 0), expected(bins * bins, double(n) / (bins * bins));
      for (int p = 0; p < n; ++p) {
        Sampler s(SamplerKind::Sobol, 9, uint64_t(p), sample);
        s.set_dimension(da);
        const float ua = s.get1d();
        s.set_dimension(db);
        const float ub = s.get1d();
        ++obs[int(ua * bins) * bins + int(ub * bins)];
      }
      auto r = chi_square(obs, expected);
      EXPECT_GT(r.p_value, kChiSquareAlpha)
          << "dims " << da << "," << db << " sample " << sample << " chi2 " << r.statistic << " dof " << r.dof;
    }
  }
}

// The mean over 64 pixels (independent randomisations) of a 256-sample estimate of a
// smooth 2D integral: unbiased (within 4 standard errors of the replicate mean) and
// with far less variance than independent samples (Owen-scrambled nets: O(n^-3) against
// O(n^-1); at n = 256 the ratio is about 1e-3, the test asks for 1/20).
TEST(Sampler, SobolIntegratesASmoothFunctionWithFarLessVariance) {
  auto f = [](Vec2 u) { return double(u.x) * u.y + std::sin(3.0 * u.x) * u.y * u.y; };
  const double exact = 0.25 + (1 - std::cos(3.0)) / 9.0;  // int x y + (1/3) int sin(3x)
  const int n = 256, replicates = 64;
  auto replicate_stats = [&](SamplerKind kind, uint64_t dim) {
    double s = 0, s2 = 0;
    for (int r = 0; r < replicates; ++r) {
      double est = 0;
      for (int i = 0; i < n; ++i) {
        Sampler sm(kind, 5, uint64_t(r), uint32_t(i));
        sm.set_dimension(dim);
        est += f(sm.get2d());
      }
      est /= n;
      s += est;
      s2 += est * est;
    }
    const double mean = s / replicates, var = (s2 / replicates - mean * mean) * replicates / (replicates - 1);
    return std::pair{mean, var};
  };
  for (uint64_t dim : {uint64_t(0), uint64_t(38), Sampler::region(4, 1)}) {
    auto [m_sobol, v_sobol] = replicate_stats(SamplerKind::Sobol, dim);
    auto [m_indep, v_indep] = replicate_stats(SamplerKind::Independent, dim);
    EXPECT_NEAR(m_sobol, exact, 4 * std::sqrt(v_sobol / replicates) + 1e-7) << "dim " << dim;
    EXPECT_NEAR(m_indep, exact, 4 * std::sqrt(v_indep / replicates)) << "dim " << dim;
    EXPECT_LT(v_sobol, v_indep / 20) << "dim " << dim;
  }
}

TEST(Sampler, SameArgumentsSameNumbersAndIndependentIsTheRngStream) {
  Sampler a(SamplerKind::Sobol, 3, 11, 5), b(SamplerKind::Sobol, 3, 11, 5);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_fraction(), b.next_fraction());
  Sampler other_seed(SamplerKind::Sobol, 4, 11, 5);
  Sampler c(SamplerKind::Sobol, 3, 11, 5);
  int same = 0;
  for (int i = 0; i < 100; ++i) same += c.next_fraction() == other_seed.next_fraction();
  EXPECT_LT(same, 3);

  Sampler ind(SamplerKind::Independent, 3, 11, 5);
  Rng rng(3, 11, 5);
  ind.set_dimension(1000);  // ignored by independent sampling
  for (int i = 0; i < 100; ++i) EXPECT_EQ(ind.get1d(), rng.uniform());
}

// After `stratified` numbers a region continues the sample's PCG32 stream: the numbers
// before the limit are the low-discrepancy ones, those after are the stream's.
TEST(Sampler, StratifiedCountHandsOverToTheStream) {
  Sampler a(SamplerKind::Sobol, 3, 11, 5), b(SamplerKind::Sobol, 3, 11, 5);
  Rng stream(3, 11, 5);
  a.set_dimension(1000, 3);
  b.set_dimension(1000);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(a.next_fraction(), b.next_fraction());
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a.next_fraction(), stream.next_u32());
  a.set_dimension(1000);  // a new region is stratified again
  Sampler c(SamplerKind::Sobol, 3, 11, 5);
  c.set_dimension(1000);
  EXPECT_EQ(a.next_fraction(), c.next_fraction());
}

TEST(Sampler, UniformValuesStayInsideTheUnitInterval) {
  for (uint32_t x : {0u, 1u, 0xffffff00u, 0xffffffffu}) {
    EXPECT_GE(fraction_to_float(x), 0.0f);
    EXPECT_LT(fraction_to_float(x), 1.0f);
    EXPECT_GT(fraction_to_double(x), 0.0);
    EXPECT_LT(fraction_to_double(x), 1.0);
  }
}

TEST(Sampler, KindsParseByName) {
  SamplerKind k = SamplerKind::Independent;
  EXPECT_TRUE(parse_sampler_kind("sobol", k));
  EXPECT_EQ(k, SamplerKind::Sobol);
  EXPECT_TRUE(parse_sampler_kind("independent", k));
  EXPECT_EQ(k, SamplerKind::Independent);
  EXPECT_FALSE(parse_sampler_kind("halton", k));
  EXPECT_STREQ(sampler_kind_name(SamplerKind::Sobol), "sobol");
}

}  // namespace
}  // namespace dermis
