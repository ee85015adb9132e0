// V2 with FE (label `validation`): the Taylor bar of Ma 2005, §2.3.2 from
// examples/taylor_bar/fe.toml — OFHC copper at 190 m/s on a rigid frictionless wall, quarter
// model of 0.25 mm hexahedra (the MPM scene's particle spacing), to 72 us. Prints the row: L, D,
// W, mean error (eq 2-42), steps, smallest and largest time step and wall time, for one-point
// hexahedra (viscous and stiffness hourglass control) and for 2x2x2 B-bar hexahedra. Measured
// (34,272 hexahedra, 38,007 nodes; 2 threads on a shared 2-core machine, so wall times are
// rough):
//   | one-point, viscous 0.1     | L 16.30 | D 13.48 | W 10.14 | 0.0038 | 7259 steps | 178 s |
//   | one-point, stiffness 0.05  | L 16.18 | D 12.75 | W 10.16 | 0.0209 | 6248 steps | 161 s |
//   | one-point, stiffness 0.1   | L 16.04 | D 12.31 | W 10.14 | 0.0339 | 5098 steps |  56 s |
//   | 2x2x2 B-bar                | L 16.30 | D 13.54 | W 10.14 | 0.0044 | 7177 steps | 382 s |
// The stiffness form keeps its hourglass forces elastic while the lip flows plastically, so it
// stiffens the mushroom (smaller D) the more the higher its coefficient.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/reference_checks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/fe_model.hpp"

namespace afemp::fem {
namespace {

// The example with `extra` keys added to its body table.
core::Scene taylor_bar(const std::string& extra) {
  const std::string path = std::string(AFEMP_SOURCE_DIR) + "/examples/taylor_bar/fe.toml";
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string anchor = "velocity = [0, 0, -190]\n";
  const auto at = text.find(anchor);
  EXPECT_NE(at, std::string::npos);
  text.insert(at + anchor.size(), extra);
  return core::parse_scene(text, path);
}

core::RunSummary run_row(const std::string& label, const std::string& extra) {
  const core::Scene scene = taylor_bar(extra);
  FeModel model(scene);
  const core::RunSummary s = analysis::run(model, scene, {});
  const core::TaylorMeasures& m = s.taylor.value();
  std::printf(
      "| afemp FE %s | %zu | %zu | %.2f | %.2f | %.2f | %.4f | %ld | %.3g | %.3g | %.1f | "
      "%.2f %% | %.1f %% | %d |\n",
      label.c_str(), s.elements, model.solver().nodes().size(), m.length, m.impact_diameter,
      m.bulge_diameter, s.taylor_error, s.steps, s.min_dt, s.max_dt, s.wall_seconds,
      100.0 * s.max_energy_error, 100.0 * s.final.hourglass / s.final.internal,
      core::thread_count());
  std::fflush(stdout);
  return s;
}

void print_header() {
  std::printf(
      "| method | elements | nodes | L | D | W | mean error | steps | min dt | max dt | "
      "wall s | max energy error | hourglass / internal | threads |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| experiment | | | 16.2 | 13.5 | 10.1 | - | | | | | | | |\n");
  std::printf("| MPM3D (Ma 2005) | | | 16.4 | 13.6 | 9.9 | 0.011 | 408 | | | | | | |\n");
}

// Reference: experiment L 16.2, D 13.5, W 10.1; pass mark mean error <= 0.03 (VALIDATION V2).
// The energy balance (plastic work and bulk-viscous heating are internal energy, the
// hourglass work is booked) closes within 2 %.
TEST(TaylorBar, OnePointHexahedraMatchExperimentWithinThreePercentMeanError) {
  print_header();
  const core::RunSummary s = run_row("one-point, viscous hourglass", "");
  EXPECT_LE(s.taylor_error, 0.03);
  EXPECT_LT(s.max_energy_error, 0.02);
}

// The stiffness form at 0.05, its default coefficient (fem/hourglass.hpp): the same pass mark. At
// 0.1 it is reported, and a stiffer hourglass must resist the lip of the mushroom more: D at 0.1 <=
// D at 0.05.
TEST(TaylorBar, StiffnessHourglassMatchesExperimentWithinThreePercentMeanError) {
  print_header();
  const core::RunSummary s = run_row("one-point, stiffness hourglass 0.05",
                                     "hourglass = { form = \"stiffness\", coefficient = 0.05 }\n");
  EXPECT_LE(s.taylor_error, 0.03);
  EXPECT_LT(s.max_energy_error, 0.02);
  const core::RunSummary stiffer =
      run_row("one-point, stiffness hourglass 0.1", "hourglass = { form = \"stiffness\" }\n");
  EXPECT_LE(stiffer.taylor->impact_diameter, s.taylor->impact_diameter);
  EXPECT_LT(stiffer.max_energy_error, 0.02);
}

TEST(TaylorBar, FullyIntegratedHexahedraMatchExperimentWithinThreePercentMeanError) {
  print_header();
  const core::RunSummary s = run_row("2x2x2 B-bar", "element = \"full\"\n");
  EXPECT_LE(s.taylor_error, 0.03);
  EXPECT_LT(s.max_energy_error, 0.02);
}

}  // namespace
}  // namespace afemp::fem
