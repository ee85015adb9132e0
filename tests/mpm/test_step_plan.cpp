// The step plan (Ma 2005, §2.2.4): the list of stages a scene needs, built once and executed
// exactly. References: the stage lists of mpm/step_plan.cpp for each update order
// (Lian et al. 2013, eqs 25-27), the material composition each scene asks for, and the `afemp
// check` printout, which must be the plan the solver runs.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "mpm/step_plan.hpp"
#include "test_support.hpp"

namespace afemp::mpm {
namespace {

using Names = std::vector<std::string>;

// (A) elastic steel, no EOS, no gravity, USL.
const std::string scene_a =
    "[run]\nend_time = 1.0\n"
    "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [8, 8, 8]\n"
    "[mpm]\nscheme = \"USL\"\n"
    "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
    "[[bodies]]\nname = \"block\"\nmaterial = \"steel\"\nparticles_per_cell = 2\n"
    "velocity = [0, 0, -10]\n"
    "shape = { box = { min = [2, 2, 2], max = [5, 5, 5] } }\n";

// (B) Johnson-Cook copper with thermal softening (m > 0, melt temperature) and adiabatic
// heating (specific_heat > 0), Mie-Grueneisen EOS, gravity, MUSL; plus a material no body
// uses, which the plan must leave out.
const std::string scene_b =
    "[run]\nend_time = 1.0\ngravity = [0, 0, -9.81e-3]\n"
    "[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [8, 8, 8]\n"
    "[mpm]\nscheme = \"MUSL\"\n"
    "[materials.spare]\ndensity = 2.7e-3\nE = 70e3\nnu = 0.33\n"
    "[materials.copper]\ndensity = 8.93e-3\nE = 117e3\nnu = 0.35\nspecific_heat = 383\n"
    "strength = { model = \"johnson-cook\", A = 90, B = 292, n = 0.31, C = 0.025, m = 1.09, "
    "melt_temperature = 1356 }\n"
    "eos = { model = \"mie-gruneisen\", c0 = 3940, s = 1.49, gamma0 = 2.02 }\n"
    "[[bodies]]\nname = \"slug\"\nmaterial = \"copper\"\nparticles_per_cell = 2\n"
    "velocity = [0, 0, -50]\n"
    "shape = { box = { min = [2, 2, 2], max = [5, 5, 5] } }\n";

// Reference: the USL chain of step_plan.cpp (velocity, strain and stress share one sweep
// with the weights of the step's start) and the scene's composition.
TEST(StepPlan, ElasticUslSceneGetsTheUslChainWithoutEosThermalOrGravity) {
  const core::Scene scene = core::parse_scene(scene_a, "a.toml");
  const StepPlan plan = build_step_plan(scene);
  EXPECT_EQ(plan.scheme, core::UpdateScheme::USL);
  EXPECT_EQ(plan.stage_names(), (Names{"bin particles", "p2g mass momentum force",
                                       "grid momentum update", "g2p velocity strain stress"}));
  ASSERT_EQ(plan.stages.size(), 4u);
  EXPECT_EQ(plan.stages[1].kind, StageKind::p2g_mass_momentum_force);
  EXPECT_EQ(plan.stages[3].kind, StageKind::g2p_velocity_strain_stress);
  ASSERT_EQ(plan.materials.size(), 1u);
  EXPECT_EQ(plan.materials[0].material, "steel");
  EXPECT_EQ(plan.materials[0].strength, "elastic");
  EXPECT_EQ(plan.materials[0].eos, "none");
  EXPECT_FALSE(plan.materials[0].thermal);
  EXPECT_FALSE(plan.gravity);
  EXPECT_TRUE(plan.jaumann);
  EXPECT_EQ(plan.velocity_fields, 1);
}

// Reference: the MUSL chain (velocity update, remap of the updated particle momentum, then
// the strain from the remapped field) and a thermal Johnson-Cook + Mie-Grueneisen batch.
TEST(StepPlan, JohnsonCookMieGruneisenMuslSceneGetsRemapThermalAndGravity) {
  const core::Scene scene = core::parse_scene(scene_b, "b.toml");
  const StepPlan plan = build_step_plan(scene);
  EXPECT_EQ(plan.scheme, core::UpdateScheme::MUSL);
  EXPECT_EQ(plan.stage_names(),
            (Names{"bin particles", "p2g mass momentum force", "grid momentum update",
                   "g2p velocity", "p2g remap", "strain stress update"}));
  ASSERT_EQ(plan.stages.size(), 6u);
  EXPECT_EQ(plan.stages[3].kind, StageKind::g2p_velocity);
  EXPECT_EQ(plan.stages[4].kind, StageKind::p2g_remap);
  EXPECT_EQ(plan.stages[5].kind, StageKind::strain_stress_update);
  ASSERT_EQ(plan.materials.size(), 1u) << "the unused material must not be planned";
  EXPECT_EQ(plan.materials[0].material, "copper");
  EXPECT_EQ(plan.materials[0].strength, "johnson-cook");
  EXPECT_EQ(plan.materials[0].eos, "mie-gruneisen");
  EXPECT_TRUE(plan.materials[0].thermal);
  EXPECT_TRUE(plan.gravity);
  EXPECT_EQ(plan.velocity_fields, 1);
}

// Reference: the USF chain (stress from the velocity at the start of the step, force after).
TEST(StepPlan, UsfSceneUpdatesStressBeforeTheForce) {
  std::string text = scene_a;
  text.replace(text.find("\"USL\""), 5, "\"USF\"");
  const StepPlan plan = build_step_plan(core::parse_scene(text, "usf.toml"));
  EXPECT_EQ(plan.stage_names(),
            (Names{"bin particles", "p2g mass momentum", "grid velocity", "strain stress update",
                   "p2g force", "grid momentum update", "g2p velocity position"}));
}

// Reference: step() runs each stage of the plan exactly once (stage_counts() == steps for
// every stage), so the run is the plan that was printed.
TEST(StepPlan, SolverRunsEveryPlannedStageOncePerStep) {
  for (const std::string* text : {&scene_a, &scene_b}) {
    const core::Scene scene = core::parse_scene(*text, "plan.toml");
    MpmSolver solver(scene, generate_particles(scene));
    EXPECT_EQ(solver.plan().stage_names(), build_step_plan(scene).stage_names());
    const long steps = 7;
    for (long k = 0; k < steps; ++k) solver.step(solver.stable_time_step());
    EXPECT_EQ(solver.step_count(), steps);
    ASSERT_EQ(solver.stage_counts().size(), solver.plan().stages.size());
    for (std::size_t i = 0; i < solver.stage_counts().size(); ++i)
      EXPECT_EQ(solver.stage_counts()[i], steps) << solver.plan().stages[i].name;
  }
}

// Reference: `afemp check` prints plan.describe() verbatim (same stages, same order, same
// composition) for the scene it read, and says what each scene asked for.
TEST(StepPlan, AfempCheckPrintsThePlanTheSolverRuns) {
  test::ScratchDir dir;
  struct Case {
    const std::string* text;
    const char* file;
    std::vector<std::string> says;
  };
  const Case cases[] = {
      {&scene_a, "a.toml", {"EOS none", "thermal off", "body force: none", "USL"}},
      {&scene_b, "b.toml", {"mie-gruneisen", "thermal on", "body force: gravity", "MUSL"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = dir.write(c.file, *c.text);
    const test::CommandResult r = test::run_afemp("check \"" + path + "\"", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const StepPlan plan = build_step_plan(core::read_scene(path));
    const std::string described = plan.describe();
    EXPECT_NE(r.out.find(described), std::string::npos) << "printed:\n"
                                                        << r.out << "\nplan:\n"
                                                        << described;
    // The stage names appear in plan order.
    std::size_t at = 0;
    for (const auto& name : plan.stage_names()) {
      const std::size_t next = r.out.find(". " + name + "  --", at);
      ASSERT_NE(next, std::string::npos) << name;
      at = next;
    }
    for (const auto& s : c.says) EXPECT_NE(r.out.find(s), std::string::npos) << s;
  }
}

// Reference: `afemp check` names the failure model of each material its particles update
// (issue 46: a Johnson-Cook damage model of particles went unlisted), and the materials of
// mesh bodies, which no particle stage updates, are not listed there.
TEST(StepPlan, AfempCheckListsEachParticleMaterialsFailureModel) {
  std::string text = scene_b;
  text.insert(text.find("eos = "),
              "failure = { model = \"johnson-cook\", D1 = 0.54, D2 = 4.89, D3 = -3.03, "
              "D4 = 0.014, D5 = 1.12, reference_strain_rate = 1e-3 }\n");
  text +=
      "[[bodies]]\nname = \"plate\"\ndiscretisation = \"hexahedra\"\nmaterial = \"spare\"\n"
      "shape = { box = { min = [2, 2, 6], max = [5, 5, 7] } }\nmesh = { size = 1 }\n";
  const std::string plan = build_step_plan(core::parse_scene(text, "b.toml")).describe();
  EXPECT_NE(plan.find("copper: strength johnson-cook, EOS mie-gruneisen, thermal on (plastic "
                      "work heats), failure Johnson-Cook damage, D1 .. D5 = 0.54, 4.89, -3.03, "
                      "0.014, 1.12"),
            std::string::npos)
      << plan;
  EXPECT_EQ(plan.find("spare"), std::string::npos) << plan;
}

}  // namespace
}  // namespace afemp::mpm
