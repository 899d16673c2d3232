#include "dermis/render/checkpoint.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace dermis {

namespace {

// File layout (native byte order): magic, version, the key, then width x height x 3
// doubles (the sums), as many (the sums of squares), width x height uint32 (the sample
// counts), as many (the pass's targets) and width x height uint64 (the rays traced).
// Version 1 had no squares, targets or rays.
constexpr char kMagic[8] = {'D', 'E', 'R', 'M', 'C', 'K', 'P', 'T'};
constexpr uint32_t kVersion = 2;

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t sampler;
  uint64_t scene_hash, seed;
  int32_t full_width, full_height, x0, y0, x1, y1;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

Header header_of(const CheckpointKey& k) {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kVersion;
  h.sampler = uint32_t(k.sampler);
  h.scene_hash = k.scene_hash;
  h.seed = k.seed;
  h.full_width = k.full_width;
  h.full_height = k.full_height;
  h.x0 = k.pixels.x0, h.y0 = k.pixels.y0, h.x1 = k.pixels.x1, h.y1 = k.pixels.y1;
  return h;
}

}  // namespace

uint64_t fingerprint(std::string_view bytes, uint64_t h) {
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;  // FNV-1a's prime (Fowler, Noll, Vo)
  return h;
}

void write_checkpoint(const std::string& path, const CheckpointKey& key, const Film& film) {
  const std::string tmp = path + ".tmp";
  auto fail = [&](const std::string& why) {
    std::remove(tmp.c_str());
    return std::runtime_error(fmt::format("{}: could not write the checkpoint: {}", path, why));
  };
  {
    File f(std::fopen(tmp.c_str(), "wb"));
    if (!f) throw fail(std::strerror(errno));
    const Header h = header_of(key);
    const bool ok =
        std::fwrite(&h, sizeof h, 1, f.get()) == 1 &&
        std::fwrite(film.sum.data(), sizeof(double), film.sum.size(), f.get()) == film.sum.size() &&
        std::fwrite(film.sum_sq.data(), sizeof(double), film.sum_sq.size(), f.get()) == film.sum_sq.size() &&
        std::fwrite(film.samples.data(), sizeof(uint32_t), film.samples.size(), f.get()) == film.samples.size() &&
        std::fwrite(film.target.data(), sizeof(uint32_t), film.target.size(), f.get()) == film.target.size() &&
        std::fwrite(film.rays.data(), sizeof(uint64_t), film.rays.size(), f.get()) == film.rays.size() &&
        std::fflush(f.get()) == 0;
    if (!ok) throw fail(std::strerror(errno));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw fail(ec.message());
}

Film read_checkpoint(const std::string& path, const CheckpointKey& expected) {
  auto fail = [&](const std::string& why) {
    return std::runtime_error(fmt::format("{}: cannot resume from this checkpoint: {}", path, why));
  };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw fail("no such file");
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw fail(std::strerror(errno));
  Header h{};
  if (std::fread(&h, sizeof h, 1, f.get()) != 1 || std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
    throw fail("it is not a Dermis checkpoint");
  if (h.version == 1)
    throw fail(
        "it was written by an older Dermis (checkpoint version 1, without the per-pixel variances that "
        "version 2 keeps); resume it with that Dermis, or render again");
  if (h.version != kVersion) throw fail(fmt::format("version {}, this Dermis reads version {}", h.version, kVersion));
  const Header want = header_of(expected);
  if (h.scene_hash != want.scene_hash) throw fail("it was written for another scene (the scene file changed)");
  if (h.seed != want.seed) throw fail(fmt::format("it was written with --seed {}, not {}", h.seed, want.seed));
  if (h.sampler != want.sampler)
    throw fail(fmt::format("it was written with the {} sampler", sampler_kind_name(SamplerKind(h.sampler))));
  if (h.full_width != want.full_width || h.full_height != want.full_height || h.x0 != want.x0 || h.y0 != want.y0 ||
      h.x1 != want.x1 || h.y1 != want.y1)
    throw fail(fmt::format("it was written for a {}x{} image (pixels [{}, {}) x [{}, {})), not {}x{}", h.full_width,
                           h.full_height, h.x0, h.x1, h.y0, h.y1, want.full_width, want.full_height));
  Film film(expected.pixels.width(), expected.pixels.height());
  const bool ok =
      std::fread(film.sum.data(), sizeof(double), film.sum.size(), f.get()) == film.sum.size() &&
      std::fread(film.sum_sq.data(), sizeof(double), film.sum_sq.size(), f.get()) == film.sum_sq.size() &&
      std::fread(film.samples.data(), sizeof(uint32_t), film.samples.size(), f.get()) == film.samples.size() &&
      std::fread(film.target.data(), sizeof(uint32_t), film.target.size(), f.get()) == film.target.size() &&
      std::fread(film.rays.data(), sizeof(uint64_t), film.rays.size(), f.get()) == film.rays.size();
  unsigned char extra;
  if (!ok || std::fread(&extra, 1, 1, f.get()) != 0) throw fail("it is truncated or has extra bytes");
  for (std::size_t i = 0; i < film.sum.size(); ++i)
    if (!std::isfinite(film.sum[i]) || film.sum[i] < 0 || !std::isfinite(film.sum_sq[i]) || film.sum_sq[i] < 0)
      throw fail("it holds a negative or non-finite sum");
  return film;
}

}  // namespace dermis
