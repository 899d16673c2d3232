// Tests of the mapped float array: values survive growth through many remaps, appends and
// shrinking, moves leave the source empty, and an empty array holds nothing.
#include "dermis/core/float_array.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace dermis {
namespace {

float value_at(std::size_t i) { return float(i % 100'003) * 0.25f + 1; }

TEST(FloatArray, ValuesSurviveGrowthThroughManyRemaps) {
  constexpr std::size_t kCount = 5'000'000;  // 20 MB: about 13 doublings from one page
  FloatArray a;
  std::size_t remaps = 0, capacity = 0;
  for (std::size_t i = 0; i < kCount; ++i) {
    a.push_back(value_at(i));
    if (a.capacity() != capacity) {
      ++remaps;
      capacity = a.capacity();
    }
  }
  EXPECT_GE(remaps, 10u);
  ASSERT_EQ(a.size(), kCount);
  for (std::size_t i = 0; i < kCount; ++i)
    if (a[i] != value_at(i)) FAIL() << "value " << i << " is " << a[i] << ", was " << value_at(i);
  a.shrink_to_fit();
  EXPECT_LT(a.capacity(), kCount + 4096);
  EXPECT_GE(a.capacity(), kCount);
  EXPECT_EQ(a[kCount - 1], value_at(kCount - 1));
  std::size_t i = 0, differing = 0;
  for (float v : a) differing += v != value_at(i++);
  EXPECT_EQ(i, kCount);
  EXPECT_EQ(differing, 0u);
}

TEST(FloatArray, SmallArrayStartsInOnePage) {
  FloatArray a{1, 2, 3};
  EXPECT_EQ(a.size(), 3u);
  EXPECT_GE(a.capacity(), 3u);
  EXPECT_LE(a.capacity(), 16384u);  // one page (64 KiB pages at most)
  EXPECT_EQ(a[0], 1);
  EXPECT_EQ(a[2], 3);
  a[1] = 5;
  EXPECT_EQ(a.data()[1], 5);
}

TEST(FloatArray, AppendAndReserve) {
  FloatArray a;
  a.reserve(10);
  EXPECT_GE(a.capacity(), 10u);
  EXPECT_TRUE(a.empty());
  std::vector<float> chunk(3000);
  for (std::size_t i = 0; i < chunk.size(); ++i) chunk[i] = float(i);
  for (int k = 0; k < 5; ++k) a.append(chunk);
  ASSERT_EQ(a.size(), 15000u);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], float(i % 3000)) << i;
  const std::vector<float> from_span(a.begin(), a.end());
  EXPECT_EQ(FloatArray(from_span).size(), 15000u);
}

TEST(FloatArray, MovesLeaveTheSourceEmpty) {
  FloatArray a{4, 5, 6};
  const float* values = a.data();
  FloatArray b(std::move(a));
  EXPECT_EQ(b.data(), values);  // the same pages, not a copy
  EXPECT_EQ(b.size(), 3u);
  EXPECT_EQ(a.size(), 0u);  // NOLINT(bugprone-use-after-move): moved-from is empty
  EXPECT_EQ(a.data(), nullptr);
  FloatArray c{7};
  c = std::move(b);
  EXPECT_EQ(c.data(), values);
  EXPECT_EQ(c[2], 6);
  EXPECT_TRUE(b.empty());  // NOLINT(bugprone-use-after-move)
  a.push_back(9);          // a moved-from array is usable
  EXPECT_EQ(a[0], 9);
}

TEST(FloatArray, EmptyArrayHoldsNothing) {
  FloatArray a;
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(a.capacity(), 0u);
  EXPECT_EQ(a.begin(), a.end());
  a.shrink_to_fit();
  EXPECT_EQ(a.data(), nullptr);
  a.push_back(1);
  a.push_back(2);
  a.append({});
  EXPECT_EQ(a.size(), 2u);
  FloatArray none{};
  EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace dermis
