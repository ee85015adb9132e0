// The nodal sums of the blocks that several ranks' particles reach, made whole on every rank
// that holds them: each rank sends its partial sums of every active block another rank owns
// (BlockPartition::rank_of) to that rank, the owner adds the partial sums of each block in rank
// order (its own at its place; the largest kept instead for an array of maxima,
// NodalArray::largest) and sends the totals back. A node is then the same on every
// rank, and a run on N ranks repeats itself bit for bit; the order differs from one rank's
// (rank count independence holds to round-off, not to the bit), except for the fixed-point
// arrays of the reproducible mode (NodalArray::fixed), whose integer sums hold it to the bit.
#pragma once

#include <span>

#include "core/grid/background_grid.hpp"
#include "core/grid/block_partition.hpp"
#include "core/rank_link.hpp"

namespace afemp::core {

// Collective: every rank calls it with the same arrays, after its own particles' sums. With
// `books` (resized to the active blocks), each of this rank's blocks is marked 1 where this rank
// books its nodes: the block's owner where it holds the block, else the lowest rank that holds
// it (an owner whose own particles do not reach the block holds no node of it, and the nodal
// work there would be booked by nobody). Every node that some rank holds is then booked once.
void sum_shared_blocks(BackgroundGrid& grid, std::span<const NodalArray> arrays,
                       const BlockPartition& partition, std::vector<char>* books = nullptr);

}  // namespace afemp::core
