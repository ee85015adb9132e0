// The run guard: a simulation that goes bad stops with a core::SimulationError naming the
// step, the particle and the field, and the output written until then stays on disk (the
// history is flushed row by row, the XDMF index is rewritten after every frame).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "afemp/simulation.hpp"
#include "analysis/reference_checks.hpp"
#include "core/output/history.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_model.hpp"
#include "test_support.hpp"

namespace afemp::mpm {
namespace {

// A steel block moving at 50 m/s onto a rigid wall (zmin), MUSL. time_step: fixed, or
// absent (stable step x factor).
std::string wall_scene(const std::string& time_step_line, const std::string& factor_line) {
  return "[run]\nend_time = 5.0\nhistory_every = 1\n" + time_step_line + factor_line +
         "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [6, 6, 8]\n"
         "boundary = { zmin = \"wall\" }\n"
         "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
         "[[bodies]]\nname = \"block\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
         "velocity = [0, 0, -50]\n"
         "shape = { box = { min = [1, 1, 1], max = [5, 5, 5] } }\n";
}

// The scene of wall_scene at 100 times its stable step.
core::Scene unstable_scene() {
  // The stable step of this scene at factor 1.
  const core::Scene probe = core::parse_scene(wall_scene("", "time_step_factor = 1.0\n"), "p.toml");
  const double stable = MpmModel(probe).solver().stable_time_step();
  EXPECT_GT(stable, 0.0);
  char fixed_step[32];
  std::snprintf(fixed_step, sizeof fixed_step, "%.17g", 100.0 * stable);
  const core::Scene scene = core::parse_scene(
      wall_scene(std::string("time_step = ") + fixed_step + "\n", ""), "unstable.toml");
  EXPECT_NEAR(scene.run.fixed_time_step, 100.0 * stable, 1e-6 * stable);
  return scene;
}

// The times of the frames fields.xmf lists, in order.
std::vector<double> frame_times(const std::string& xmf) {
  const std::string index = test::slurp(xmf);
  std::vector<double> times;
  const std::string key = "<Time Value=\"";
  for (std::size_t at = index.find(key); at != std::string::npos; at = index.find(key, at + 1))
    times.push_back(std::strtod(index.c_str() + at + key.size(), nullptr));
  return times;
}

// Reference: explicit time integration is only conditionally stable (dt < h / c); at 100
// times the stable step the impact amplifies every step until a value is NaN/Inf or a
// particle is thrown off the grid. The guard must stop the run with a SimulationError whose
// message names the step ("step N", N >= 1), the particle ("particle ID of body 'block'")
// and the field ("field 'stress'", 'volume' or 'position'), and leave history.csv with at
// least the step-0 row and fields.xmf listing frame 0, and a last frame of the state it stopped
// in: at the model's time then (the start of the step the error names, which did not finish),
// NaN and all.
TEST(Guard, UnstableTimeStepStopsWithStepParticleAndFieldAndKeepsOutput) {
  const core::Scene scene = unstable_scene();
  test::ScratchDir dir;
  const std::string out = dir.file("run");
  MpmModel sim(scene);
  core::RunOptions options;
  options.output_directory = out;
  bool thrown = false;
  try {
    analysis::run(sim, scene, options);
  } catch (const core::SimulationError& e) {
    thrown = true;
    const std::string what = e.what();
    EXPECT_GE(e.step(), 1);
    EXPECT_NE(what.find("step " + std::to_string(e.step())), std::string::npos) << what;
    EXPECT_TRUE(std::regex_search(what, std::regex("particle [0-9]+ of body 'block'"))) << what;
    EXPECT_TRUE(std::regex_search(what, std::regex("field '(stress|volume|position)'"))) << what;
    std::printf("[ guard ] %s\n", what.c_str());
  }
  ASSERT_TRUE(thrown) << "a run at 100x the stable step finished without the guard firing";

  // The output written so far is kept.
  const std::string history = out + "/history.csv";
  ASSERT_TRUE(std::filesystem::exists(history));
  const core::CsvTable table = core::read_csv(history);
  ASSERT_GE(table.rows.size(), 1u);
  EXPECT_EQ(table.rows[0][table.column("step")], 0.0);
  EXPECT_GT(table.rows[0][table.column("kinetic")], 0.0);
  const std::string xmf = out + "/fields.xmf";
  ASSERT_TRUE(std::filesystem::exists(xmf));
  ASSERT_TRUE(std::filesystem::exists(out + "/fields.h5"));
  const std::string index = test::slurp(xmf);
  EXPECT_NE(index.find("frame_000000"), std::string::npos) << index;
  EXPECT_NE(index.find("<Time Value=\"0\""), std::string::npos) << index;
  const std::vector<double> times = frame_times(xmf);
  ASSERT_EQ(times.size(), 2u) << index;
  EXPECT_GT(times[1], 0.0);
  EXPECT_EQ(times[1], sim.solver().time());
}

// Reference: the energy guard ([run] energy_error_limit) stops a run whose balance is off by
// more than the limit at three history rows in a row. A program that sets a block at rest
// moving at 10 m/s after step 3 gives it energy no force supplies (error +100 % from the row of
// step 4): the run stops at step 6 with field 'energy balance', and a last frame at that step's
// end is kept.
TEST(Guard, TheEnergyGuardStopsTheRunAndKeepsAFrameOfItsLastState) {
  test::ScratchDir dir;
  SimulationOptions options;
  options.output_directory = dir.str();
  Simulation sim(core::parse_scene("[run]\nend_time = 1\nhistory_every = 1\n"
                                   "energy_error_limit = 0.01\n"
                                   "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [6, 6, 6]\n"
                                   "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
                                   "[[bodies]]\nname = \"block\"\nmaterial = \"steel\"\n"
                                   "shape = { box = { min = [2, 2, 2], max = [4, 4, 4] } }\n",
                                   "runaway.toml"),
                 options);
  sim.on_step([](Simulation& s) {
    if (s.step_count() == 3)
      for (core::Vec3& v : s.particles().velocity) v = {10.0, 0.0, 0.0};
  });
  try {
    sim.run();
    FAIL() << "the energy guard did not stop the run";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    std::printf("[ guard ] %s\n", what.c_str());
    EXPECT_EQ(e.step(), 6);
    EXPECT_NE(what.find("field 'energy balance'"), std::string::npos) << what;
    EXPECT_NE(what.find("body block"), std::string::npos) << what;
  }
  const std::vector<double> times = frame_times(dir.file("fields.xmf"));
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[1], sim.time());
  EXPECT_EQ(sim.step_count(), 6);
}

// Reference: a body moving at 500 m/s toward the free face z = 4 of a 4-cell grid: its top
// particles (z = 2.75) reach the face after (4 - 2.75) / 500 = 2.5 us, about 53 steps of
// 0.3 h / (c + 500) = 4.7e-5 ms: the particle that crosses the face must stop the run with
// field 'position' and "left the grid", not be lost silently.
TEST(Guard, ParticleLeavingTheGridStopsTheRunWithFieldPosition) {
  const core::Scene scene = core::parse_scene(
      "[run]\nend_time = 1.0\n"
      "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [4, 4, 4]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
      "[[bodies]]\nname = \"runaway\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
      "velocity = [0, 0, 500]\n"
      "shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }\n",
      "leave.toml");
  MpmModel sim(scene);
  try {
    analysis::run(sim, scene, core::RunOptions{});
    FAIL() << "the body left the grid without an error";
  } catch (const core::SimulationError& e) {
    const std::string what = e.what();
    std::printf("[ guard ] %s\n", what.c_str());
    EXPECT_NE(what.find("field 'position'"), std::string::npos) << what;
    EXPECT_NE(what.find("left the grid"), std::string::npos) << what;
    EXPECT_TRUE(std::regex_search(what, std::regex("particle [0-9]+ of body 'runaway'"))) << what;
    // It stopped at the step the particle crossed: the time is within a step of 2.5 us.
    EXPECT_NEAR(sim.solver().time(), (4.0 - 2.75) / 500.0, 1.5 * sim.solver().stable_time_step());
    EXPECT_GE(e.step(), 45);
    EXPECT_LE(e.step(), 60);
  }
}

}  // namespace
}  // namespace afemp::mpm
