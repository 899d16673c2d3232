#include "mpi_process_group.h"

#include <mpi.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace dermis::app {

namespace {

// MPI counts are int: large arrays go in pieces (the film of a large frame has more
// than 2^31 numbers only beyond 700 Mpixels, but the pieces cost nothing).
constexpr std::size_t kPiece = std::size_t(1) << 28;

template <class T>
void sum_to_root_in_pieces(std::span<T> values, MPI_Datatype type, int rank) {
  for (std::size_t at = 0; at < values.size(); at += kPiece) {
    const int n = int(std::min(kPiece, values.size() - at));
    if (rank == 0)
      MPI_Reduce(MPI_IN_PLACE, values.data() + at, n, type, MPI_SUM, 0, MPI_COMM_WORLD);
    else
      MPI_Reduce(values.data() + at, nullptr, n, type, MPI_SUM, 0, MPI_COMM_WORLD);
  }
}

template <class T>
void allgather_shares(const ProcessGroup& group, std::span<T> values, std::size_t width, MPI_Datatype type) {
  const std::size_t items = values.size() / width;
  if (values.size() >= std::size_t(1) << 31)
    throw std::length_error("allgather: more than 2^31 numbers in one exchange");
  std::vector<int> counts(group.size()), offsets(group.size());
  for (int r = 0; r < group.size(); ++r) {
    const auto [begin, end] = group.share_of(r, items);
    counts[r] = int((end - begin) * width);
    offsets[r] = int(begin * width);
  }
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, values.data(), counts.data(), offsets.data(), type,
                 MPI_COMM_WORLD);
}

}  // namespace

MpiProcessGroup::MpiProcessGroup() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void MpiProcessGroup::allgather(std::span<float> values, std::size_t width) {
  allgather_shares(*this, values, width, MPI_FLOAT);
}
void MpiProcessGroup::allgather(std::span<double> values, std::size_t width) {
  allgather_shares(*this, values, width, MPI_DOUBLE);
}

void MpiProcessGroup::broadcast(std::span<double> values) {
  MPI_Bcast(values.data(), int(values.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void MpiProcessGroup::sum_all(std::span<int64_t> values) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
}

void MpiProcessGroup::sum_all(std::span<float> values) {
  for (std::size_t at = 0; at < values.size(); at += kPiece) {
    const int n = int(std::min(kPiece, values.size() - at));
    MPI_Allreduce(MPI_IN_PLACE, values.data() + at, n, MPI_FLOAT, MPI_SUM, MPI_COMM_WORLD);
  }
}

void MpiProcessGroup::sum_to_root(std::span<double> values) { sum_to_root_in_pieces(values, MPI_DOUBLE, rank_); }
void MpiProcessGroup::sum_to_root(std::span<uint32_t> values) { sum_to_root_in_pieces(values, MPI_UINT32_T, rank_); }
void MpiProcessGroup::sum_to_root(std::span<uint64_t> values) { sum_to_root_in_pieces(values, MPI_UINT64_T, rank_); }

void MpiProcessGroup::gather_to_root(double value, std::span<double> out) {
  MPI_Gather(&value, 1, MPI_DOUBLE, rank_ == 0 ? out.data() : nullptr, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

}  // namespace dermis::app
