#include "dermis/core/float_array.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <new>
#include <utility>

namespace dermis {

namespace {

std::size_t page_bytes() {
  static const std::size_t bytes = std::size_t(sysconf(_SC_PAGESIZE));
  return bytes;
}

// Bytes of whole pages holding `floats` values; std::bad_alloc past what a size_t can count.
std::size_t mapping_bytes(std::size_t floats) {
  const std::size_t page = page_bytes();
  if (floats > (std::numeric_limits<std::size_t>::max() - page) / sizeof(float)) throw std::bad_alloc();
  return (floats * sizeof(float) + page - 1) / page * page;
}

}  // namespace

FloatArray::FloatArray(std::span<const float> values) { append(values); }

FloatArray::~FloatArray() {
  if (data_) munmap(data_, capacity_ * sizeof(float));
}

FloatArray::FloatArray(FloatArray&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      capacity_(std::exchange(other.capacity_, 0)) {}

FloatArray& FloatArray::operator=(FloatArray&& other) noexcept {
  if (this != &other) {
    if (data_) munmap(data_, capacity_ * sizeof(float));
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
  }
  return *this;
}

void FloatArray::remap(std::size_t floats) {
  const std::size_t bytes = mapping_bytes(floats);
  void* p;
  if (!data_)
    p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  else
    p = mremap(data_, capacity_ * sizeof(float), bytes, MREMAP_MAYMOVE);
  if (p == MAP_FAILED) throw std::bad_alloc();  // the old mapping, if any, is still whole
  data_ = static_cast<float*>(p);
  capacity_ = bytes / sizeof(float);
}

void FloatArray::grow(std::size_t at_least) {
  // Doubling: a remap per doubling, and the pages past the last value are address space only.
  remap(std::max(at_least, 2 * capacity_));
}

void FloatArray::reserve(std::size_t n) {
  if (n > capacity_) remap(n);
}

void FloatArray::append(std::span<const float> values) {
  if (values.empty()) return;
  if (values.size() > capacity_ - size_) grow(size_ + values.size());
  std::memcpy(data_ + size_, values.data(), values.size() * sizeof(float));
  size_ += values.size();
}

void FloatArray::shrink_to_fit() {
  if (!data_) return;
  if (size_ == 0) {
    munmap(data_, capacity_ * sizeof(float));
    data_ = nullptr;
    capacity_ = 0;
    return;
  }
  const std::size_t bytes = mapping_bytes(size_);
  if (bytes == capacity_ * sizeof(float)) return;
  // Shrinking in place never moves the mapping (no MREMAP_MAYMOVE needed).
  void* p = mremap(data_, capacity_ * sizeof(float), bytes, 0);
  if (p == MAP_FAILED) return;  // the larger mapping is still valid
  capacity_ = bytes / sizeof(float);
}

}  // namespace dermis
