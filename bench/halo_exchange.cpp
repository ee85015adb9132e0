// What summing the shared blocks costs a step on N ranks (core/mpi/shared_block_sums.hpp),
// against the scatter it follows: a scene's particles (COLUMN-G by default) divided among the
// ranks by their blocks (core/grid/block_partition.hpp), each rank scattering its own mass,
// momentum and force-sized values (7 per node, as P2G's) with the linear hat, then the shared
// blocks summed. Medians of 50 repetitions per rank; rank 0 prints every rank's.
//   mpiexec -n N build/bench/afemp_bench_halo_exchange [SCENE]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/grid/background_grid.hpp"
#include "core/grid/block_partition.hpp"
#include "core/mpi/ranks.hpp"
#include "core/mpi/shared_block_sums.hpp"
#include "core/scene.hpp"
#include "mpm/particle_generation.hpp"

int main(int argc, char** argv) {
  using namespace afemp;
  core::MpiSession session(argc, argv);
  const int ranks = core::rank_count(), me = core::rank_index();
  const core::Scene scene = core::read_scene(argc > 1 ? argv[1] : AFEMP_BENCH_SCENE);
  const mpm::Particles all = mpm::generate_particles(scene);
  core::BackgroundGrid g(scene.mpm.grid);
  auto block_of = [&](const core::Vec3& x) {
    const auto c = g.cell_of(x);
    return core::BlockCoord{c[0] / 4, c[1] / 4, c[2] / 4};
  };
  std::map<core::BlockCoord, double> count;
  for (const core::Vec3& x : all.position) count[block_of(x)] += 1.0;
  std::vector<core::BlockCoord> blocks;
  std::vector<double> weights;
  for (const auto& [b, w] : count) {
    blocks.push_back(b);
    weights.push_back(w);
  }
  const core::BlockPartition partition = core::bisect_blocks(blocks, weights, ranks);
  std::vector<std::size_t> mine;
  std::vector<std::int64_t> cells;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (partition.rank_of(block_of(all.position[i])) == me) {
      mine.push_back(i);
      cells.push_back(g.linear_cell(g.cell_of(all.position[i])));
    }
  g.activate(cells);
  const core::NodalArray arrays[] = {{g.mass.data(), 1},
                                     {reinterpret_cast<double*>(g.momentum.data()), 3},
                                     {reinterpret_cast<double*>(g.force.data()), 3}};
  std::size_t shared = 0;
  for (std::size_t a = 0; a < g.active_block_count(); ++a)
    if (partition.rank_of(g.block_coord(g.active_block(a))) != me) ++shared;

  using clock = std::chrono::steady_clock;
  std::vector<double> scatter_s, sum_s;
  for (int rep = 0; rep < 50; ++rep) {
    const auto t0 = clock::now();
    std::fill(g.mass.begin(), g.mass.end(), 0.0);
    std::fill(g.momentum.begin(), g.momentum.end(), core::Vec3{});
    std::fill(g.force.begin(), g.force.end(), core::Vec3{});
    for (std::size_t i : mine) {
      const auto c = g.cell_of(all.position[i]);
      const core::CellWeights w = g.weights(all.position[i], c);
      std::array<std::int32_t, 8> slots;
      g.node_slots(c, slots);
      for (std::size_t n = 0; n < 8; ++n) {
        const auto s = static_cast<std::size_t>(slots[n]);
        const double mw = all.mass[i] * w.w[n];
        g.mass[s] += mw;
        g.momentum[s] += mw * all.velocity[i];
        g.force[s] -= all.volume[i] * w.grad[n];
      }
    }
    const auto t1 = clock::now();
    core::sum_shared_blocks(g, arrays, partition);
    const auto t2 = clock::now();
    scatter_s.push_back(std::chrono::duration<double>(t1 - t0).count());
    sum_s.push_back(std::chrono::duration<double>(t2 - t1).count());
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  double row[5] = {static_cast<double>(mine.size()), static_cast<double>(g.active_block_count()),
                   static_cast<double>(shared), median(scatter_s), median(sum_s)};
  std::vector<double> rows(me == 0 ? 5 * static_cast<std::size_t>(ranks) : 5);
  if (me == 0) std::copy_n(row, 5, rows.begin());
  for (int r = 1; r < ranks; ++r) {
    std::vector<core::RankMessage> out;
    if (me == r) {
      core::RankMessage m{0, std::vector<std::byte>(sizeof row)};
      std::memcpy(m.bytes.data(), row, sizeof row);
      out.push_back(std::move(m));
    }
    for (const core::RankMessage& m : core::exchange(out))
      std::memcpy(rows.data() + 5 * static_cast<std::size_t>(r), m.bytes.data(), sizeof row);
  }
  if (me != 0) return 0;
  std::printf("%d ranks, %zu particles, 1 thread each\n", ranks, all.size());
  std::printf(
      "| rank | particles | active blocks | blocks it sends (shared) | scatter (ms) | shared-block "
      "sums (ms) |\n|---|---|---|---|---|---|\n");
  for (int r = 0; r < ranks; ++r) {
    const double* x = rows.data() + 5 * static_cast<std::size_t>(r);
    std::printf("| %d | %.0f | %.0f | %.0f | %.3f | %.3f |\n", r, x[0], x[1], x[2], 1e3 * x[3],
                1e3 * x[4]);
  }
  return 0;
}
