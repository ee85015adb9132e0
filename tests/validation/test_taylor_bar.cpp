// V2 with MPM (label `validation`): the Taylor bar of seed 001 §2.3.2 from
// examples/taylor_bar/mpm.toml — OFHC copper at 190 m/s on a rigid wall, quarter model,
// 8 particles per cell, to 72 us. Prints the row: L, D, W, mean error (eq 2-42), steps and
// wall time, beside the experiment and the seed's MPM3D row.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::mpm {
namespace {

TEST(TaylorBar, MpmMatchesExperimentWithinThreePercentMeanError) {
  const core::Scene scene =
      core::read_scene(std::string(AFEMP_SOURCE_DIR) + "/examples/taylor_bar/mpm.toml");
  ASSERT_TRUE(scene.taylor_reference.has_value());
  MpmModel sim(scene);
  const core::RunSummary s = core::run(sim, scene, {});
  ASSERT_TRUE(s.taylor.has_value());
  const core::TaylorMeasures& m = *s.taylor;
  std::printf("| method | cell | particles | L | D | W | mean error | steps | wall s | threads |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| experiment | | | 16.2 | 13.5 | 10.1 | - | | | |\n");
  std::printf("| MPM3D (seed 001) | | | 16.4 | 13.6 | 9.9 | 0.011 | 408 | | |\n");
  std::printf("| afemp MPM (%s) | %g | %zu | %.2f | %.2f | %.2f | %.4f | %ld | %.1f | %d |\n",
              core::to_string(scene.mpm.scheme), scene.mpm.grid.cell, s.particles, m.length,
              m.impact_diameter, m.bulge_diameter, s.taylor_error, s.steps, s.wall_seconds,
              core::thread_count());
  // Reference: experiment L 16.2, D 13.5, W 10.1; pass mark mean error <= 0.03 (VALIDATION
  // V2), and the run keeps its energy balance (plastic work is internal energy) within 2 %.
  EXPECT_LE(s.taylor_error, 0.03);
  EXPECT_LT(s.max_energy_error, 0.02);
}

}  // namespace
}  // namespace afemp::mpm
