// The ranks of MPI_COMM_WORLD as the renderer's ProcessGroup (render/process_group.h):
// each collective is one MPI call. MPI is called from the main thread only (the
// render's worker threads never call it): MPI_THREAD_FUNNELED is enough.
#pragma once

#include "dermis/render/process_group.h"

namespace dermis::app {

class MpiProcessGroup : public ProcessGroup {
 public:
  MpiProcessGroup();  // after MPI_Init

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void allgather(std::span<float> values, std::size_t width) override;
  void allgather(std::span<double> values, std::size_t width) override;
  void broadcast(std::span<double> values) override;
  void sum_all(std::span<int64_t> values) override;
  void sum_all(std::span<float> values) override;
  void sum_to_root(std::span<double> values) override;
  void sum_to_root(std::span<uint32_t> values) override;
  void sum_to_root(std::span<uint64_t> values) override;
  void gather_to_root(double value, std::span<double> out) override;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace dermis::app
