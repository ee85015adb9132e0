// Particle-to-grid sums across 1 to 4 ranks (core/mpi/shared_block_sums.hpp): the particles of a
// cube split among the ranks by their blocks, each rank scatters its own and the shared blocks
// are summed; every node any rank holds must equal one rank's scatter of all the particles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/grid/background_grid.hpp"
#include "core/grid/block_partition.hpp"
#include "core/mpi/ranks.hpp"
#include "core/mpi/shared_block_sums.hpp"

namespace afemp::core {
namespace {

struct Point {
  Vec3 x, v;
  double m;
};

// 2 points per cell per direction over [0, 8)^3 on 1 mm cells (at 0.25 and 0.75 of a cell: the
// trilinear weights are products of 1/4 and 3/4), masses 1 .. 5, velocities not binary fractions.
std::vector<Point> cube_points() {
  std::vector<Point> p;
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        const double id = static_cast<double>(p.size());
        p.push_back({{0.25 + 0.5 * i, 0.25 + 0.5 * j, 0.25 + 0.5 * k},
                     {0.1 * id, 1.0 / (1.0 + id), -0.3},
                     1.0 + static_cast<double>(p.size() % 5)});
      }
  return p;
}

// Mass and momentum of `points` scattered into g (activated for them).
void scatter(BackgroundGrid& g, const std::vector<Point>& points) {
  std::vector<std::int64_t> cells;
  for (const Point& p : points) cells.push_back(g.linear_cell(g.cell_of(p.x)));
  g.activate(cells);
  std::fill(g.mass.begin(), g.mass.end(), 0.0);
  std::fill(g.momentum.begin(), g.momentum.end(), Vec3{});
  for (const Point& p : points) {
    const auto c = g.cell_of(p.x);
    const CellWeights w = g.weights(p.x, c);
    std::array<std::int32_t, 8> slots;
    g.node_slots(c, slots);
    for (std::size_t n = 0; n < 8; ++n) {
      g.mass[static_cast<std::size_t>(slots[n])] += p.m * w.w[n];
      g.momentum[static_cast<std::size_t>(slots[n])] += (p.m * w.w[n]) * p.v;
    }
  }
}

// Reference: one rank's scatter of all 4096 points, here on every rank. The masses are sums of
// integers times products of 1/4 and 3/4, exact in any order: equal to the bit. The momenta
// (v not binary fractions) within 1e-14 of the largest. Every block of that scatter is held by
// some rank, and its masses sum to the particles' (12,286) exactly; every block is booked by
// exactly one rank that holds it (the blocks just past the cube's high faces hold no point and
// are reached by the points of the cells below them: their owner need not hold them), so that
// the masses of the booked nodes, summed over the ranks, are the particles'.
TEST(MpiSharedBlockSums, EveryNodeHoldsOneRanksSumOfAllParticles) {
  const int n = rank_count(), me = rank_index();
  GridSettings settings;
  settings.cell = 1.0;
  settings.max = {16.0, 16.0, 16.0};
  const std::vector<Point> all = cube_points();
  BackgroundGrid whole(settings);
  scatter(whole, all);

  // The blocks that hold points, partitioned by their point counts.
  BackgroundGrid g(settings);
  std::map<BlockCoord, double> count;
  for (const Point& p : all) {
    const auto c = g.cell_of(p.x);
    count[{c[0] / 4, c[1] / 4, c[2] / 4}] += 1.0;
  }
  std::vector<BlockCoord> blocks;
  std::vector<double> weights;
  for (const auto& [b, w] : count) {
    blocks.push_back(b);
    weights.push_back(w);
  }
  const BlockPartition partition = bisect_blocks(blocks, weights, n);
  std::vector<Point> mine;
  for (const Point& p : all) {
    const auto c = g.cell_of(p.x);
    if (partition.rank_of({c[0] / 4, c[1] / 4, c[2] / 4}) == me) mine.push_back(p);
  }
  scatter(g, mine);
  const NodalArray arrays[] = {{g.mass.data(), 1},
                               {reinterpret_cast<double*>(g.momentum.data()), 3}};
  std::vector<char> books;
  sum_shared_blocks(g, arrays, partition, &books);
  ASSERT_EQ(books.size(), g.active_block_count());

  double largest = 0.0;
  for (const Vec3& m : whole.momentum) largest = std::max(largest, norm(m));
  int wrong_mass = 0, wrong_momentum = 0, outside = 0;
  std::vector<double> held(whole.active_block_count(), 0.0);
  for (std::size_t s = 0; s < g.slot_count(); ++s) {
    const std::int32_t a = whole.active_number(g.active_block(s / BackgroundGrid::block_nodes));
    if (a < 0) {
      ++outside;
      continue;
    }
    held[static_cast<std::size_t>(a)] = 1.0;
    const std::size_t w =
        static_cast<std::size_t>(a) * BackgroundGrid::block_nodes + s % BackgroundGrid::block_nodes;
    if (g.mass[s] != whole.mass[w]) ++wrong_mass;
    if (norm(g.momentum[s] - whole.momentum[w]) > 1e-14 * largest) ++wrong_momentum;
  }
  EXPECT_EQ(outside, 0) << "a block one rank's scatter does not reach";
  EXPECT_EQ(wrong_mass, 0);
  EXPECT_EQ(wrong_momentum, 0);
  // Each block booked once, by a rank that holds it; the booked nodes hold the whole mass.
  std::vector<double> booked(whole.active_block_count(), 0.0);
  std::vector<double> booked_mass{0.0};
  for (std::size_t b = 0; b < g.active_block_count(); ++b) {
    if (!books[b]) continue;
    booked[static_cast<std::size_t>(whole.active_number(g.active_block(b)))] += 1.0;
    for (std::size_t s = 0; s < BackgroundGrid::block_nodes; ++s)
      booked_mass[0] += g.mass[b * BackgroundGrid::block_nodes + s];
  }
  sum_in_rank_order(booked);
  sum_in_rank_order(booked_mass);
  EXPECT_EQ(std::count(booked.begin(), booked.end(), 1.0),
            static_cast<std::ptrdiff_t>(booked.size()));
  // Every block of one rank's scatter is on some rank, and holds the particles' mass.
  sum_in_rank_order(held);
  EXPECT_EQ(std::count(held.begin(), held.end(), 0.0), 0);
  double total = 0.0, on_grid = 0.0;
  for (const Point& p : all) total += p.m;
  for (double m : whole.mass) on_grid += m;
  EXPECT_EQ(on_grid, total);
  EXPECT_EQ(booked_mass[0], total);
}

}  // namespace
}  // namespace afemp::core
