// Recursive coordinate bisection of the grid's blocks (core/grid/block_partition.hpp) and the
// halo it leaves each rank, against what a regular lattice gives in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/grid/block_partition.hpp"

namespace afemp::core {
namespace {

std::vector<BlockCoord> lattice(int nx, int ny, int nz) {
  std::vector<BlockCoord> b;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) b.push_back({i, j, k});
  return b;
}

// Reference: 8 x 8 x 8 blocks of equal weight bisected x, then y, then z (the longest side, x
// first on a tie) among 8 ranks are eight 4 x 4 x 4 cubes of 64 blocks each. A corner cube
// [0, 4)^3 reaches [-1, 5)^3 = 216 blocks; of those, the ones with every coordinate in
// [-1, 3) (4^3 = 64) no other rank reaches, so 216 - 64 = 152 are shared, with 7 other ranks.
TEST(BlockPartition, EqualBlocksOfACubeSplitIntoEightEqualCubes) {
  const std::vector<BlockCoord> blocks = lattice(8, 8, 8);
  const std::vector<double> weights(blocks.size(), 1.0);
  const BlockPartition p = bisect_blocks(blocks, weights, 8);
  for (double load : p.load) EXPECT_EQ(load, 64.0);
  for (int r = 0; r < 8; ++r) {
    BlockCoord lo{99, 99, 99}, hi{-1, -1, -1};
    int count = 0;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      if (p.owner[i] == r) {
        ++count;
        for (std::size_t a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], blocks[i][a]);
          hi[a] = std::max(hi[a], blocks[i][a]);
        }
      }
    EXPECT_EQ(count, 64);
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_EQ(hi[a] - lo[a], 3) << "rank " << r << " axis " << a;
      EXPECT_EQ(lo[a] % 4, 0);
    }
  }
  const std::vector<RankHalo> halo = rank_halos(blocks, p.owner, 8);
  for (const RankHalo& h : halo) {
    EXPECT_EQ(h.owned, 64u);
    EXPECT_EQ(h.reached, 216u);
    EXPECT_EQ(h.shared, 152u);
    EXPECT_EQ(h.neighbours, 7);
  }
}

// Reference: a row of 4 blocks between 2 ranks is cut in its middle; each half reaches
// 4 x 3 x 3 = 36 blocks, of which the two layers x = 1, 2 (2 x 9 = 18) the other reaches too.
TEST(BlockPartition, ARowCutInTwoSharesTwoLayersOfBlocks) {
  const std::vector<BlockCoord> blocks = lattice(4, 1, 1);
  const std::vector<double> weights(4, 1.0);
  const BlockPartition p = bisect_blocks(blocks, weights, 2);
  EXPECT_EQ(p.owner, (std::vector<int>{0, 0, 1, 1}));
  for (const RankHalo& h : rank_halos(blocks, p.owner, 2)) {
    EXPECT_EQ(h.reached, 36u);
    EXPECT_EQ(h.shared, 18u);
    EXPECT_EQ(h.neighbours, 1);
  }
}

// Reference: the loads sum to the total weight (every block owned by one rank), and each cut
// misses its share by at most half the heaviest block, so after ceil(log2 5) = 3 levels a
// rank's load is within 3 heaviest blocks of total / 5; the split depends on the blocks, not on
// the order they are given in; the cuts give every block its owner, and a block below every
// block (above every block) rank 0 (the last rank).
TEST(BlockPartition, UnequalWeightsBalanceWithinTheHeaviestBlockPerLevelInAnyOrder) {
  std::vector<BlockCoord> blocks = lattice(10, 6, 3);
  std::vector<double> weights(blocks.size());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> w(0.0, 50.0);
  for (double& x : weights) x = w(rng);
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const double heaviest = *std::max_element(weights.begin(), weights.end());
  const BlockPartition p = bisect_blocks(blocks, weights, 5);
  EXPECT_NEAR(std::accumulate(p.load.begin(), p.load.end(), 0.0), total, 1e-9 * total);
  for (double load : p.load) EXPECT_LE(std::abs(load - total / 5), 3.0 * heaviest) << load;
  std::map<BlockCoord, int> owner;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    owner[blocks[i]] = p.owner[i];
    EXPECT_EQ(p.rank_of(blocks[i]), p.owner[i]) << "the cuts give each block its owner";
  }
  // Beyond the blocks (a halo block): the rank of the nearest side of every cut.
  EXPECT_EQ(p.rank_of({-1, -1, -1}), 0);
  EXPECT_EQ(p.rank_of({10, 6, 3}), 4);

  std::vector<std::size_t> order(blocks.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<BlockCoord> shuffled;
  std::vector<double> shuffled_weights;
  for (std::size_t i : order) {
    shuffled.push_back(blocks[i]);
    shuffled_weights.push_back(weights[i]);
  }
  const BlockPartition q = bisect_blocks(shuffled, shuffled_weights, 5);
  for (std::size_t i = 0; i < shuffled.size(); ++i) EXPECT_EQ(q.owner[i], owner[shuffled[i]]);
}

// Reference: every rank needs a block; 3 blocks among 4 ranks is refused, naming both counts.
TEST(BlockPartition, MoreRanksThanBlocksIsRefused) {
  const std::vector<BlockCoord> blocks = lattice(3, 1, 1);
  const std::vector<double> weights(3, 1.0);
  try {
    bisect_blocks(blocks, weights, 4);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("3 blocks cannot be divided among 4 ranks"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace afemp::core
