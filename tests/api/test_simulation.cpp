// The library API (include/afemp/simulation.hpp) against the scene file it stands beside.
// References: a scene built in code must give the model the scene file gives (same step plan,
// bit-identical history: the two are one model); a program's nodal load F on a free body gives
// it the momentum F t (Newton's second law) and its work enters the energy balance; bad input
// throws InputError naming the object and the field, and the library prints nothing.
#include <gtest/gtest.h>

#include <afemp/afemp.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "scratch_dir.hpp"
#include "taylor_bar_scene.hpp"

namespace {

using afemp::Vec3;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string taylor_toml(bool hexahedra) {
  return afemp::test::taylor_bar_scene(hexahedra);
}

// The same bar, built in code.
afemp::Scene taylor_in_code(bool hexahedra) {
  afemp::Scene s;
  s.run.end_time = 0.01;
  afemp::Material copper;
  copper.name = "copper";
  copper.density = 8.93e-3;
  copper.youngs_modulus = 117e3;
  copper.poisson_ratio = 0.35;
  copper.strength = afemp::JohnsonCook{.A = 157, .B = 425, .n = 1.0, .C = 0.0};
  s.materials.push_back(copper);
  afemp::BodySpec bar;
  bar.name = "bar";
  bar.material = 0;
  bar.shape =
      afemp::CylinderShape{.base = {0, 0, 0}, .axis = {0, 0, 1}, .radius = 3.8, .length = 25.4};
  bar.velocity = {0, 0, -190};
  if (hexahedra) {
    bar.discretisation = afemp::Discretisation::hexahedra;
    bar.mesh.size = 1.0;
    bar.mesh.sectors = 1;
    for (int axis = 0; axis < 2; ++axis) {
      afemp::ConstraintSpec c;
      c.nodes.kind = afemp::NodeSelector::Kind::plane;
      c.nodes.normal[axis] = 1.0;
      c.components[static_cast<std::size_t>(axis)] = true;
      s.constraints.push_back(c);
    }
    afemp::WallSpec wall;
    wall.normal = {0, 0, 1};
    s.walls.push_back(wall);
  } else {
    s.has_grid = true;
    s.mpm.grid.cell = 1.0;
    s.mpm.grid.max = {10, 10, 26};
    s.mpm.grid.faces = {afemp::FaceCondition::symmetric, afemp::FaceCondition::free,
                        afemp::FaceCondition::symmetric, afemp::FaceCondition::free,
                        afemp::FaceCondition::wall,      afemp::FaceCondition::free};
  }
  s.bodies.push_back(bar);
  return s;
}

struct Trace {
  std::string plan;
  std::vector<double> kinetic, internal, plastic;
  std::vector<Vec3> final_positions;
};

Trace trace(afemp::Scene scene) {
  afemp::Simulation sim(std::move(scene));
  Trace t;
  t.plan = sim.describe();
  sim.on_step([&](afemp::Simulation& s) {
    const afemp::Energies e = s.energies();
    t.kinetic.push_back(e.kinetic);
    t.internal.push_back(e.internal);
    t.plastic.push_back(e.plastic);
  });
  sim.run();
  if (!sim.particles().position.empty()) {
    const auto x = sim.particles().position;
    t.final_positions.assign(x.begin(), x.end());
  } else {
    const auto x = sim.nodes().position;
    t.final_positions.assign(x.begin(), x.end());
  }
  return t;
}

void expect_same(const Trace& code, const Trace& file) {
  EXPECT_EQ(code.plan, file.plan);
  ASSERT_EQ(code.kinetic.size(), file.kinetic.size());
  ASSERT_GT(code.kinetic.size(), 10u);
  for (std::size_t k = 0; k < code.kinetic.size(); ++k) {
    ASSERT_EQ(code.kinetic[k], file.kinetic[k]) << "step " << k + 1;
    ASSERT_EQ(code.internal[k], file.internal[k]) << "step " << k + 1;
    ASSERT_EQ(code.plastic[k], file.plastic[k]) << "step " << k + 1;
  }
  ASSERT_EQ(code.final_positions.size(), file.final_positions.size());
  for (std::size_t i = 0; i < code.final_positions.size(); ++i)
    ASSERT_EQ(afemp::norm(code.final_positions[i] - file.final_positions[i]), 0.0) << "point " << i;
  // The bar hits the wall: plastic work is done (a run that did nothing would match too).
  EXPECT_GT(file.plastic.back(), 0.01 * file.kinetic.front());
}

}  // namespace

