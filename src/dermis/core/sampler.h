// The random numbers of one pixel sample, by dimension.
//
// `Sobol`: Owen-scrambled Sobol' points padded dimension by dimension (Burley 2020,
// "Practical Hash-based Owen Scrambling", sec. 5): dimension d of sample i is point
// shuffle_d(i) of the scrambled sequence, with the shuffle and the scramble seeded by
// (pixel seed, d). Each 1D dimension and each 2D pair taken by `get2d` is a (0,2)-sequence
// in the sample index of its own pixel; different dimensions, and different pixels, are
// decorrelated by their seeds. Dimensions are 64-bit keys, so a caller lays out regions
// (camera, path vertices, subsurface walks) without a fixed table (`region`).
// `Independent`: PCG32 numbers of the stream (seed, pixel, sample); dimensions ignored.
//
// Both give the same image for the same seed whatever the thread count: a pixel sample's
// numbers depend on (seed, pixel, sample index, dimension) only.
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>

#include "dermis/core/rng.h"
#include "dermis/core/sobol.h"
#include "dermis/core/vec.h"

namespace dermis {

enum class SamplerKind : uint8_t { Sobol, Independent };

// "sobol" or "independent"; false for anything else.
inline bool parse_sampler_kind(std::string_view name, SamplerKind& kind) {
  if (name == "sobol") return kind = SamplerKind::Sobol, true;
  if (name == "independent") return kind = SamplerKind::Independent, true;
  return false;
}
inline const char* sampler_kind_name(SamplerKind kind) { return kind == SamplerKind::Sobol ? "sobol" : "independent"; }

class Sampler {
 public:
  Sampler(SamplerKind kind, uint64_t seed, uint64_t pixel, uint32_t sample_index)
      : Sampler(kind, seed, pixel, sample_index, pixel_key(seed, pixel)) {}
  // The same, with pixel_key(seed, pixel) made once for all of a pixel's samples.
  Sampler(SamplerKind kind, uint64_t seed, uint64_t pixel, uint32_t sample_index, uint64_t key)
      : kind_(kind),
        seed_(seed),
        pixel_(pixel),
        pixel_key_(key),
        pixel_seed_(uint32_t(pixel_key_)),
        index_(sample_index),
        reversed_index_(reverse_bits(sample_index)) {}
  static uint64_t pixel_key(uint64_t seed, uint64_t pixel) { return mix64(seed ^ mix64(pixel + 0x5ab1e5eedull)); }

  SamplerKind kind() const { return kind_; }
  // The k-th of `count` draws that one pixel sample makes from the same dimensions (the
  // exits of a subsurface entry): Sobol' index count x i + k instead of i, so that the
  // count x N draws of a pixel's N samples are one stratified sequence (a (0,2)-sequence
  // in each pair of dimensions) rather than `count` independent ones. set_split(0, 1)
  // ends it. Callers give every split its own dimensions per `count` (two splits of
  // different counts in the same dimensions would share indices). The sample's PCG32
  // stream and sample_hash keep the sample's own index; the independent sampler ignores it.
  void set_split(uint32_t k, uint32_t count) {
    const bool fits = count >= 1 && k < count && index_ <= (~uint32_t(0) - k) / count;
    reversed_index_ = reverse_bits(fits ? index_ * count + k : index_);
  }
  // The next number is taken from dimension d (and d + 1 for get2d), and so on.
  void set_dimension(uint64_t d) {
    dim_ = d;
    stratified_end_ = ~uint64_t(0);
  }
  // From dimension d, only the first `stratified` numbers are low-discrepancy; the rest
  // (the deep steps of a random walk, where stratification no longer pays for the
  // hashing) continue the sample's own PCG32 stream, which never repeats a number.
  void set_dimension(uint64_t d, uint32_t stratified) {
    dim_ = d;
    stratified_end_ = d + stratified;
  }
  uint64_t dimension() const { return dim_; }
  // Where the sampler stands (its dimension and the end of its stratified run): a nested
  // estimate draws from a region of its own and the caller comes back with `restore`.
  struct Position {
    uint64_t dimension, stratified_end;
  };
  Position position() const { return {dim_, stratified_end_}; }
  void restore(Position p) {
    dim_ = p.dimension;
    stratified_end_ = p.stratified_end;
  }
  // The first dimension of a region of 2^32 dimensions named by (parent dimension, tag):
  // a hash, so that nested regions (a walk inside a path inside another path) never
  // share a dimension, short of a 64-bit collision.
  static uint64_t region(uint64_t parent, uint32_t tag) {
    return mix64(parent ^ mix64(uint64_t(tag) + 0x7e610000ull)) & ~uint64_t(0xffffffffu);
  }

