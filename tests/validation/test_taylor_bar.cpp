// V2 with MPM (label `validation`): the Taylor bar of Ma 2005, §2.3.2 from
// examples/taylor_bar/mpm.toml — OFHC copper at 190 m/s on a rigid wall, quarter model,
// 8 particles per cell, to 72 us. Prints the row: L, D, W, mean error (eq 2-42), steps and
// wall time, beside the experiment and the MPM3D row of Ma 2005.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/reference_checks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::mpm {
namespace {

// Runs the example with extra [mpm] lines and prints its row beside the experiment's.
core::RunSummary taylor_row(const std::string& method_lines, const char* label) {
  std::ifstream in(std::string(AFEMP_SOURCE_DIR) + "/examples/taylor_bar/mpm.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene_text = text.str();
  const std::string key = "[mpm]\n";
  scene_text.insert(scene_text.find(key) + key.size(), method_lines);
  const core::Scene scene = core::parse_scene(scene_text, "examples/taylor_bar/mpm.toml");
  EXPECT_TRUE(scene.taylor_reference.has_value());
  MpmModel sim(scene);
  const core::RunSummary s = analysis::run(sim, scene, {});
  EXPECT_TRUE(s.taylor.has_value());
  const core::TaylorMeasures& m = *s.taylor;
  std::printf(
      "| method | cell | particles | L | D | W | mean error | energy error | steps | wall s | "
      "threads |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| experiment | | | 16.2 | 13.5 | 10.1 | - | | | | |\n");
  std::printf("| MPM3D (Ma 2005) | | | 16.4 | 13.6 | 9.9 | 0.011 | | 408 | | |\n");
  std::printf(
      "| afemp MPM %s (%s) | %g | %zu | %.2f | %.2f | %.2f | %.4f | %+.2f %% | %ld | %.1f | %d |\n",
      label, core::to_string(scene.mpm.scheme), scene.mpm.grid.cell, s.particles, m.length,
      m.impact_diameter, m.bulge_diameter, s.taylor_error, 100.0 * s.energy_error, s.steps,
      s.wall_seconds, core::thread_count());
  return s;
}

// Reference: experiment L 16.2, D 13.5, W 10.1; pass mark mean error <= 0.03 (VALIDATION
// V2), and the run keeps its energy balance (plastic work is internal energy) within 2 %.
TEST(TaylorBar, MpmMatchesExperimentWithinThreePercentMeanError) {
  const core::RunSummary s = taylor_row("", "linear hat, FLIP");
  EXPECT_LE(s.taylor_error, 0.03);
  EXPECT_LT(s.max_energy_error, 0.02);
}

// The same with uGIMP weights, with FLIP and with the affine transfer (measured on the
// development machine, 2 threads: mean error 0.0195 and 0.0152, energy -0.8 % and -3.2 %).
// The affine transfer damps the particles' velocity noise, and that energy is lost, never
// gained: its balance is held to a 5 % loss and +0.5 %.
TEST(TaylorBar, MpmWithGimpMatchesExperimentWithinThreePercentMeanError) {
  const core::RunSummary flip = taylor_row("shape_function = \"gimp\"\n", "uGIMP, FLIP");
  EXPECT_LE(flip.taylor_error, 0.03);
  EXPECT_LT(flip.max_energy_error, 0.02);
  const core::RunSummary apic =
      taylor_row("shape_function = \"gimp\"\ntransfer = \"apic\"\n", "uGIMP, APIC");
  EXPECT_LE(apic.taylor_error, 0.03);
  EXPECT_LT(apic.energy_error, 0.005);
  EXPECT_GT(apic.energy_error, -0.05);
}

}  // namespace
}  // namespace afemp::mpm
