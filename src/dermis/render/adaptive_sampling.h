// Adaptive sampling: after a first pass every pixel has, pixels whose estimated error is
// below a noise threshold stop taking samples (Cycles' "noise threshold"; Lee, Redner &
// Uselton 1985, "Statistically optimized sampling for distributed ray tracing": sample a
// pixel until its variance estimate is small enough). The error is the standard error of
// the pixel's mean, from its samples' variance, relative to the square root of its value
// (pixel_noise_error). A pixel goes on while any pixel of its 3x3 neighbourhood is
// above the threshold, so that one pixel whose few samples happened to agree cannot stop
// among noisy neighbours. The stopping rule depends on the samples, so it is not strictly
// unbiased (Kirk & Arvo 1991); the neighbourhood and a minimum count keep that bias below
// the noise (adaptive_sampling_test.cpp).
//
// Everything here is a function of the film alone (sums, sums of squares, counts): the
// renderer takes its decisions between passes from the film, so that a render is the same
// whatever the thread or process count, and a checkpoint holds all the state there is.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dermis/render/film.h"

namespace dermis {

struct AdaptiveSampling {
  // Relative error at which a pixel stops (Cycles' default is 0.01); 0: off, every pixel
  // takes the full count.
  double noise_threshold = 0;
  // Samples every pixel takes before any stops; 0: the default (default_min_spp).
  int min_spp = 0;

  bool enabled() const { return noise_threshold > 0; }
};

// The error's denominator is the square root of the pixel's value, at least of this.
constexpr double kErrorValueFloor = 1e-4;

// max(16, sqrt(spp)) rounded up to a multiple of 16 (the sampler's blocks), at most spp.
int default_min_spp(int spp);

// The pixel's estimated error: the standard error of its mean (the samples' variance
// over the count, averaged over R, G, B) over the square root of its value (the average of
// R, G, B, at least kErrorValueFloor), both times `output_scale` (the Film's exposure: the
// value as written). For a white pixel (value 1) this is the relative error; for darker
// ones it is the error as a display shows it (display encodings are close to a square
// root: d sqrt(v) = dv / 2 sqrt(v)), as Cycles' noise threshold measures it. A purely
// relative error lets near-black pixels lit by rare paths take the whole budget (measured
// against uniform sampling: docs/results/results-adaptive.md, "The error criterion").
// Zero for a pixel whose samples are all equal (a background); +infinity with fewer than
// 2 samples.
float pixel_noise_error(const Film& film, std::size_t pixel, double output_scale);
// The same from a pixel's sums (RGB) and sums of squares over its n samples.
float pixel_noise_error(const double* sum, const double* sum_sq, uint32_t n, double output_scale);

// The error of every pixel of the film (width x height, row-major).
void noise_error_map(const Film& film, double output_scale, std::span<float> error);

// The largest error in each pixel's 3x3 neighbourhood (clipped at the image's edges).
void neighbourhood_max(std::span<const float> error, int width, int height, std::span<float> out);

// The count a pixel that must go on reaches in its next pass: `count` plus the largest
// power of two that is at most max(16, count / 4) (blocks of the Owen-scrambled Sobol'
// sequence: a prefix made of such blocks stays well stratified), at most `spp`.
uint32_t next_adaptive_count(uint32_t count, uint32_t spp);

}  // namespace dermis
