// MpiRankLink (mpi_rank_link.hpp): each call forwards to the MPI ranks' functions.
#include "core/mpi/mpi_rank_link.hpp"

#include "core/mpi/ranks.hpp"
#include "core/mpi/shared_block_sums.hpp"

namespace afemp::core {

int MpiRankLink::rank() const {
  return rank_index();
}

int MpiRankLink::ranks() const {
  return rank_count();
}

void MpiRankLink::sum_shared_blocks(BackgroundGrid& grid, std::span<const NodalArray> arrays,
                                    const BlockPartition& partition, std::vector<char>* books) {
  core::sum_shared_blocks(grid, arrays, partition, books);
}

void MpiRankLink::sum_in_rank_order(std::span<double> values) {
  core::sum_in_rank_order(values);
}

// The largest value is minus the smallest of the negated ones, exactly.
double MpiRankLink::max_over_ranks(double value) {
  return -min_over_ranks(-value);
}

std::vector<RankMessage> MpiRankLink::exchange(std::span<const RankMessage> outgoing) {
  return core::exchange(outgoing);
}

void MpiRankLink::gather_into(std::span<const std::byte> mine,
                              std::vector<std::vector<std::byte>>& every, bool to_rank_0) {
  gather_bytes(mine, every, to_rank_0);
}

void MpiRankLink::broadcast_from_rank_0(std::vector<std::byte>& bytes) {
  broadcast_bytes(bytes);
}

}  // namespace afemp::core
