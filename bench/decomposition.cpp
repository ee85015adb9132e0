// The decomposition estimate of a scene (analysis/decomposition_estimate.hpp): how its points
// would divide among 2 to 1024 ranks by recursive coordinate bisection of the grid's blocks,
// each rank's load against the mean and the blocks it would share. The geometry of the scaling
// estimate (bench/README.md, "Decomposition"); it runs no step.
//   afemp_bench_decomposition SCENE [RANKS ...]
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "analysis/decomposition_estimate.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"

int main(int argc, char** argv) {
  using namespace afemp;
  if (argc < 2) {
    std::fprintf(stderr, "usage: afemp_bench_decomposition SCENE [RANKS ...]\n");
    return 2;
  }
  std::vector<int> ranks;
  for (int i = 2; i < argc; ++i) ranks.push_back(std::atoi(argv[i]));
  if (ranks.empty()) ranks = {2, 4, 8, 16, 64, 256, 1024};
  const core::Scene scene = core::read_scene(argv[1]);
  const auto model = coupling::make_model(scene);
  const auto estimates = analysis::estimate_decomposition(*model, scene, ranks);
  if (estimates.empty()) {
    std::fprintf(stderr, "no rank count given is at most the scene's blocks\n");
    return 2;
  }
  std::printf("%s: %zu points in %zu blocks\n\n", argv[1], estimates.front().points,
              estimates.front().blocks);
  std::printf(
      "| ranks | points per rank (mean) | most on one rank / mean | blocks one rank stores "
      "(most) | shared blocks per rank (mean, most) | neighbour ranks (most) |\n"
      "|---|---|---|---|---|---|\n");
  for (const analysis::DecompositionEstimate& e : estimates)
    std::printf("| %d | %.0f | %.3f | %zu | %.1f, %zu | %d |\n", e.ranks, e.mean_points,
                e.max_points / e.mean_points, e.max_reached, e.mean_shared, e.max_shared,
                e.max_neighbours);
  return 0;
}
