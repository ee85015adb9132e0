// [run] terminate (LS-DYNA's *TERMINATION_BODY): a run stops once a body's centre of mass has
// moved the given distance, checked at each history row.
#include <gtest/gtest.h>

#include <string>

#include "afemp/errors.hpp"
#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "mpm/mpm_model.hpp"
#include "scene_errors.hpp"

namespace afemp::mpm {
namespace {

// A free steel block of particles drifting at 50 m/s (mm/ms) along -z, fixed step 1e-4 ms.
std::string drifting_block(const std::string& terminate) {
  return "[run]\nend_time = 1.0\ntime_step = 1e-4\nhistory_every = 3\n" + terminate +
         "[grid]\ncell = 1.0\nmin = [0, 0, -2]\nmax = [6, 6, 8]\n"
         "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
         "[[bodies]]\nname = \"block\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
         "velocity = [0, 0, -50]\n"
         "shape = { box = { min = [1, 1, 1], max = [5, 5, 5] } }\n";
}

TEST(Terminate, RunStopsAtTheFirstHistoryRowPastTheTravel) {
  // Reference: a free body in uniform translation moves v t exactly, so with travel 0.1 the
  // distance is reached at t = 0.1 / 50 = 0.002 (step 20); rows come every 3 steps, so the run
  // stops at step 21, t = 0.0021 (1e-12), and says why. Without terminate it runs to 1.0.
  const core::Scene scene = core::parse_scene(
      drifting_block("terminate = { body = \"block\", travel = 0.1 }\n"), "t.toml");
  ASSERT_TRUE(scene.run.terminate.has_value());
  MpmModel sim(scene);
  const core::RunSummary s = analysis::run(sim, scene, {});
  EXPECT_EQ(s.steps, 21);
  EXPECT_NEAR(s.time, 0.0021, 1e-12);
  EXPECT_NE(s.terminated.find("body 'block' travelled 0.105"), std::string::npos) << s.terminated;
  const core::Scene plain = core::parse_scene(drifting_block(""), "t.toml");
  core::Scene short_run = plain;
  short_run.run.end_time = 0.005;
  MpmModel free_run(short_run);
  const core::RunSummary f = analysis::run(free_run, short_run, {});
  EXPECT_EQ(f.steps, 50);
  EXPECT_TRUE(f.terminated.empty());
}

TEST(Terminate, KeysNameTheBodyAndTheDistance) {
  std::string e = test::error_of(drifting_block("terminate = { body = \"blok\", travel = 1 }\n"));
  EXPECT_NE(e.find("run.terminate.body"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown body \"blok\""), std::string::npos) << e;
  e = test::error_of(drifting_block("terminate = { body = \"block\", travel = 0 }\n"));
  EXPECT_NE(e.find("run.terminate.travel"), std::string::npos) << e;
  e = test::error_of(drifting_block("terminate = { body = \"block\" }\n"));
  EXPECT_NE(e.find("run.terminate.travel"), std::string::npos) << e;
}

}  // namespace
}  // namespace afemp::mpm
