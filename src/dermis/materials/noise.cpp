#include "dermis/materials/noise.h"

#include <cmath>
#include <cstdint>

namespace dermis {

namespace {

// The permutation of 0..255 of Perlin's reference implementation of improved noise
// (K. Perlin, "Improving Noise", SIGGRAPH 2002; mrl.nyu.edu/~perlin/noise/).
constexpr uint8_t kPermutation[256] = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

int perm(int i) { return kPermutation[i & 255]; }

// Perlin 2002, "Improving Noise" §3: the dot product of (x, y, z) with one of the 12
// vectors from the centre of a cube to its edge midpoints (4 of them repeated to make 16),
// chosen by the low 4 bits of the hash.
float gradient(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 ? x : y;
  const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// Perlin 2002, eq. in §4: the quintic 6t^5 - 15t^4 + 10t^3 (zero first and second derivatives at 0 and 1).
float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

float lerp(float t, float a, float b) { return a + t * (b - a); }

// The lattice noise of Perlin 2002 with the gradient ramp `grad` at the 8 corners.
template <class Gradient>
float lattice_noise(Vec3 p, Gradient grad) {
  // The lattice cell, reduced modulo 256 (the period) in double so that large
  // coordinates neither overflow an int nor lose the offset within the cell.
  auto split = [](float c, int& cell, float& offset) {
    const double f = std::floor(double(c));
    offset = float(double(c) - f);
    cell = int(int64_t(std::fmod(f, 256.0) + 256) & 255);
  };
  int X, Y, Z;
  float x, y, z;
  split(p.x, X, x);
  split(p.y, Y, y);
  split(p.z, Z, z);
  const float u = fade(x), v = fade(y), w = fade(z);
  // Perlin 2002 reference implementation: hash the 8 corners, interpolate their gradient ramps.
  const int A = perm(X) + Y, AA = perm(A) + Z, AB = perm(A + 1) + Z;
  const int B = perm(X + 1) + Y, BA = perm(B) + Z, BB = perm(B + 1) + Z;
  return lerp(w,
              lerp(v, lerp(u, grad(perm(AA), x, y, z), grad(perm(BA), x - 1, y, z)),
                   lerp(u, grad(perm(AB), x, y - 1, z), grad(perm(BB), x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(perm(AA + 1), x, y, z - 1), grad(perm(BA + 1), x - 1, y, z - 1)),
                   lerp(u, grad(perm(AB + 1), x, y - 1, z - 1), grad(perm(BB + 1), x - 1, y - 1, z - 1))));
}

// pbrt-v4's choice of gradient for the 16 hashes (util/noise.cpp Grad): the same twelve
// edge vectors for hashes 0-11; hashes 12-15 repeat (1, 1, 0), (-1, 1, 0), (0, -1, 1), (0, -1, -1).
float gradient_pbrt_v4(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 || h == 12 || h == 13 ? x : y;
  const float v = h < 4 || h == 12 || h == 13 ? y : z;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

}  // namespace

float perlin_noise(Vec3 p) { return lattice_noise(p, gradient); }

float perlin_noise_pbrt_v4(Vec3 p) { return lattice_noise(p, gradient_pbrt_v4); }

// Ebert et al., "Texturing and Modeling" (3rd ed.), §2.6: fBm = sum_i omega^i noise(lambda^i p);
// lambda slightly below 2 so that the octaves' lattices do not line up (pbrt-v4's 1.99).
float fbm(Vec3 p, float omega, int octaves) {
  float sum = 0, o = 1, lambda = 1;
  for (int i = 0; i < octaves; ++i) {
    sum += o * perlin_noise(p * lambda);
    lambda *= 1.99f;
    o *= omega;
  }
  return sum;
}

// Perlin 1985, "An Image Synthesizer" §5 (turbulence = sum_i |noise(2^i p)| / 2^i), with
// weights omega^i; the octaves that a filter footprint would clamp contribute their mean 0.2
// (pbrt-v4, which clamps none here but still adds the term for the first clamped octave).
float turbulence(Vec3 p, float omega, int octaves) {
  float sum = 0, o = 1, lambda = 1;
  for (int i = 0; i < octaves; ++i) {
    sum += o * std::abs(perlin_noise(p * lambda));
    lambda *= 1.99f;
    o *= omega;
  }
  return sum + 0.2f * o;
}

}  // namespace dermis
