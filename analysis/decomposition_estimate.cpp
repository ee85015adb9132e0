// The decomposition estimate of a model (decomposition_estimate.hpp).
#include "analysis/decomposition_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "core/grid/background_grid.hpp"
#include "core/grid/block_partition.hpp"

namespace afemp::analysis {

std::vector<DecompositionEstimate> estimate_decomposition(const core::Model& model,
                                                          const core::Scene& scene,
                                                          std::span<const int> rank_counts) {
  std::vector<core::Vec3> points;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const core::BodyPoints p = model.body_points(static_cast<int>(b));
    points.insert(points.end(), p.position.begin(), p.position.end());
  }
  if (points.empty()) throw std::invalid_argument("the scene has no particles or nodes");
  core::Vec3 origin = scene.mpm.grid.min;
  double cell = scene.mpm.grid.cell;
  if (!(cell > 0.0)) {
    // A mesh alone: the mean spacing of its nodes over their bounding box.
    core::Vec3 hi = points.front();
    origin = hi;
    for (const core::Vec3& x : points)
      for (int a = 0; a < 3; ++a) {
        origin[a] = std::min(origin[a], x[a]);
        hi[a] = std::max(hi[a], x[a]);
      }
    cell = std::cbrt((hi.x - origin.x) * (hi.y - origin.y) * (hi.z - origin.z) /
                     static_cast<double>(points.size()));
    if (!(cell > 0.0)) throw std::invalid_argument("the scene's nodes span no volume");
  }
  const double edge = core::BackgroundGrid::block_edge * cell;
  std::map<core::BlockCoord, double> weight;
  for (const core::Vec3& x : points) {
    core::BlockCoord b;
    for (int a = 0; a < 3; ++a)
      b[static_cast<std::size_t>(a)] = static_cast<int>(std::floor((x[a] - origin[a]) / edge));
    weight[b] += 1.0;
  }
  std::vector<core::BlockCoord> blocks;
  std::vector<double> weights;
  for (const auto& [b, w] : weight) {
    blocks.push_back(b);
    weights.push_back(w);
  }
  return estimate_blocks(blocks, weights, rank_counts);
}

std::vector<DecompositionEstimate> estimate_blocks(std::span<const core::BlockCoord> blocks,
                                                   std::span<const double> weights,
                                                   std::span<const int> rank_counts) {
  double points = 0.0;
  for (double w : weights) points += w;
  std::vector<DecompositionEstimate> out;
  for (int ranks : rank_counts) {
    if (ranks < 1 || static_cast<std::size_t>(ranks) > blocks.size()) continue;
    const core::BlockPartition part = core::bisect_blocks(blocks, weights, ranks);
    const std::vector<core::RankHalo> halo = core::rank_halos(blocks, part.owner, ranks);
    DecompositionEstimate e;
    e.ranks = ranks;
    e.points = static_cast<std::size_t>(std::llround(points));
    e.blocks = blocks.size();
    e.max_points = *std::max_element(part.load.begin(), part.load.end());
    e.mean_points = points / ranks;
    double shared = 0.0;
    for (const core::RankHalo& h : halo) {
      e.max_reached = std::max(e.max_reached, h.reached);
      e.max_shared = std::max(e.max_shared, h.shared);
      e.max_neighbours = std::max(e.max_neighbours, h.neighbours);
      shared += static_cast<double>(h.shared);
    }
    e.mean_shared = shared / ranks;
    out.push_back(e);
  }
  return out;
}

}  // namespace afemp::analysis
