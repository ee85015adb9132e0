// The FE step plan (fem/fe_step_plan.cpp): the stages one explicit FE step runs for a scene,
// built once, timed exactly and printed by `afemp check`. References: the stage order of
// FeSolver::begin_step / finish_step (nodal update, rigid walls, hexahedra, trusses, erosion;
// conversion where the coupled step takes the particles), and each stage only where the scene
// asks for it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/scene.hpp"
#include "fem/fe_model.hpp"
#include "fem/fe_step_plan.hpp"
#include "mpm/test_support.hpp"

namespace afemp::fem {
namespace {

using Names = std::vector<std::string>;

const std::string steel = R"([materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "j2", yield = 300 }
)";

// (A) a block held on one face: hexahedra only, no wall, no gravity.
const std::string block = "[run]\nend_time = 1.0\n" + steel + R"([[bodies]]
name = "block"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 2] } }
mesh = { size = 0.5 }
velocity = [0, 0, -10]
[[constraints]]
nodes = { plane = { point = [0, 0, 2], normal = [0, 0, 1] } }
fixed = ["all"]
)";

// (B) a fully integrated block with erosion falling on a wall under gravity, beside a truss.
const std::string block_wall_truss =
    "[run]\nend_time = 1.0\ngravity = [0, 0, -9.81e-3]\n" + steel + R"([[bodies]]
name = "block"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0.1], max = [1, 1, 2] } }
mesh = { size = 0.5 }
element = "full"
erosion = { plastic_strain = 0.5 }
velocity = [0, 0, -10]
[[bodies]]
name = "rod"
discretisation = "trusses"
material = "steel"
shape = { line = { from = [3, 0, 0.1], to = [3, 0, 2] } }
mesh = { size = 0.5 }
area = 0.1
velocity = [0, 0, -10]
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
)";

// (C) a block whose hexahedra convert into particles inside a grid.
const std::string converting = "[run]\nend_time = 1.0\n" + steel + R"([grid]
cell = 0.5
min = [-1, -1, -1]
max = [2, 2, 3]
[[bodies]]
name = "block"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 2] } }
mesh = { size = 0.5 }
hourglass = { form = "assumed_strain", coefficient = 1 }
conversion = { plastic_strain = 0.2 }
velocity = [0, 0, -10]
)";

FeStepPlan plan_of(const std::string& text) {
  const core::Scene scene = core::parse_scene(text, "plan.toml");
  return FeSolver(scene).plan();
}

// Reference: only the nodal update and the hexahedra; the held face's nodes are the imposed
// velocity components the nodal update sets (3 x 3 nodes on z = 2), and the reason names the
// one-point element, its hourglass form and the default bulk viscosity.
TEST(FeStepPlan, HeldBlockRunsTheNodalUpdateAndTheHexahedra) {
  const FeStepPlan plan = plan_of(block);
  EXPECT_EQ(plan.stage_names(), (Names{"nodal update", "hexahedra"}));
  ASSERT_EQ(plan.stages.size(), 2u);
  EXPECT_EQ(plan.stages[0].kind, FeStageKind::nodal_update);
  EXPECT_EQ(plan.stages[1].kind, FeStageKind::hexahedra);
  EXPECT_NE(plan.stages[0].why.find("imposed velocity components on 9 nodes"), std::string::npos)
      << plan.stages[0].why;
  EXPECT_EQ(plan.stages[0].why.find("gravity"), std::string::npos) << plan.stages[0].why;
  EXPECT_NE(plan.stages[1].why.find("block: one-point, viscous hourglass control Q_hg = 0.1, "
                                    "bulk viscosity linear 0.06, quadratic 1.5"),
            std::string::npos)
      << plan.stages[1].why;
  EXPECT_EQ(plan.index(FeStageKind::rigid_walls), -1);
  EXPECT_EQ(plan.index(FeStageKind::hexahedra), 1);
}

