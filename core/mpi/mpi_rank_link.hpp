// The ranks of MPI_COMM_WORLD as a solver's RankLink (core/rank_link.hpp), over
// core/mpi/ranks.hpp and core/mpi/shared_block_sums.hpp. Needs a live MpiSession.
#pragma once

#include "core/rank_link.hpp"

namespace afemp::core {

class MpiRankLink final : public RankLink {
 public:
  int rank() const override;
  int ranks() const override;
  void sum_shared_blocks(BackgroundGrid& grid, std::span<const NodalArray> arrays,
                         const BlockPartition& partition, std::vector<char>* books) override;
  void sum_in_rank_order(std::span<double> values) override;
  double max_over_ranks(double value) override;
  std::vector<RankMessage> exchange(std::span<const RankMessage> outgoing) override;
  void gather_into(std::span<const std::byte> mine, std::vector<std::vector<std::byte>>& every,
                   bool to_rank_0) override;
  void broadcast_from_rank_0(std::vector<std::byte>& bytes) override;
};

}  // namespace afemp::core
