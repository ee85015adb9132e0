// The decomposition estimate of a scene (analysis/decomposition_estimate.hpp) against a body
// whose particles fill the grid's blocks evenly.
#include <gtest/gtest.h>

#include "analysis/decomposition_estimate.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"

namespace afemp::analysis {
namespace {

// Reference: an 8 mm cube on 1 mm cells at 2 particles per cell per direction is 16^3 = 4096
// particles in 2 x 2 x 2 blocks of 4 x 4 x 4 cells (512 each). Among 8 ranks each holds one
// block (4096 / 8 = 512 particles, load ratio exactly 1); a corner block reaches 3^3 = 27
// blocks, of which all but the one farthest from the others (26) another rank reaches too,
// with 7 neighbour ranks. Among 2 ranks: 2048 each, each reaching 4 x 4 x 3 = 48 blocks, 2 x 16
// = 32 of them shared.
TEST(DecompositionEstimate, AnEvenlyFilledCubeSplitsIntoEqualBlocks) {
  const core::Scene scene = core::parse_scene(
      "[run]\nend_time = 1.0\n"
      "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [16, 16, 16]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
      "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
      "shape = { box = { min = [0, 0, 0], max = [8, 8, 8] } }\n",
      "cube.toml");
  const auto model = coupling::make_model(scene);
  const int ranks[] = {2, 8, 9};
  const std::vector<DecompositionEstimate> e = estimate_decomposition(*model, scene, ranks);
  ASSERT_EQ(e.size(), 2u) << "9 ranks among 8 blocks are left out";
  EXPECT_EQ(e[0].points, 4096u);
  EXPECT_EQ(e[0].blocks, 8u);
  EXPECT_EQ(e[0].max_points, 2048.0);
  EXPECT_EQ(e[0].max_reached, 48u);
  EXPECT_EQ(e[0].max_shared, 32u);
  EXPECT_EQ(e[0].max_neighbours, 1);
  EXPECT_EQ(e[1].ranks, 8);
  EXPECT_EQ(e[1].max_points, 512.0);
  EXPECT_EQ(e[1].mean_points, 512.0);
  EXPECT_EQ(e[1].max_reached, 27u);
  EXPECT_EQ(e[1].max_shared, 26u);
  EXPECT_EQ(e[1].mean_shared, 26.0);
  EXPECT_EQ(e[1].max_neighbours, 7);
}

}  // namespace
}  // namespace afemp::analysis