// Reference: every stage of a pure FE step, in the order FeSolver runs them: gravity in the
// nodal update, the wall, the B-bar hexahedra, the trusses, the erosion of the block.
TEST(FeStepPlan, WallTrussGravityAndErosionAddTheirStagesInStepOrder) {
  const FeStepPlan plan = plan_of(block_wall_truss);
  EXPECT_EQ(plan.stage_names(),
            (Names{"nodal update", "rigid walls", "hexahedra", "trusses", "erosion"}));
  EXPECT_NE(plan.stages[0].why.find("gravity m g"), std::string::npos) << plan.stages[0].why;
  EXPECT_EQ(plan.stages[0].why.find("imposed"), std::string::npos) << plan.stages[0].why;
  EXPECT_NE(plan.stages[2].why.find("block: fully integrated (2x2x2) with B-bar"),
            std::string::npos)
      << plan.stages[2].why;
  EXPECT_NE(plan.stages[4].why.find("block: plastic strain 0.5"), std::string::npos)
      << plan.stages[4].why;
  EXPECT_EQ(plan.stages[4].why.find("rod"), std::string::npos) << "the rod does not erode";
  // Eroding at material failure, the plan names the material's failure model (trusses take
  // none: the rod is made of a wire without one).
  std::string jc = block_wall_truss;
  jc.replace(jc.find("erosion = { plastic_strain = 0.5 }"),
             std::string("erosion = { plastic_strain = 0.5 }").size(),
             "erosion = { material_failure = true }");
  jc.replace(jc.find("[[bodies]]"), 0,
             "failure = { model = \"johnson-cook\", D1 = 0.05, D2 = 3.44, D3 = -2.12 }\n"
             "[materials.wire]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n");
  const std::string rod = "discretisation = \"trusses\"\nmaterial = \"steel\"";
  jc.replace(jc.find(rod), rod.size(), "discretisation = \"trusses\"\nmaterial = \"wire\"");
  const FeStepPlan failing = plan_of(jc);
  EXPECT_NE(
      failing.stages[4].why.find(
          "block: material failure (Johnson-Cook damage, D1 .. D5 = 0.05, 3.44, -2.12, 0, 0)"),
      std::string::npos)
      << failing.stages[4].why;
  // Each stage names its bodies' material models, the failure model included (issue 46).
  EXPECT_NE(failing.stages[2].why.find(", material steel (strength j2, EOS none, failure "
                                       "Johnson-Cook damage, D1 .. D5 = 0.05, 3.44, -2.12, 0, 0)"),
            std::string::npos)
      << failing.stages[2].why;
  EXPECT_NE(
      failing.stages[3].why.find("rod: material wire (strength elastic, EOS none, failure none)"),
      std::string::npos)
      << failing.stages[3].why;
}

// Reference: conversion comes last (the coupled step takes the particles after the FE step),
// with its criterion and the particles an element becomes.
TEST(FeStepPlan, ConvertingBodyAddsTheConversionStage) {
  const FeStepPlan plan = plan_of(converting);
  EXPECT_EQ(plan.stage_names(), (Names{"nodal update", "hexahedra", "conversion"}));
  EXPECT_NE(plan.stages[1].why.find("block: one-point, assumed-strain"), std::string::npos)
      << plan.stages[1].why;
  EXPECT_NE(plan.stages[2].why.find("block: 1 particle per element when plastic strain >= 0.2"),
            std::string::npos)
      << plan.stages[2].why;
}

// Reference: a run times exactly the planned stages, in plan order, once per step.
TEST(FeStepPlan, RunRecordsTimingsForExactlyThePlannedStages) {
  for (const std::string* text : {&block, &block_wall_truss, &converting}) {
    const core::Scene scene = core::parse_scene(*text, "plan.toml");
    FeModel model(scene);
    const long steps = 5;
    for (long k = 0; k < steps; ++k) model.step(model.stable_time_step());
    const std::vector<core::StageTiming> timings = model.stage_timings();
    const Names planned = model.solver().plan().stage_names();
    Names timed;
    for (const core::StageTiming& t : timings) {
      timed.push_back(t.name);
      EXPECT_EQ(t.count, steps) << t.name;
      EXPECT_GE(t.seconds, 0.0) << t.name;
    }
    EXPECT_EQ(timed, planned);
  }
}

// Reference: `afemp check` prints the plan the solver runs, verbatim, for an FE scene and for
// the FE part of a coupled one.
TEST(FeStepPlan, AfempCheckPrintsThePlanTheSolverRuns) {
  mpm::test::ScratchDir dir;
  for (const char* example : {"elastic_bar/fe.toml", "taylor_bar/afemp.toml"}) {
    SCOPED_TRACE(example);
    const std::string path = std::string(AFEMP_SOURCE_DIR) + "/examples/" + example;
    const mpm::test::CommandResult r = mpm::test::run_afemp("check \"" + path + "\"", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const core::Scene scene = core::read_scene(path);
    const std::string described = FeSolver(scene).plan().describe();
    EXPECT_NE(r.out.find(described), std::string::npos) << "printed:\n"
                                                        << r.out << "\nplan:\n"
                                                        << described;
  }
}

}  // namespace
}  // namespace afemp::fem
