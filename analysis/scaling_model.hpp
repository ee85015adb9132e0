// A model of the step time of an MPM run divided among P MPI ranks, from the decomposition's
// geometry (analysis/decomposition_estimate.hpp) and per-item costs measured on one machine,
// with an interconnect's latency and bandwidth assumed (docs/parallel.md, "Scaling model";
// bench/scaling_model.cpp prints its tables). The step of the slowest rank is the sum of
//
//   compute     = point_seconds x (the most points one rank holds)
//   halo        = scatters x [ shared x (block_sum_seconds + 2 block_bytes / bandwidth)
//                              + 2 neighbours x latency + alltoall(P) ]
//   migration   = points x (scan_seconds + crossing x point_bytes / bandwidth)
//                 + neighbours x latency + alltoall(P)
//   collectives = 2 allreduce(P) (the stable step's two maxima)
//                 + gather_broadcast(P, energy_values) (the energies in rank order)
//
// with shared and neighbours the most blocks one rank shares and the most ranks it shares them
// with, alltoall(P) = ceil(log2 P) latency (the exchange's message sizes, Bruck's algorithm),
// allreduce(P) = 2 ceil(log2 P) latency, and gather_broadcast(P, k) = 2 ceil(log2 P) latency +
// 2 P k 8 bytes / bandwidth (rank 0 receives and sends every rank's values). The terms are
// serial: no overlap of communication with computation, which the step does not do. On one rank
// the step is compute alone (the same per-point cost: a one-process run).
#pragma once

#include <vector>

#include "analysis/decomposition_estimate.hpp"

namespace afemp::analysis {

struct StepCostModel {
  // Measured, per step (docs/parallel.md says where and how):
  double point_seconds = 0.0;      // the whole step of one process per point, one thread
  double block_sum_seconds = 0.0;  // a shared block's sums per scatter: pack, copy, add, return
  double scan_seconds = 0.0;       // migration: finding each held point's rank
  double crossing = 0.0;           // points sent per step, a fraction of a rank's points
  double point_bytes = 0.0;        // one point through the point-state schema
  int scatters = 2;                // scatters followed by the shared sums (MUSL: P2G, remap)
  int energy_values = 17;          // values the energies sum (11 + 6 per body; one body)
  // Assumed: the interconnect, per rank.
  double latency = 0.0;                   // seconds per message
  double bandwidth = 0.0;                 // bytes per second
  double block_bytes = 64.0 * 7.0 * 8.0;  // a block's nodal sums: 64 nodes x 7 doubles
};

struct StepEstimate {
  int ranks = 1;
  double points_per_rank = 0.0;                                          // the mean
  double compute = 0.0, halo = 0.0, migration = 0.0, collectives = 0.0;  // seconds per step
  double total = 0.0;
  double speedup = 1.0;     // one process's step (point_seconds x points) over total
  double efficiency = 1.0;  // speedup / ranks
};

StepEstimate estimate_step(const DecompositionEstimate& d, const StepCostModel& m);

// A box of nx x ny x nz full grid blocks, each holding `points_per_block` points: the blocks and
// weights estimate_blocks takes (strong scaling: one box on many rank counts; weak scaling: a
// box per rank count with as many blocks per rank).
void block_box(int nx, int ny, int nz, double points_per_block,
               std::vector<core::BlockCoord>& blocks, std::vector<double>& weights);

}  // namespace afemp::analysis
