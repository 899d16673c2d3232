// Checkpoint files: exact round trip, and every mismatch refused with its reason.
#include "dermis/render/checkpoint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace dermis {
namespace {

std::string temp_path(const char* name) {
  return (std::filesystem::temp_directory_path() / (std::string("dermis_ckpt_") + name + "_" +
                                                    std::to_string(::testing::UnitTest::GetInstance()->random_seed())))
      .string();
}

std::string error_of(const std::string& path, const CheckpointKey& key) {
  try {
    read_checkpoint(path, key);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(Checkpoint, RoundTripIsExactAndMismatchesAreRefused) {
  CheckpointKey key{fingerprint("scene text"), 7, SamplerKind::Sobol, 20, 10, {2, 1, 5, 3}};
  Film film(3, 2);
  for (std::size_t i = 0; i < film.sum.size(); ++i) film.sum[i] = 0.1 * double(i) + 1e-17;
  for (std::size_t i = 0; i < film.sum_sq.size(); ++i) film.sum_sq[i] = 0.3 * double(i) + 1e-16;
  for (std::size_t i = 0; i < film.samples.size(); ++i)
    film.samples[i] = uint32_t(i + 1), film.target[i] = uint32_t(2 * i), film.rays[i] = 1000 + i;
  const std::string path = temp_path("roundtrip");
  write_checkpoint(path, key, film);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Film back = read_checkpoint(path, key);
  EXPECT_EQ(back.sum, film.sum);
  EXPECT_EQ(back.samples, film.samples);
  EXPECT_EQ(back.sum_sq, film.sum_sq);
  EXPECT_EQ(back.target, film.target);
  EXPECT_EQ(back.rays, film.rays);

  CheckpointKey other = key;
  other.scene_hash = fingerprint("scene text!");
  EXPECT_NE(error_of(path, other).find("another scene"), std::string::npos);
  other = key, other.seed = 8;
  EXPECT_NE(error_of(path, other).find("--seed 7, not 8"), std::string::npos);
  other = key, other.sampler = SamplerKind::Independent;
  EXPECT_NE(error_of(path, other).find("sobol sampler"), std::string::npos);
  other = key, other.pixels = {0, 0, 3, 2};
  EXPECT_NE(error_of(path, other).find("20x10 image"), std::string::npos);

  // Truncated, padded, not a checkpoint, missing.
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size - 1);
  EXPECT_NE(error_of(path, key).find("truncated"), std::string::npos);
  std::filesystem::resize_file(path, size + 1);
  EXPECT_NE(error_of(path, key).find("extra bytes"), std::string::npos);
  std::ofstream(path) << "hello";
  EXPECT_NE(error_of(path, key).find("not a Dermis checkpoint"), std::string::npos);
  std::filesystem::remove(path);
  EXPECT_NE(error_of(path, key).find("no such file"), std::string::npos);
}

TEST(Checkpoint, AnUnwritableFolderIsAnErrorAndLeavesNothing) {
  Film film(1, 1);
  EXPECT_THROW(write_checkpoint("/nonexistent-dir/x.ckpt", CheckpointKey{}, film), std::runtime_error);
}

TEST(Checkpoint, FingerprintIsFnv1a) {
  EXPECT_EQ(fingerprint(""), 14695981039346656037ull);
  EXPECT_EQ(fingerprint("a"), 0xaf63dc4c8601ec8cull);  // the published FNV-1a 64 test vector
  EXPECT_EQ(fingerprint("scene text"), fingerprint(" text", fingerprint("scene")));  // in pieces
}

}  // namespace
}  // namespace dermis
