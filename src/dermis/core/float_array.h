// A growable array of floats in memory of its own: an anonymous private mapping that grows by
// mremap, which moves page tables instead of copying values.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <memory>
#include <span>

namespace dermis {

// Why not std::vector: a grid read from scene text has no count until its ']', and a vector's
// growth copies every value into a new buffer while the old one is still resident (twice the
// grid at that moment); here growth remaps the same pages, and pages not yet written are
// never resident. Move-only (a grid exists once); mmap and mremap failures throw std::bad_alloc.
class FloatArray {
 public:
  FloatArray() = default;
  explicit FloatArray(std::span<const float> values);
  FloatArray(std::initializer_list<float> values) : FloatArray(std::span<const float>(values.begin(), values.size())) {}
  ~FloatArray();
  FloatArray(FloatArray&& other) noexcept;
  FloatArray& operator=(FloatArray&& other) noexcept;
  FloatArray(const FloatArray&) = delete;
  FloatArray& operator=(const FloatArray&) = delete;

  void push_back(float v) {
    if (size_ == capacity_) grow(size_ + 1);
    data_[size_++] = v;
  }
  void append(std::span<const float> values);
  // Room for n values without a further remap.
  void reserve(std::size_t n);
  // Gives back the pages past the last value (mremap down; none left when empty).
  void shrink_to_fit();

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::size_t capacity() const { return capacity_; }
  float* data() { return data_; }
  const float* data() const { return data_; }
  float& operator[](std::size_t i) { return data_[i]; }
  float operator[](std::size_t i) const { return data_[i]; }
  float* begin() { return data_; }
  float* end() { return data_ + size_; }
  const float* begin() const { return data_; }
  const float* end() const { return data_ + size_; }

 private:
  // Maps (or remaps) to exactly `floats` values of capacity, rounded up to whole pages.
  void remap(std::size_t floats);
  void grow(std::size_t at_least);

  float* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;  // values the mapping holds (its bytes / sizeof(float))
};

// A shared array holding a copy of `values` (small grids made in code: defaults, tests).
inline std::shared_ptr<const FloatArray> make_shared_floats(std::span<const float> values) {
  return std::make_shared<const FloatArray>(values);
}
inline std::shared_ptr<const FloatArray> make_shared_floats(std::initializer_list<float> values) {
  return std::make_shared<const FloatArray>(values);
}

}  // namespace dermis
