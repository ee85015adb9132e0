// What a solver divided among MPI ranks asks of the other ranks, with no MPI type in sight: the
// library (libafemp) holds the solvers' side of the decomposition and needs no MPI; programs
// that run on ranks link core/mpi/ (afemp_ranks) and hand the solver an MpiRankLink
// (core/mpi/mpi_rank_link.hpp). Every call is collective: every rank makes the same calls in
// the same order.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "core/grid/block_partition.hpp"

namespace afemp::core {

class BackgroundGrid;

// A byte buffer to a rank (outgoing) or from one (incoming).
struct RankMessage {
  int rank = 0;
  std::vector<std::byte> bytes;
};

// A nodal array of the grid: fields x slots entries of `components` doubles each (mass 1,
// momentum and force 3), as BackgroundGrid stores them. The ranks' parts of a node are added,
// or for `largest` (grid contact's reach, a maximum over the particles) the largest is kept.
// `fixed`: the entries are 128-bit fixed-point values (core/exact_sum.hpp), two doubles'
// width each (components counts doubles: 2 a value), added as integers, whose sums do not
// depend on their order. `one_field`: slots entries only (an array the velocity fields share,
// the mixed pressure's), not fields x slots.
struct NodalArray {
  double* data = nullptr;
  int components = 1;
  bool largest = false;
  bool fixed = false;
  bool one_field = false;
};

class RankLink {
 public:
  virtual ~RankLink() = default;
  virtual int rank() const = 0;   // this process's rank
  virtual int ranks() const = 0;  // how many
  // After each rank's own scatter: the nodal sums (or maxima, NodalArray::largest) of every
  // block that several ranks' particles reach made whole, the same bits on every rank that holds
  // the block (core/mpi/shared_block_sums.hpp). `books`, where given (one entry per active
  // block), is set to whether this rank books the block's nodes (their work, their state kept
  // whole): the owner where it holds the block, else the lowest rank that holds it.
  virtual void sum_shared_blocks(BackgroundGrid& grid, std::span<const NodalArray> arrays,
                                 const BlockPartition& partition, std::vector<char>* books) = 0;
  // Each element summed over the ranks in rank order (the same bits on every rank).
  virtual void sum_in_rank_order(std::span<double> values) = 0;
  virtual double max_over_ranks(double value) = 0;
  // Every rank sends at most one message to each other rank and receives what was sent to it,
  // ordered by sender.
  virtual std::vector<RankMessage> exchange(std::span<const RankMessage> outgoing) = 0;

  // Every rank's `mine` into every[r], indexed by rank (this rank's own copied at its place): on
  // every rank, or with to_rank_0 on rank 0 alone (the other ranks get their own, the rest
  // empty). The buffers are resized in place, so that a gather repeated each step allocates
  // nothing once their sizes settle.
  virtual void gather_into(std::span<const std::byte> mine,
                           std::vector<std::vector<std::byte>>& every, bool to_rank_0) = 0;
  // Rank 0's `bytes` on every rank (the other ranks' replaced).
  virtual void broadcast_from_rank_0(std::vector<std::byte>& bytes) = 0;
  // The same into new buffers.
  std::vector<std::vector<std::byte>> gather(std::span<const std::byte> mine,
                                             bool to_rank_0 = false) {
    std::vector<std::vector<std::byte>> every;
    gather_into(mine, every, to_rank_0);
    return every;
  }
};

// The bytes of a text or of an array of plain values, for RankLink::gather and exchange.
inline std::span<const std::byte> bytes_of(std::string_view text) {
  return std::as_bytes(std::span<const char>(text.data(), text.size()));
}
template <class T>
std::span<const std::byte> bytes_of(std::span<const T> values) {
  return std::as_bytes(values);
}

}  // namespace afemp::core
