// Background grid: trilinear shape functions (Ma 2005, eqs 2-5) and the sparse 4x4x4-node
// block activation. References: partition of unity and linear completeness of the trilinear
// basis (exact identities, checked to round-off), and block counts computed by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "core/grid/background_grid.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "test_support.hpp"

namespace afemp::mpm {
namespace {

using core::BackgroundGrid;
using core::GridSettings;
using core::Vec3;

// An off-origin grid with a cell that is not a power of two, so that no identity holds by
// accident of exact binary arithmetic: 13 x 9 x 10 cells (node counts not multiples of 4).
GridSettings odd_grid() {
  GridSettings g;
  g.cell = 0.35;
  g.min = {-3.2, 1.5, 10.0};
  g.max = {-3.2 + 13 * 0.35, 1.5 + 9 * 0.35, 10.0 + 10 * 0.35};
  return g;
}

std::vector<Vec3> random_points(const BackgroundGrid& grid, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto& s = grid.settings();
  std::vector<Vec3> pts;
  for (int i = 0; i < count; ++i) {
    Vec3 x;
    for (int a = 0; a < 3; ++a) {
      // Stay a hair inside the domain so the containing cell is always inside the grid.
      const double span = grid.cells()[static_cast<std::size_t>(a)] * grid.cell();
      x[a] = s.min[a] + span * (1e-9 + (1.0 - 2e-9) * u(rng));
    }
    pts.push_back(x);
  }
  return pts;
}

Vec3 node_of(const BackgroundGrid& g, const std::array<int, 3>& c, int n) {
  return g.node_position(c[0] + (n & 1), c[1] + ((n >> 1) & 1), c[2] + (n >> 2));
}

// Reference: sum_I N_I(x) = 1 and sum_I grad N_I(x) = 0 for the trilinear basis (exact);
// tolerance 1e-14 on N and 1e-14 / h on the gradient (round-off of a few products).
TEST(Grid, ShapeFunctionsArePartitionOfUnityWithZeroGradientSum) {
  const BackgroundGrid g(odd_grid());
  for (const Vec3& x : random_points(g, 2000, 11)) {
    const auto c = g.cell_of(x);
    ASSERT_TRUE(g.inside(c));
    const core::CellWeights w = g.weights(x, c);
    double sum = 0.0;
    Vec3 grad;
    for (int n = 0; n < 8; ++n) {
      sum += w.w[static_cast<std::size_t>(n)];
      grad += w.grad[static_cast<std::size_t>(n)];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(grad[a], 0.0, 1e-14 * g.inverse_cell());
  }
}

// Reference: linear completeness, sum_I N_I(x) x_I = x and sum_I grad N_I(x) (x) x_I = I
// (the basis reproduces linear fields exactly); tolerance 1e-12 relative to |x| (positions
// up to ~14 with h = 0.35) and 1e-12 on the identity.
TEST(Grid, ShapeFunctionsReproduceLinearFieldsExactly) {
  const BackgroundGrid g(odd_grid());
  for (const Vec3& x : random_points(g, 2000, 12)) {
    const auto c = g.cell_of(x);
    const core::CellWeights w = g.weights(x, c);
    Vec3 xr;
    double jac[3][3] = {};
    for (int n = 0; n < 8; ++n) {
      const Vec3 xi = node_of(g, c, n);
      xr += w.w[static_cast<std::size_t>(n)] * xi;
      const Vec3& d = w.grad[static_cast<std::size_t>(n)];
      for (int r = 0; r < 3; ++r)
        for (int s = 0; s < 3; ++s) jac[r][s] += xi[r] * d[s];  // d x_r / d x_s
    }
    const double scale = core::norm(x);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(xr[a], x[a], 1e-12 * scale);
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) EXPECT_NEAR(jac[r][s], r == s ? 1.0 : 0.0, 1e-12);
  }
}

// Reference: trilinear weights are products of (1 - f) and f with f in [0, 1): each lies in
// [0, 1]; at a grid node the node's own weight is exactly 1 and the others 0.
TEST(Grid, ShapeFunctionWeightsLieBetweenZeroAndOneAndInterpolateNodes) {
  const BackgroundGrid g(odd_grid());
  for (const Vec3& x : random_points(g, 2000, 13)) {
    const core::CellWeights w = g.weights(x, g.cell_of(x));
    for (double wi : w.w) {
      EXPECT_GE(wi, 0.0);
      EXPECT_LE(wi, 1.0);
    }
  }
  const std::array<int, 3> c{4, 2, 7};
  const core::CellWeights w = g.weights(g.node_position(4, 2, 7), c);
  EXPECT_NEAR(w.w[0], 1.0, 1e-14);
  for (int n = 1; n < 8; ++n) EXPECT_NEAR(w.w[static_cast<std::size_t>(n)], 0.0, 1e-14);
}

using Node = std::tuple<int, int, int>;
using Block = std::tuple<int, int, int>;

Block block_of(int i, int j, int k) {
  constexpr int e = BackgroundGrid::block_edge;
  return {i / e, j / e, k / e};
}

// Activates `cells` and checks the result against the definition: the active blocks are exactly
// those holding a node of a given cell; node_slots gives each node of each cell a slot that
// maps back to that node (node_of_slot), one slot per node, one node per slot.
void expect_activation_matches(BackgroundGrid& g, const std::vector<std::int64_t>& cells) {
  g.activate(cells);
  std::set<Block> expected_blocks;
  for (std::int64_t l : cells) {
    const auto c = g.cell_from_linear(l);
    for (int n = 0; n < 8; ++n)
      expected_blocks.insert(block_of(c[0] + (n & 1), c[1] + ((n >> 1) & 1), c[2] + (n >> 2)));
  }
  ASSERT_EQ(g.active_block_count(), expected_blocks.size());
  ASSERT_EQ(g.slot_count(), expected_blocks.size() * BackgroundGrid::block_nodes);
  EXPECT_EQ(g.mass.size(), g.slot_count());

  // Every slot belongs to an expected block and the slot -> node map is injective.
  std::map<Node, std::size_t> slot_of_node;
  for (std::size_t s = 0; s < g.slot_count(); ++s) {
    const auto n = g.node_of_slot(s);
    EXPECT_TRUE(expected_blocks.count(block_of(n[0], n[1], n[2])) == 1)
        << "slot " << s << " lies in a block no given cell touches";
    const bool fresh = slot_of_node.emplace(Node{n[0], n[1], n[2]}, s).second;
    EXPECT_TRUE(fresh) << "two slots map to node " << n[0] << "," << n[1] << "," << n[2];
  }
  // node_slots round-trips through node_of_slot for every node of every given cell.
  for (std::int64_t l : cells) {
    const auto c = g.cell_from_linear(l);
    EXPECT_EQ(g.linear_cell(c), l);
    std::array<std::int32_t, 8> slots;
    g.node_slots(c, slots);
    for (int n = 0; n < 8; ++n) {
      const std::array<int, 3> node{c[0] + (n & 1), c[1] + ((n >> 1) & 1), c[2] + (n >> 2)};
      const auto s = slots[static_cast<std::size_t>(n)];
      ASSERT_GE(s, 0);
      ASSERT_LT(static_cast<std::size_t>(s), g.slot_count());
      EXPECT_EQ(g.node_of_slot(static_cast<std::size_t>(s)), node);
      EXPECT_EQ(slot_of_node.at(Node{node[0], node[1], node[2]}), static_cast<std::size_t>(s));
    }
  }
}

// Reference: the definition of activate() (blocks = those holding a node of a given cell),
// for random cell sets in random order with repeats, including cells on block edges (whose
// nodes straddle 2, 4 or 8 blocks) and on the last cell layer of each axis.
TEST(Grid, ActivateGivesSlotsForExactlyTheNodesOfTheGivenCells) {
  BackgroundGrid g(odd_grid());
  std::mt19937_64 rng(21);
  const auto nc = g.cells();
  std::uniform_int_distribution<int> ui(0, nc[0] - 1), uj(0, nc[1] - 1), uk(0, nc[2] - 1);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<std::int64_t> cells;
    for (int i = 0; i < 25; ++i) cells.push_back(g.linear_cell({ui(rng), uj(rng), uk(rng)}));
    cells.push_back(g.linear_cell({3, 3, 3}));                          // 8 blocks
    cells.push_back(g.linear_cell({nc[0] - 1, nc[1] - 1, nc[2] - 1}));  // last corner cell
    cells.push_back(cells.front());                                     // a repeat
    expect_activation_matches(g, cells);  // re-activation must also drop the old blocks
  }
  // A single interior cell away from block edges: one block, 64 slots.
  const std::vector<std::int64_t> one{g.linear_cell({5, 5, 5})};
  expect_activation_matches(g, one);
  EXPECT_EQ(g.active_block_count(), 1u);
}

core::Scene box_scene(const Vec3& lo, const Vec3& hi) {
  return core::parse_scene(
      "[run]\nend_time = 1.0\n"
      "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [16, 16, 16]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
      "[[bodies]]\nname = \"b\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
      "shape = { box = { min = " +
          test::vec(lo.x, lo.y, lo.z) + ", max = " + test::vec(hi.x, hi.y, hi.z) + " } }\n",
      "blocks.toml");
}

// Reference (by hand, h = 1, blocks of 4 nodes per edge: block b holds nodes 4b..4b+3):
//  box [0,3]^3: cells 0..2, nodes 0..3        -> 1 block per axis -> 1 block, 27 cells;
//  box [4,8]^3: cells 4..7, nodes 4..8        -> blocks 1, 2      -> 8 blocks, 64 cells;
//  box [2,6]^3: cells 2..5, nodes 2..6        -> blocks 0, 1      -> 8 blocks, 64 cells;
//  box [0,3]x[0,3]x[0,7]: z nodes 0..7        -> 1 x 1 x 2        -> 2 blocks, 63 cells.
TEST(Grid, CompactBodyActivatesTheBlockCountComputedByHand) {
  struct Case {
    Vec3 lo, hi;
    std::size_t blocks, cells;
  };
  const Case cases[] = {{{0, 0, 0}, {3, 3, 3}, 1, 27},
                        {{4, 4, 4}, {8, 8, 8}, 8, 64},
                        {{2, 2, 2}, {6, 6, 6}, 8, 64},
                        {{0, 0, 0}, {3, 3, 7}, 2, 63}};
  for (const Case& k : cases) {
    const core::Scene scene = box_scene(k.lo, k.hi);
    MpmSolver solver(scene, generate_particles(scene));
    solver.prepare();
    EXPECT_EQ(solver.active_cells(), k.cells);
    EXPECT_EQ(solver.grid().active_block_count(), k.blocks)
        << "box " << k.lo.x << ".." << k.hi.x << " x " << k.lo.z << ".." << k.hi.z;
    EXPECT_EQ(solver.grid().slot_count(), k.blocks * 64);
  }
}

}  // namespace
}  // namespace afemp::mpm
