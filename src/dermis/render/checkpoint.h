// A render's film saved to disk so that the render can be continued later
// (`dermis render --checkpoint FILE` / `--resume FILE`). The film's per-pixel sums and
// sample counts are stored exactly (doubles), so a resumed render is bit-identical to
// one never stopped (renderer.h, RenderOptions::resume).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "dermis/core/sampler.h"
#include "dermis/render/film.h"

namespace dermis {

// What a checkpoint must match to be resumed: the same scene (a hash of its file's
// bytes), seed, sampler, resolution and crop window. The number of samples may differ:
// resuming with more samples per pixel continues the same sample sequence.
struct CheckpointKey {
  uint64_t scene_hash = 0;
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::Sobol;
  int full_width = 0, full_height = 0;
  PixelBounds pixels{0, 0, 0, 0};
};

// FNV-1a (64-bit) of a byte string: the scene's fingerprint. `h`: the fingerprint of the
// bytes before these (a file hashed a chunk at a time).
inline constexpr uint64_t kFingerprintOfNothing = 14695981039346656037ull;  // FNV-1a's offset basis
uint64_t fingerprint(std::string_view bytes, uint64_t h = kFingerprintOfNothing);

// Writes the film to `path` through a temporary file renamed over it, so that an
// interrupted write never leaves a truncated checkpoint. Throws std::runtime_error
// ("PATH: could not write the checkpoint: REASON").
void write_checkpoint(const std::string& path, const CheckpointKey& key, const Film& film);

// Reads a checkpoint written for `expected`; throws std::runtime_error naming the file
// and what differs (another scene, seed, sampler or resolution) or what is wrong with it.
Film read_checkpoint(const std::string& path, const CheckpointKey& expected);

}  // namespace dermis
