// The FE solver is deterministic by design: element forces are gathered per node in the fixed
// order of the incidence lists and every reduction combines per-thread sums in thread order,
// so a run gives the same node and element state bit for bit with one thread, with two, and
// when repeated.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "copper_bar_on_wall.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {
namespace {

// A copper bar onto a rigid wall with Johnson-Cook, Mie-Grueneisen and erosion: every stage.
const std::string scene_text = test::eroding_copper_bar_of_hexahedra();

struct State {
  std::vector<core::Vec3> position;
  std::vector<core::SymTensor> stress;
  std::size_t live = 0;
};

State run(int threads) {
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  const core::Scene scene = core::parse_scene(scene_text, "determinism.toml");
  FeSolver solver(scene);
  EXPECT_TRUE(core::worth_threads(solver.hexahedra().size()));  // threaded element sweep
  EXPECT_TRUE(core::worth_threads(solver.nodes().size()));      // threaded node sweep
  for (int k = 0; k < 100; ++k) solver.step(solver.stable_time_step());
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  return {solver.nodes().position, solver.hexahedra().stress, solver.live_hexahedra()};
}

bool same_bits(const void* a, const void* b, std::size_t bytes) {
  return std::memcmp(a, b, bytes) == 0;
}

TEST(FeDeterminism, OneAndTwoThreadsGiveTheSameBits) {
  const State one = run(1), two = run(2), again = run(2);
  ASSERT_EQ(one.position.size(), two.position.size());
  std::printf("%zu nodes, %zu of %zu hexahedra alive after 100 steps\n", one.position.size(),
              one.live, one.stress.size());
  EXPECT_LT(one.live, one.stress.size());  // erosion took part
  EXPECT_TRUE(same_bits(one.position.data(), two.position.data(),
                        one.position.size() * sizeof(core::Vec3)));
  EXPECT_TRUE(
      same_bits(one.stress.data(), two.stress.data(), one.stress.size() * sizeof(core::SymTensor)));
  EXPECT_TRUE(same_bits(two.position.data(), again.position.data(),
                        two.position.size() * sizeof(core::Vec3)));
  EXPECT_EQ(one.live, two.live);
}

}  // namespace
}  // namespace afemp::fem