  // A 64-bit hash of (seed, pixel, sample index, key) that takes no dimension: the seed of
  // a stochastic query whose own random stream is not worth stratifying (the walks of
  // a layered BSDF, the choice of a mix material; key: the path vertex's block).
  uint64_t sample_hash(uint64_t key) const { return mix64(mix64(pixel_seed_ ^ (uint64_t(index_) << 32)) ^ key); }

  // The next dimension as a 32-bit fraction of one.
  uint32_t next_fraction() {
    if (kind_ == SamplerKind::Independent || dim_ >= stratified_end_) return stream().next_u32();
    const uint32_t seed = dimension_seed(dim_++);
    const uint32_t i = shuffled_index(seed);
    // Dimension 0 of Sobol' is the bit reversal of the index; reverse(scramble(reverse(x)))
    // composed with it is one Laine–Karras pass (Burley 2020, listing 5).
    return reverse_bits(laine_karras_permutation(i, hash_combine(seed, 0x0b1c0u)));
  }
  float get1d() { return fraction_to_float(next_fraction()); }
  // Two dimensions jointly stratified (Sobol' dimensions 0 and 1 of one shuffled index).
  Vec2 get2d() {
    if (kind_ == SamplerKind::Independent || dim_ + 1 >= stratified_end_) return {get1d(), get1d()};
    const auto [x, y] = next_pair();
    return {fraction_to_float(x), fraction_to_float(y)};
  }

  // The same in double precision (32-bit fractions): for a number that is cut into a
  // discrete choice and what is left of it (DiskProbeSampler::sample).
  Vec2d get2d_double() {
    if (kind_ == SamplerKind::Independent || dim_ + 1 >= stratified_end_) {
      const double x = uniform_double();
      return {x, uniform_double()};
    }
    const auto [x, y] = next_pair();
    return {fraction_to_double(x), fraction_to_double(y)};
  }

  // The interface of Rng, so that code written for a random stream (the sss library)
  // takes a Sampler too: each call is the next dimension.
  float uniform() { return get1d(); }
  double uniform_double() {
    return kind_ == SamplerKind::Independent || dim_ >= stratified_end_ ? stream().uniform_double()
                                                                        : fraction_to_double(next_fraction());
  }

 private:
  // The sample's PCG32 stream, seeded on first use: a camera sample that meets only the
  // sky never draws from it.
  Rng& stream() {
    if (!stream_seeded_) rng_ = Rng(seed_, pixel_, index_), stream_seeded_ = true;
    return rng_;
  }
  // Sobol' dimensions 0 and 1 of one shuffled index, scrambled: the next two dimensions
  // as a pair of 32-bit fractions.
  std::pair<uint32_t, uint32_t> next_pair() {
    const uint32_t seed = dimension_seed(dim_);
    dim_ += 2;
    const uint32_t i = shuffled_index(seed);
    const uint32_t x = reverse_bits(laine_karras_permutation(i, hash_combine(seed, 0x0b1c0u)));
    // nested_uniform_scramble(sobol_sample(i, 1), ...), the point's reversal from a table.
    const uint32_t y =
        reverse_bits(laine_karras_permutation(sobol_sample_reversed(i, 1), hash_combine(seed, 0x0b1c1u)));
    return {x, y};
  }
  // nested_uniform_scramble(index_, seed), the index's reversal kept from the constructor
  // (or the split's, set_split).
  uint32_t shuffled_index(uint32_t seed) const { return reverse_bits(laine_karras_permutation(reversed_index_, seed)); }
  // The seed of dimension d in this pixel: one multiply-xorshift-multiply round of
  // (pixel key ^ d), its high half. Distinct dimensions of a pixel give distinct 64-bit
  // values (each step is a bijection); two dependent multiplications instead of the four
  // of two chained hash_combines, since every number drawn waits for this seed.
  uint32_t dimension_seed(uint64_t d) const {
    uint64_t z = (pixel_key_ ^ d) * 0x9e3779b97f4a7c15ull;
    z ^= z >> 32;
    z *= 0xd6e8feb86659fd93ull;
    return uint32_t(z >> 32);
  }

  SamplerKind kind_;
  bool stream_seeded_ = false;
  Rng rng_;
  uint64_t seed_, pixel_;
  uint64_t pixel_key_;
  uint32_t pixel_seed_;
  uint32_t index_;
  uint32_t reversed_index_;
  uint64_t dim_ = 0;
  uint64_t stratified_end_ = ~uint64_t(0);
};

}  // namespace dermis
