// The step-time model of a divided run (scaling_model.hpp).
#include "analysis/scaling_model.hpp"

#include <cmath>

namespace afemp::analysis {

namespace {

// Rounds of a tree-shaped collective among p ranks.
double rounds(int p) {
  return p > 1 ? std::ceil(std::log2(static_cast<double>(p))) : 0.0;
}

}  // namespace

StepEstimate estimate_step(const DecompositionEstimate& d, const StepCostModel& m) {
  StepEstimate e;
  e.ranks = d.ranks;
  e.points_per_rank = d.mean_points;
  e.compute = m.point_seconds * d.max_points;
  if (d.ranks > 1) {
    const double shared = static_cast<double>(d.max_shared);
    const double neighbours = static_cast<double>(d.max_neighbours);
    const double alltoall = rounds(d.ranks) * m.latency;
    e.halo = m.scatters * (shared * (m.block_sum_seconds + 2.0 * m.block_bytes / m.bandwidth) +
                           2.0 * neighbours * m.latency + alltoall);
    e.migration = d.max_points * (m.scan_seconds + m.crossing * m.point_bytes / m.bandwidth) +
                  neighbours * m.latency + alltoall;
    const double allreduce = 2.0 * rounds(d.ranks) * m.latency;
    const double gather_broadcast =
        2.0 * rounds(d.ranks) * m.latency + 2.0 * d.ranks * m.energy_values * 8.0 / m.bandwidth;
    e.collectives = 2.0 * allreduce + gather_broadcast;
  }
  e.total = e.compute + e.halo + e.migration + e.collectives;
  const double one = m.point_seconds * static_cast<double>(d.points);
  e.speedup = e.total > 0.0 ? one / e.total : 1.0;
  e.efficiency = e.speedup / d.ranks;
  return e;
}

void block_box(int nx, int ny, int nz, double points_per_block,
               std::vector<core::BlockCoord>& blocks, std::vector<double>& weights) {
  blocks.clear();
  weights.clear();
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        blocks.push_back({i, j, k});
        weights.push_back(points_per_block);
      }
}

}  // namespace afemp::analysis
