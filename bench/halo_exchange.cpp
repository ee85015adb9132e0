// What summing the shared blocks costs a step on N ranks (core/mpi/shared_block_sums.hpp),
// against the scatter it follows: a scene's particles (COLUMN-G by default) divided among the
// ranks by their blocks (core/grid/block_partition.hpp), each rank scattering its own mass,
// momentum and force-sized values (7 per node, as P2G's) with the linear hat, then the shared
// blocks summed; and the same scatter in 64-bit fixed point, as a mode bit-identical across rank
// counts would accumulate. Medians of 50 repetitions per rank; rank 0 prints every rank's.
//   mpiexec -n N build/bench/afemp_bench_halo_exchange [SCENE]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
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
  // Calls f(slot, m N, V grad N) for each of particle i's 8 nodes (the linear hat).
  const auto each_node = [&](std::size_t i, auto&& f) {
    const auto c = g.cell_of(all.position[i]);
    const core::CellWeights w = g.weights(all.position[i], c);
    std::array<std::int32_t, 8> slots;
    g.node_slots(c, slots);
    for (std::size_t n = 0; n < 8; ++n)
      f(static_cast<std::size_t>(slots[n]), all.mass[i] * w.w[n], all.volume[i] * w.grad[n]);
  };
  std::vector<double> scatter_s, sum_s;
  for (int rep = 0; rep < 50; ++rep) {
    const auto t0 = clock::now();
    std::fill(g.mass.begin(), g.mass.end(), 0.0);
    std::fill(g.momentum.begin(), g.momentum.end(), core::Vec3{});
    std::fill(g.force.begin(), g.force.end(), core::Vec3{});
    for (std::size_t i : mine)
      each_node(i, [&](std::size_t s, double mw, const core::Vec3& vg) {
        g.mass[s] += mw;
        g.momentum[s] += mw * all.velocity[i];
        g.force[s] -= vg;
      });
    const auto t1 = clock::now();
    core::sum_shared_blocks(g, arrays, partition);
    const auto t2 = clock::now();
    scatter_s.push_back(std::chrono::duration<double>(t1 - t0).count());
    sum_s.push_back(std::chrono::duration<double>(t2 - t1).count());
  }
  // The same scatter accumulated in 64-bit fixed point (Le Grand, Götz & Walker 2013), whose sums
  // do not depend on their order: what a mode bit-identical across rank counts would pay for its
  // scatters. Each array's scale, the same on every rank, puts the bound of its sums (every
  // contribution's magnitude added up; a weight gradient is at most 1 / h) below 2^62.
  double bound[3] = {0.0, 0.0, 0.0};
  for (std::size_t i : mine) {
    const core::Vec3& v = all.velocity[i];
    bound[0] += all.mass[i];
    bound[1] += all.mass[i] * std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    bound[2] += all.volume[i] * g.inverse_cell();
  }
  double scale[3];
  for (int k = 0; k < 3; ++k) {
    int exponent = 0;
    std::frexp(core::sum_in_rank_order(bound[k]), &exponent);
    scale[k] = std::ldexp(1.0, 62 - exponent);
  }
  std::vector<std::int64_t> qm(g.mass.size()), qp(3 * g.momentum.size()), qf(3 * g.force.size());
  std::vector<double> fixed_s;
  for (int rep = 0; rep < 50; ++rep) {
    const auto t0 = clock::now();
    std::fill(qm.begin(), qm.end(), 0);
    std::fill(qp.begin(), qp.end(), 0);
    std::fill(qf.begin(), qf.end(), 0);
    for (std::size_t i : mine)
      each_node(i, [&](std::size_t s, double mw, const core::Vec3& vg) {
        qm[s] += std::llrint(mw * scale[0]);
        for (int k = 0; k < 3; ++k) {
          qp[3 * s + static_cast<std::size_t>(k)] +=
              std::llrint(mw * all.velocity[i][k] * scale[1]);
          qf[3 * s + static_cast<std::size_t>(k)] -= std::llrint(vg[k] * scale[2]);
        }
      });
    fixed_s.push_back(std::chrono::duration<double>(clock::now() - t0).count());
  }
  // The fixed-point masses against the same scatter in doubles (before any shared block's sum).
  std::vector<double> mass(g.mass.size(), 0.0);
  for (std::size_t i : mine)
    each_node(i, [&](std::size_t s, double mw, const core::Vec3&) { mass[s] += mw; });
  double mass_difference = 0.0, largest_mass = 0.0;
  for (std::size_t s = 0; s < mass.size(); ++s) {
    largest_mass = std::max(largest_mass, mass[s]);
    mass_difference =
        std::max(mass_difference, std::abs(static_cast<double>(qm[s]) / scale[0] - mass[s]));
  }

  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  double row[7] = {static_cast<double>(mine.size()),
                   static_cast<double>(g.active_block_count()),
                   static_cast<double>(shared),
                   median(scatter_s),
                   median(sum_s),
                   median(fixed_s),
                   mass_difference / largest_mass};
  constexpr std::size_t width = std::size(row);
  std::vector<double> rows(me == 0 ? width * static_cast<std::size_t>(ranks) : width);
  if (me == 0) std::copy_n(row, width, rows.begin());
  for (int r = 1; r < ranks; ++r) {
    std::vector<core::RankMessage> out;
    if (me == r) {
      core::RankMessage m{0, std::vector<std::byte>(sizeof row)};
      std::memcpy(m.bytes.data(), row, sizeof row);
      out.push_back(std::move(m));
    }
    for (const core::RankMessage& m : core::exchange(out))
      std::memcpy(rows.data() + width * static_cast<std::size_t>(r), m.bytes.data(), sizeof row);
  }
  if (me != 0) return 0;
  std::printf("%d ranks, %zu particles, 1 thread each\n", ranks, all.size());
  std::printf(
      "| rank | particles | active blocks | blocks it sends (shared) | scatter (ms) | shared-block "
      "sums (ms) | scatter in fixed point (ms) | its masses, largest difference / largest |\n"
      "|---|---|---|---|---|---|---|---|\n");
  for (int r = 0; r < ranks; ++r) {
    const double* x = rows.data() + width * static_cast<std::size_t>(r);
    std::printf("| %d | %.0f | %.0f | %.0f | %.3f | %.3f | %.3f | %.1e |\n", r, x[0], x[1], x[2],
                1e3 * x[3], 1e3 * x[4], 1e3 * x[5], x[6]);
  }
  return 0;
}