TEST(SimulationApi, ParticleTaylorBarBuiltInCodeIsTheSceneFilesModel) {
  expect_same(trace(taylor_in_code(false)),
              trace(afemp::core::parse_scene(taylor_toml(false), "taylor_mpm.toml")));
}

TEST(SimulationApi, HexahedronTaylorBarBuiltInCodeIsTheSceneFilesModel) {
  expect_same(trace(taylor_in_code(true)),
              trace(afemp::core::parse_scene(taylor_toml(true), "taylor_fe.toml")));
}

// A free elastic block of hexahedra, pulled by a program's load F (total, spread over the
// nodes of its +x face) from rest: its momentum is F t (to within the half step at which
// central differences hold velocities), and the load's work balances the energy.
TEST(SimulationApi, ProgramNodalLoadGivesMomentumFtAndIsBookedAsExternalWork) {
  afemp::Scene s;
  s.run.end_time = 0.01;
  afemp::Material steel;
  steel.name = "steel";
  steel.density = 7.85e-3;
  steel.youngs_modulus = 200e3;
  steel.poisson_ratio = 0.3;
  s.materials.push_back(steel);
  afemp::BodySpec block;
  block.name = "block";
  block.material = 0;
  block.discretisation = afemp::Discretisation::hexahedra;
  block.shape = afemp::BoxShape{{0, 0, 0}, {4, 2, 2}};
  block.mesh.divisions = {4, 2, 2};
  s.bodies.push_back(block);
  afemp::Simulation sim(s);
  const double force = 100.0;  // N
  afemp::NodeFields nodes = sim.nodes();
  std::size_t loaded = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) loaded += nodes.position[i].x > 4.0 - 1e-9;
  ASSERT_EQ(loaded, 9u);  // a 3 x 3 node face
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.position[i].x > 4.0 - 1e-9) nodes.external_force[i] = {force / 9.0, 0, 0};
  const double dt = sim.stable_time_step();
  const afemp::RunSummary r = sim.run();
  const double px = r.final.bodies[0].momentum.x;
  EXPECT_NEAR(px, force * r.time, force * dt) << "p = F t";
  EXPECT_NEAR(r.final.bodies[0].momentum.y, 0.0, 1e-12 * force * r.time);
  EXPECT_GT(r.final.external_work, 0.0);
  EXPECT_LT(std::abs(r.energy_error), 0.01) << "the load's work enters the balance";
  const std::vector<Vec3> f = sim.node_forces();
  Vec3 total;
  for (const Vec3& fi : f) total += fi;
  EXPECT_NEAR(afemp::norm(total), 0.0, 1e-9 * force) << "internal forces sum to zero";
}

// The callbacks run once per step, in the order added, and see the state after the step.
TEST(SimulationApi, StepCallbacksRunAfterEveryStepInOrder) {
  afemp::Simulation sim(afemp::core::parse_scene(taylor_toml(false), "taylor_mpm.toml"));
  std::vector<int> order;
  long calls = 0;
  sim.on_step([&](afemp::Simulation& s) {
    order.push_back(1);
    ++calls;
    EXPECT_EQ(s.step_count(), calls);
  });
  sim.on_step([&](afemp::Simulation&) { order.push_back(2); });
  sim.run_to(0.004);
  EXPECT_NEAR(sim.time(), 0.004, 1e-12);
  EXPECT_FALSE(sim.finished());
  const afemp::RunSummary r = sim.run();
  EXPECT_EQ(calls, r.steps);
  ASSERT_EQ(order.size(), static_cast<std::size_t>(2 * calls));
  for (std::size_t k = 0; k < order.size(); ++k) EXPECT_EQ(order[k], k % 2 == 0 ? 1 : 2);
  EXPECT_NEAR(r.time, 0.01, 1e-12);
}

// Reference: determinism (docs/restart.md). A program's run checkpointed after 60 steps and
// continued by a second Simulation from that checkpoint ends with the uninterrupted run's
// particles, bit for bit, and the same step count. (Steps, not run_to: run_to cuts its last
// step to land on the time asked, which the uninterrupted run does not.)
TEST(SimulationApi, ARunContinuedFromItsCheckpointEndsAsTheUninterruptedOne) {
  afemp::test::ScratchDir dir;
  const afemp::Scene scene = afemp::core::parse_scene(taylor_toml(false), "taylor_mpm.toml");
  afemp::Simulation whole(scene);
  const afemp::RunSummary w = whole.run();

  afemp::SimulationOptions first_options;
  first_options.output_directory = dir.file("run");
  std::string checkpoint;
  {
    afemp::Simulation first(scene, first_options);
    for (int k = 0; k < 60; ++k) first.step();
    checkpoint = first.checkpoint();
    EXPECT_EQ(checkpoint, afemp::newest_checkpoint(dir.file("run")));
  }
  afemp::SimulationOptions options = first_options;
  options.restart_from = checkpoint;
  afemp::Simulation second(scene, options);
  EXPECT_EQ(second.step_count(), 60);
  const afemp::RunSummary r = second.run();
  EXPECT_EQ(r.steps, w.steps);
  const afemp::ParticleFields a = whole.particles(), b = second.particles();
  ASSERT_EQ(a.position.size(), b.position.size());
  for (std::size_t i = 0; i < a.position.size(); ++i) {
    ASSERT_EQ(a.position[i].x, b.position[i].x) << i;
    ASSERT_EQ(a.position[i].z, b.position[i].z) << i;
    ASSERT_EQ(a.stress[i].zz, b.stress[i].zz) << i;
  }
}

