// The processes that share one render (e.g. the ranks of an MPI job): which share of
// the work is this process's, and the few collective steps the render needs — the
// pre-passes' exchange, the stop flags and progress at each pass boundary, the film
// reduced to rank 0. The base class is one process alone: every step is a no-op. The
// MPI group lives in apps/dermis-mpi/, so the library never includes MPI.
//
// (Named "process group", not "distribution": core/distribution.h is the 1D pdf.)
//
// Collectives: every process calls them in the same order with the same sizes. They
// are called per stage, per table, per pass: never per ray or sample.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

namespace dermis {

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;

  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  bool is_root() const { return rank() == 0; }

  // This process's contiguous share [begin, end) of n items: blocks in rank order,
  // the first n % size() processes one item more.
  std::pair<std::size_t, std::size_t> share(std::size_t n) const { return share_of(rank(), n); }
  std::pair<std::size_t, std::size_t> share_of(int rank, std::size_t n) const {
    const std::size_t p = std::size_t(size()), r = std::size_t(rank), q = n / p, extra = n % p;
    const std::size_t begin = r * q + std::min(r, extra);
    return {begin, begin + q + (r < extra ? 1 : 0)};
  }

  // values holds n items of `width` numbers; each process filled the items of its
  // share(n). Afterwards every process holds all of them, exactly as their owners did.
  virtual void allgather(std::span<float> /*values*/, std::size_t /*width*/) {}
  virtual void allgather(std::span<double> /*values*/, std::size_t /*width*/) {}
  // Rank 0's values, to every process.
  virtual void broadcast(std::span<double> /*values*/) {}
  // Element-wise sums over the processes, on every process (stop flags, counts).
  virtual void sum_all(std::span<int64_t> /*values*/) {}
  virtual void sum_all(std::span<float> /*values*/) {}  // per-pixel maps: each from its owner
  // Element-wise sums over the processes, on rank 0 only (elsewhere: unspecified).
  virtual void sum_to_root(std::span<double> /*values*/) {}
  virtual void sum_to_root(std::span<uint32_t> /*values*/) {}
  virtual void sum_to_root(std::span<uint64_t> /*values*/) {}
  // Each process's number, on rank 0 (size() of them, in rank order; elsewhere unspecified).
  virtual void gather_to_root(double value, std::span<double> out) {
    if (!out.empty()) out[0] = value;
  }

  // True on every process when `flag` is true on any: a decision all must take together.
  bool any(bool flag) {
    int64_t v = flag ? 1 : 0;
    sum_all(std::span<int64_t>(&v, 1));
    return v > 0;
  }
};

// The group of one process, for callers that have none.
inline ProcessGroup& single_process() {
  static ProcessGroup group;
  return group;
}

}  // namespace dermis
