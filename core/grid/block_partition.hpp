// How the grid's sparse blocks would divide among ranks: recursive coordinate bisection
// (Berger & Bokhari 1987, IEEE Trans. Computers 36(5)) of the blocks that hold work, weighted by
// it, and the halo each rank then shares with the others. The decomposition of a run across MPI
// ranks starts from this split; today it gives the geometry of the scaling estimate
// (bench/decomposition.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace afemp::core {

using BlockCoord = std::array<int, 3>;

// Owner rank of each block, in the order given, and each rank's summed weight; and the cuts, so
// that any block, one with no weight included (a block only the halo of another reaches), has a
// rank: rank_of.
struct BlockPartition {
  std::vector<int> owner;
  std::vector<double> load;
  // A cut sends a block below it to `lower`, else to `upper`: below when its coordinates, taken
  // in the order (axis, axis + 1, axis + 2) mod 3, come before `first_upper`'s. A child is a cut's
  // index, or, when negative, the rank -1 - child.
  struct Cut {
    int axis = 0;
    BlockCoord first_upper{};
    int lower = -1, upper = -1;
  };
  std::vector<Cut> cuts;  // cuts[0] the first; empty for one rank
  int rank_of(const BlockCoord& b) const;
};

// Splits the blocks among `ranks` ranks (blocks.size() >= ranks >= 1; weights >= 0, one per
// block): the blocks are cut across the longest side of their bounding box (in blocks; x
// before y before z on a tie) into two groups whose weights stand as the rank counts of the two
// halves (floor(ranks / 2) to the lower side), and each group again until one rank is left. The
// cut falls between blocks in (axis, then the other two coordinates) order, where the weight
// below it is nearest its share; every group keeps at least one block per rank. The result
// depends on the blocks and weights only, not their order.
BlockPartition bisect_blocks(std::span<const BlockCoord> blocks, std::span<const double> weights,
                             int ranks);

// What each rank would hold and share: the blocks its own blocks' particles and elements reach
// (the owned blocks and their 26 neighbours: every stencil of afemp reaches at most two nodes
// past its cell, within the next 4 x 4 x 4-node block), how many of those another rank reaches
// too (the halo whose nodal sums are exchanged each scatter), and with how many ranks it shares
// them.
struct RankHalo {
  std::size_t owned = 0, reached = 0, shared = 0;
  int neighbours = 0;
};

std::vector<RankHalo> rank_halos(std::span<const BlockCoord> blocks, std::span<const int> owner,
                                 int ranks);

}  // namespace afemp::core
