// The step-time model of a divided run (analysis/scaling_model.hpp) against its closed form.
#include <gtest/gtest.h>

#include <vector>

#include "analysis/scaling_model.hpp"

namespace afemp::analysis {
namespace {

// Reference: the header's formula worked by hand for 4 ranks (2 rounds of a tree), the most
// loaded rank holding 1,100 of 4,000 points and sharing 10 blocks with 3 ranks:
//   compute     = 1e-6 x 1100                                            = 1.1e-3
//   halo        = 2 [10 (1e-5 + 2 x 3584 / 1e9) + 2 x 3 x 2e-6 + 2 x 2e-6] = 3.7536e-4
//   migration   = 1100 (1e-8 + 0.01 x 400 / 1e9) + 3 x 2e-6 + 2 x 2e-6     = 2.54e-5
//   collectives = 2 (2 x 2 x 2e-6) + 2 x 2 x 2e-6 + 2 x 4 x 11 x 8 / 1e9  = 2.4704e-5
// total 1.525464e-3 s, speedup 4e-3 / total = 2.62216. Tolerance: round-off (1e-12 relative).
TEST(ScalingModel, AStepIsTheSumOfItsTermsAsWorkedByHand) {
  DecompositionEstimate d;
  d.ranks = 4;
  d.points = 4000;
  d.max_points = 1100.0;
  d.mean_points = 1000.0;
  d.max_shared = 10;
  d.max_neighbours = 3;
  StepCostModel m;
  m.point_seconds = 1e-6;
  m.block_sum_seconds = 1e-5;
  m.scan_seconds = 1e-8;
  m.crossing = 0.01;
  m.point_bytes = 400.0;
  m.energy_values = 11;
  m.latency = 2e-6;
  m.bandwidth = 1e9;
  const StepEstimate e = estimate_step(d, m);
  EXPECT_NEAR(e.compute, 1.1e-3, 1e-15);
  EXPECT_NEAR(e.halo, 3.7536e-4, 1e-15);
  EXPECT_NEAR(e.migration, 2.54e-5, 1e-16);
  EXPECT_NEAR(e.collectives, 2.4704e-5, 1e-16);
  EXPECT_NEAR(e.total, 1.525464e-3, 1e-15);
  EXPECT_NEAR(e.speedup, 4e-3 / 1.525464e-3, 1e-12);
  EXPECT_NEAR(e.efficiency, e.speedup / 4.0, 1e-12);
}

// Reference: with communication free, an even split of equal blocks runs P times faster: a box
// of 4 x 4 x 4 blocks of 1,000 points among 8 ranks gives each 2 x 2 x 2 blocks (8,000 points),
// speedup exactly 8. On one rank the step is the compute alone, speedup 1.
TEST(ScalingModel, FreeCommunicationAndAnEvenSplitGiveTheIdealSpeedup) {
  std::vector<core::BlockCoord> blocks;
  std::vector<double> weights;
  block_box(4, 4, 4, 1000.0, blocks, weights);
  ASSERT_EQ(blocks.size(), 64u);
  const int ranks[] = {1, 8};
  const std::vector<DecompositionEstimate> d = estimate_blocks(blocks, weights, ranks);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[1].max_points, 8000.0);
  EXPECT_EQ(d[1].max_neighbours, 7);
  StepCostModel m;
  m.point_seconds = 1e-7;
  m.bandwidth = 1e300;  // latency and the per-block and per-point costs are 0 by default
  const StepEstimate one = estimate_step(d[0], m);
  EXPECT_DOUBLE_EQ(one.total, 1e-7 * 64000.0);
  EXPECT_DOUBLE_EQ(one.speedup, 1.0);
  const StepEstimate eight = estimate_step(d[1], m);
  EXPECT_DOUBLE_EQ(eight.total, 1e-7 * 8000.0);
  EXPECT_DOUBLE_EQ(eight.speedup, 8.0);
  // Communication only slows it: a latency of 1 microsecond costs at least the stable step's two
  // maxima (2 x 2 x 3 rounds) and the energies' gather and broadcast (2 x 3 rounds).
  m.latency = 1e-6;
  const StepEstimate slower = estimate_step(d[1], m);
  EXPECT_GE(slower.collectives, 18e-6 - 1e-18);
  EXPECT_LT(slower.speedup, 8.0);
}

}  // namespace
}  // namespace afemp::analysis
