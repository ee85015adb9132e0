// The scaling model of a divided MPM run (analysis/scaling_model.hpp) for 64-1024 ranks: strong
// scaling of a Hanchak slab (V6) at 4 mm cells and 3 particles per cell direction (27.4 million
// particles), weak scaling at 64 blocks (110,592 particles) per rank, and the model of a scene's
// own decomposition on the rank counts given, to set beside runs measured on them. The measured
// costs are this machine's (docs/parallel.md, "Scaling model", says how each was taken); the
// interconnect is assumed. Prints Markdown tables; runs no step.
//   afemp_bench_scaling_model [SCENE [RANKS ...]]
#include "analysis/scaling_model.hpp"

#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "analysis/decomposition_estimate.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "mpm/particle_migration.hpp"

namespace {

using namespace afemp;

void print_table(const char* title, const std::vector<analysis::DecompositionEstimate>& rows,
                 const analysis::StepCostModel& m, const std::vector<double>& one_rank_steps) {
  std::printf("%s\n\n", title);
  std::printf(
      "| ranks | points per rank | most / mean | shared blocks (most) | neighbours (most) | "
      "compute | halo | migration | collectives | step | speedup | efficiency |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const analysis::StepEstimate e = analysis::estimate_step(rows[k], m);
    // Weak scaling: each rank count against one rank holding the same points per rank (the
    // scaled speedup: ranks x that rank's step over this step).
    const double efficiency = one_rank_steps.empty() ? e.efficiency : one_rank_steps[k] / e.total;
    const double speedup = one_rank_steps.empty() ? e.speedup : e.ranks * efficiency;
    std::printf(
        "| %d | %.0f | %.3f | %zu | %d | %.2f ms | %.3f ms | %.3f ms | %.3f ms | %.2f ms | %.1f | "
        "%.2f |\n",
        e.ranks, e.points_per_rank, rows[k].max_points / rows[k].mean_points, rows[k].max_shared,
        rows[k].max_neighbours, 1e3 * e.compute, 1e3 * e.halo, 1e3 * e.migration,
        1e3 * e.collectives, 1e3 * e.total, speedup, efficiency);
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  analysis::StepCostModel m;
  // Measured on the 2-core development VM (docs/parallel.md, "Scaling model"):
  m.point_seconds = 2.40e-7;     // the MPM Taylor bar, 1 thread: 10.27 s / (18,666 x 2,293)
  m.block_sum_seconds = 5.1e-6;  // bench/halo_exchange.cpp, 2 ranks: 0.13-0.24 ms / 36 blocks
  m.scan_seconds = 8.9e-9;       // the Taylor bar on 2 ranks: 0.19 s / 2,293 steps / 9,333
  m.crossing = 0.005;            // MpiMpmRanks' bar: 180-540 sent in 150 steps, 575-1150 a rank
  m.scatters = 2;                // MUSL: P2G and the remap
  // Assumed: a 100 Gb/s link shared by the 16 ranks of a node, 2 microseconds a message.
  m.latency = 2e-6;
  m.bandwidth = 12.5e9 / 16.0;
  // The schema's bytes per point: the Taylor bar's particles as its solver holds them.
  const std::string scene_path = argc > 1 ? argv[1] : AFEMP_BENCH_SCENE;
  const core::Scene scene = core::read_scene(scene_path);
  {
    const mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
    const std::size_t n = std::min<std::size_t>(solver.particles().size(), 1000);
    std::vector<std::int32_t> which(n);
    std::iota(which.begin(), which.end(), 0);
    m.point_bytes = static_cast<double>(mpm::pack_particles(solver.particles(), which).size()) /
                    static_cast<double>(n);
  }
  std::printf(
      "Inputs: %.3g s per point-step, %.3g s per shared block and scatter, %.3g s per point "
      "scanned for migration, %.3g of a rank's points sent per step, %.0f bytes per point "
      "(%s), %d scatters per step; assumed interconnect: %.3g s a message, %.3g bytes/s per "
      "rank\n\n",
      m.point_seconds, m.block_sum_seconds, m.scan_seconds, m.crossing, m.point_bytes,
      scene_path.c_str(), m.scatters, m.latency, m.bandwidth);

  const std::vector<int> large = {1, 64, 128, 256, 512, 1024};
  std::vector<core::BlockCoord> blocks;
  std::vector<double> weights;
  // The slab: 610 x 610 x 178 mm at 4 mm cells is 38 x 38 x 11 blocks of 4^3 cells, 27
  // particles per cell: 1,728 per block.
  analysis::block_box(38, 38, 11, 1728.0, blocks, weights);
  print_table(
      "Strong scaling: the V6 slab at 4 mm cells, 3 particles per cell direction (38 x 38 x 11 "
      "blocks, 27.4 million particles)",
      analysis::estimate_blocks(blocks, weights, large), m, {});

  // Weak scaling: 64 blocks per rank, boxes as near cubes.
  std::vector<analysis::DecompositionEstimate> weak;
  std::vector<double> one;
  const int dims[][3] = {{4, 4, 4},    {16, 16, 16}, {32, 16, 16},
                         {32, 32, 16}, {32, 32, 32}, {64, 32, 32}};
  for (std::size_t k = 0; k < large.size(); ++k) {
    analysis::block_box(dims[k][0], dims[k][1], dims[k][2], 1728.0, blocks, weights);
    const int r[] = {large[k]};
    weak.push_back(analysis::estimate_blocks(blocks, weights, r).front());
    one.push_back(m.point_seconds * 64.0 * 1728.0);
  }
  print_table(
      "Weak scaling: 64 blocks (110,592 particles) per rank; efficiency: one rank's step holding "
      "as many over this step; speedup: ranks x efficiency",
      weak, m, one);

  if (argc > 2) {
    std::vector<int> ranks;
    for (int i = 2; i < argc; ++i) ranks.push_back(std::atoi(argv[i]));
    // On this machine's shared memory: the measured per-block and per-point costs include the
    // copies, and a message costs no more than they do.
    analysis::StepCostModel here = m;
    here.latency = 0.0;
    here.bandwidth = 1e300;
    const auto model = coupling::make_model(scene);
    print_table((scene_path + ": its own decomposition, on this machine's shared memory (no "
                              "latency; the copies are in the measured costs)")
                    .c_str(),
                analysis::estimate_decomposition(*model, scene, ranks), here, {});
  }
  return 0;
}