// Reference: determinism (docs/restart.md), as `afemp run` meets it on SIGINT and --restart. A
// run that stop_requested ends after 40 steps writes a checkpoint of step 40 and its final row;
// restart_checkpoint finds that checkpoint for the same scene and refuses a changed one (naming
// the key) before anything is built; a deferred Simulation takes no step before start(), and
// the continued run ends with the uninterrupted run's steps and history rows, bit for bit.
TEST(SimulationApi, ARunStoppedOnRequestContinuesFromItsDirectoryAsIfNeverStopped) {
  afemp::test::ScratchDir dir;
  const afemp::Scene scene = afemp::core::parse_scene(taylor_toml(false), "taylor_mpm.toml");
  afemp::SimulationOptions whole_options;
  whole_options.output_directory = dir.file("whole");
  afemp::Simulation whole(scene, whole_options);
  const afemp::RunSummary w = whole.run();

  const std::string run_dir = dir.file("stopped");
  afemp::SimulationOptions options;
  options.output_directory = run_dir;
  int asked = 0;
  options.stop_requested = [&] { return ++asked > 40; };
  {
    afemp::Simulation first(scene, options);
    const afemp::RunSummary s = first.run();
    EXPECT_TRUE(s.interrupted);
    EXPECT_EQ(s.steps, 40);
    EXPECT_EQ(s.checkpoint, afemp::newest_checkpoint(run_dir)) << s.checkpoint_error;
    const afemp::CheckpointInfo info = afemp::read_checkpoint_info(s.checkpoint);
    EXPECT_EQ(info.step, 40);
    EXPECT_EQ(info.reason, "stopped");
  }

  const afemp::Scene changed = afemp::core::parse_scene(
      afemp::test::taylor_bar_scene(false, R"(strength = { model = "johnson-cook", A = 160, )"
                                           R"(B = 425, n = 1.0, C = 0.0 })"),
      "taylor_mpm.toml");
  try {
    afemp::restart_checkpoint(run_dir, changed);
    ADD_FAILURE() << "a changed scene continued";
  } catch (const afemp::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("materials.copper.strength.A"), std::string::npos)
        << e.what();
  }

  options.stop_requested = nullptr;
  options.restart_from = afemp::restart_checkpoint(run_dir, scene);
  options.defer_start = true;
  afemp::Simulation second(scene, options);
  EXPECT_THROW(second.step(), std::logic_error);
  second.start();
  EXPECT_EQ(second.step_count(), 40);
  const afemp::RunSummary r = second.run();
  EXPECT_FALSE(r.interrupted);
  EXPECT_EQ(r.restarted_at, 40);
  EXPECT_EQ(r.steps, w.steps);
  EXPECT_EQ(slurp(run_dir + "/history.csv"), slurp(dir.file("whole") + "/history.csv"));
}

