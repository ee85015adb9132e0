// How a model's work would divide among ranks: its points (particles and mesh nodes) binned
// into the grid's 4 x 4 x 4-node blocks, the blocks split by recursive coordinate bisection
// weighted by their points (core/grid/block_partition.hpp), and each rank's load and halo. The
// geometry of the scaling estimate (bench/decomposition.cpp, bench/README.md).
#pragma once

#include <span>
#include <vector>

#include "core/grid/block_partition.hpp"
#include "core/model.hpp"
#include "core/scene.hpp"

namespace afemp::analysis {

struct DecompositionEstimate {
  int ranks = 1;
  std::size_t points = 0, blocks = 0;  // in all, and blocks that hold a point
  double max_points = 0.0;             // the most points one rank holds
  double mean_points = 0.0;            // points / ranks
  std::size_t max_reached = 0;         // the most blocks one rank would store (RankHalo)
  double mean_shared = 0.0;            // blocks a rank shares with others, mean and most
  std::size_t max_shared = 0;
  int max_neighbours = 0;  // the most ranks one rank shares blocks with
};

// One estimate per rank count (each at most the point-holding blocks). The block edge is four of
// the scene's cells, or, for meshes without a grid, four times the nodes' mean spacing over
// their bounding box.
std::vector<DecompositionEstimate> estimate_decomposition(const core::Model& model,
                                                          const core::Scene& scene,
                                                          std::span<const int> rank_counts);
// The same for given blocks and their points (weights), as the scaling model's boxes of blocks
// take it (analysis/scaling_model.hpp).
std::vector<DecompositionEstimate> estimate_blocks(std::span<const core::BlockCoord> blocks,
                                                   std::span<const double> weights,
                                                   std::span<const int> rank_counts);

}  // namespace afemp::analysis
