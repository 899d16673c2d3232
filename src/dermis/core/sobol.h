// The Sobol' sequence in base 2 and hash-based Owen scrambling.
//
// Sobol' 1967: point i in dimension j is the XOR of the direction numbers v_{j,k} for the
// set bits k of i. The first four dimensions use the primitive polynomials and initial
// numbers of Joe & Kuo 2008 (new-joe-kuo-6.21201: dimension 0 is van der Corput).
// Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): nested uniform
// scrambling by a Laine–Karras style hash on the bit-reversed value, used both on the
// point (Owen 1995 scrambling: randomises, keeps every (t,m,s)-net a net) and on the index
// (shuffling: the first 2^m shuffled indices are an aligned block of 2^m Sobol' points).
#pragma once

#include <array>
#include <cstdint>

namespace dermis {

inline constexpr int kSobolDimensions = 4;

namespace sobol_detail {

struct Polynomial {
  int degree;       // s
  uint32_t coeffs;  // a: the inner coefficients a_1 .. a_{s-1}, a_1 the highest bit
  uint32_t m[3];    // initial odd m_1 .. m_s
};

// Bratley & Fox 1988, eq. for m_k: m_k = 2 a_1 m_{k-1} ^ 4 a_2 m_{k-2} ^ ... ^ 2^s m_{k-s} ^ m_{k-s};
// v_k = m_k / 2^k as a 32-bit fixed-point fraction.
constexpr std::array<uint32_t, 32> direction_numbers(Polynomial p) {
  std::array<uint32_t, 32> m{};
  for (int k = 0; k < p.degree; ++k) m[k] = p.m[k];
  for (int k = p.degree; k < 32; ++k) {
    uint32_t v = m[k - p.degree] ^ (m[k - p.degree] << p.degree);
    for (int i = 1; i < p.degree; ++i)
      if ((p.coeffs >> (p.degree - 1 - i)) & 1u) v ^= m[k - i] << i;
    m[k] = v;
  }
  std::array<uint32_t, 32> v{};
  for (int k = 0; k < 32; ++k) v[k] = m[k] << (31 - k);
  return v;
}

constexpr std::array<std::array<uint32_t, 32>, kSobolDimensions> make_matrices() {
  std::array<std::array<uint32_t, 32>, kSobolDimensions> d{};
  for (int k = 0; k < 32; ++k) d[0][k] = 1u << (31 - k);  // van der Corput
  d[1] = direction_numbers({1, 0u, {1, 0, 0}});           // x + 1
  d[2] = direction_numbers({2, 1u, {1, 3, 0}});           // x^2 + x + 1
  d[3] = direction_numbers({3, 1u, {1, 3, 1}});           // x^3 + x + 1
  return d;
}

inline constexpr auto kMatrices = make_matrices();

// The XOR of the direction numbers selected by each byte of the index, per byte position:
// a point is four table look-ups instead of a loop over 32 bits.
using DimensionByteTables = std::array<std::array<uint32_t, 256>, 4>;  // [byte position][byte value]
using ByteTables = std::array<DimensionByteTables, kSobolDimensions>;

// The XOR of one dimension's table entries for the four bytes of the index.
constexpr uint32_t xor_of_bytes(const DimensionByteTables& t, uint32_t index) {
  return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^ t[3][index >> 24];
}

constexpr ByteTables make_byte_tables() {
  ByteTables t{};
  for (int d = 0; d < kSobolDimensions; ++d)
    for (int byte = 0; byte < 4; ++byte)
      for (uint32_t v = 0; v < 256; ++v) {
        uint32_t x = 0;
        for (int k = 0; k < 8; ++k)
          if ((v >> k) & 1u) x ^= kMatrices[d][8 * byte + k];
        t[d][byte][v] = x;
      }
  return t;
}

inline constexpr auto kByteTables = make_byte_tables();

}  // namespace sobol_detail

// Point `index` of the unscrambled Sobol' sequence in dimension `dim` (< kSobolDimensions),
// as a 32-bit fraction of one.
constexpr uint32_t sobol_sample(uint32_t index, int dim) {
  return sobol_detail::xor_of_bytes(sobol_detail::kByteTables[dim], index);
}

// The same point by the definition (a loop over the index's bits), for tests.
constexpr uint32_t sobol_sample_reference(uint32_t index, int dim) {
  uint32_t x = 0;
  for (int k = 0; index; index >>= 1, ++k)
    if (index & 1u) x ^= sobol_detail::kMatrices[dim][k];
  return x;
}

constexpr uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

namespace sobol_detail {
constexpr ByteTables make_reversed_byte_tables() {
  ByteTables t = kByteTables;
  for (auto& dimension : t)
    for (auto& byte : dimension)
      for (uint32_t& x : byte) x = reverse_bits(x);
  return t;
}
inline constexpr auto kReversedByteTables = make_reversed_byte_tables();
}  // namespace sobol_detail

// reverse_bits(sobol_sample(index, dim)) from byte tables of reversed direction numbers
// (bit reversal is linear over XOR): the input of a nested uniform scramble, without
// reversing the point first.
constexpr uint32_t sobol_sample_reversed(uint32_t index, int dim) {
  return sobol_detail::xor_of_bytes(sobol_detail::kReversedByteTables[dim], index);
}

// Burley 2020, listing 3: a hash in which each bit depends only on the bits below it
// (Laine & Karras 2011), so on reversed bits it is a nested uniform (Owen) scramble.
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

// Burley 2020, listing 4: each bit flipped by a random function of the bits above it.
constexpr uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// Integer hash of two words (the 32-bit finaliser of Murmur3, Appleby 2011, over a combine).
constexpr uint32_t hash_combine(uint32_t seed, uint32_t v) {
  uint32_t h = seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2));
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

// A fraction of one as a float in [0, 1) (the 24 high bits) and a double in (0, 1)
// (centred in its 2^-32 cell, so that -log(1 - u) and -log(u) stay finite).
constexpr float fraction_to_float(uint32_t x) { return float(x >> 8) * 0x1p-24f; }
constexpr double fraction_to_double(uint32_t x) { return (double(x) + 0.5) * 0x1p-32; }

}  // namespace dermis