// Bad input through the API: InputError naming the object and field by the scene file's key and
// what is allowed; nothing printed.
TEST(SimulationApi, BadInputThrowsNamingObjectFieldAndWhatIsAllowed) {
  struct Case {
    const char* what;
    void (*spoil)(afemp::Scene&);
    const char* key;
    const char* allowed;
  };
  const Case cases[] = {
      {"particles per cell", [](afemp::Scene& s) { s.bodies[0].particles_per_cell = 0; },
       "bodies.bar.particles_per_cell", "allowed: 1 <= value <= 8"},
      {"Poisson ratio", [](afemp::Scene& s) { s.materials[0].poisson_ratio = 0.6; },
       "materials.copper.nu", "allowed: 0 <= value < 0.5"},
      {"material index", [](afemp::Scene& s) { s.bodies[0].material = 3; }, "bodies.bar.material",
       "not defined"},
      {"no grid", [](afemp::Scene& s) { s.has_grid = false; }, "grid", "need a grid"},
      {"end time", [](afemp::Scene& s) { s.run.end_time = -1.0; }, "run.end_time",
       "allowed: value > 0"},
      {"contact with itself",
       [](afemp::Scene& s) {
         afemp::ContactSpec c;
         c.bodies = {0, 0};
         s.contacts.push_back(c);
       },
       "contact[0].bodies", "cannot be in grid contact with itself"},
      {"sphere of trusses",
       [](afemp::Scene& s) {
         s.bodies[0].discretisation = afemp::Discretisation::trusses;
         s.bodies[0].shape = afemp::SphereShape{{5, 5, 5}, 2.0};
       },
       "bodies.bar.shape", "particles or hexahedra"},
  };
  for (const Case& c : cases) {
    afemp::Scene s = taylor_in_code(false);
    c.spoil(s);
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    try {
      afemp::Simulation sim(s);
      ADD_FAILURE() << c.what << ": no error";
    } catch (const afemp::InputError& e) {
      EXPECT_EQ(e.key(), c.key) << c.what << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find(c.allowed), std::string::npos)
          << c.what << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find("scene built in code"), std::string::npos) << e.what();
    }
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "") << c.what;
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "") << c.what;
  }
}

// Every example scene passes the API's check as it passes the parser's: the two agree (afemp
// run and check go through Simulation, which checks every scene).
TEST(SimulationApi, ExampleScenesPassTheCodeCheck) {
  int scenes = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::string(AFEMP_SOURCE_DIR) + "/examples")) {
    if (entry.path().extension() != ".toml") continue;
    const afemp::Scene s = afemp::read_scene(entry.path().string());
    EXPECT_NO_THROW(afemp::check_scene(s)) << entry.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 15);
}

// The field views show the model's own state: particle masses add up to the body's mass, and a
// program's change of velocity between steps is the body's momentum (a boundary condition in
// a callback); element views cover every hexahedron, and the bar's impact end has yielded.
TEST(SimulationApi, FieldViewsShowAndChangeTheModelsState) {
  afemp::Simulation particles(taylor_in_code(false));
  afemp::ParticleFields p = particles.particles();
  double mass = 0.0;
  for (double m : p.mass) mass += m;
  const afemp::Energies e0 = particles.energies();
  EXPECT_NEAR(mass, e0.bodies[0].mass, 1e-12 * mass);
  for (Vec3& v : p.velocity) v = {0, 0, -100};  // a program's velocity, before the first step
  EXPECT_NEAR(particles.energies().bodies[0].momentum.z, -100.0 * mass, 1e-9 * mass);
  EXPECT_TRUE(particles.hexahedra().size() == 0);

  afemp::Simulation mesh(taylor_in_code(true));
  mesh.run_to(0.01);
  const afemp::ElementFields h = mesh.hexahedra();
  ASSERT_GT(h.size(), 100u);
  double largest = 0.0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    EXPECT_EQ(h.points_per_element[k], 1);
    EXPECT_EQ(h.body[k], 0);
    largest = std::max(largest, h.plastic_strain[h.first_point[k]]);
  }
  // 190 m/s on copper (rho c_L v = 8.93e-3 * 4760 * 190 = 8.1 GPa >> A = 157 MPa): it yields.
  EXPECT_GT(largest, 0.05);
  EXPECT_TRUE(mesh.particles().position.empty());
}

// With an output directory a Simulation writes the run directory `afemp run` writes: a history
// row every history_every steps plus the first and the last, and a field frame at the start,
// every output_every and at the end (0.01 / 0.004: t = 0, 0.004, 0.008, 0.01).
TEST(SimulationApi, OutputDirectoryGetsTheHistoryAndTheFrames) {
  afemp::test::ScratchDir dir;
  afemp::Scene scene = taylor_in_code(false);
  scene.run.output_every = 0.004;
  afemp::SimulationOptions options;
  options.output_directory = dir.path().string();
  afemp::Simulation sim(scene, options);
  const afemp::RunSummary r = sim.run();
  EXPECT_EQ(r.field_frames, 4u);
  std::ifstream history(dir.path() / "history.csv");
  ASSERT_TRUE(history.good());
  std::size_t lines = 0;
  for (std::string line; std::getline(history, line);) ++lines;
  const long rows =
      r.steps / scene.run.history_every + 1 + (r.steps % scene.run.history_every != 0);
  EXPECT_EQ(lines, static_cast<std::size_t>(rows) + 1) << "rows and the header";
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "fields.xmf"));
}
