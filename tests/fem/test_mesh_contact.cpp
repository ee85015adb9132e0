// Contact between meshes and rigid bodies (fem/mesh_contact.cpp, fem/rigid_body.cpp). Units mm,
// ms, g, N, MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "fem/fe_model.hpp"
#include "fem/fe_solver.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp::fem {
namespace {

// Elastic steel: rho 7.85e-3, E 2.1e5, nu 0.3 (c_L = 6001 m/s in uniaxial strain).
constexpr const char* kSteel = "[materials.steel]\ndensity = 7.85e-3\nE = 2.1e5\nnu = 0.3\n";

double steel_bar_wave_speed() {
  const double E = 2.1e5, nu = 0.3, rho = 7.85e-3;
  return std::sqrt(E * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho));
}

// Two identical elastic steel blocks, 2 x 2 x 10 mm (2 x 2 x 40 hexahedra), every node held
// across (uniaxial strain), 0.1 mm apart, meeting head-on at 5 m/s each. No bulk viscosity: the
// 1-D answer has none.
std::string head_on_scene() {
  std::string s = "[run]\nend_time = 0.02\n";
  s += kSteel;
  for (const char* side : {"left", "right"}) {
    const bool left = side[0] == 'l';
    char body[512];
    std::snprintf(
        body, sizeof body,
        "[[bodies]]\nname = \"%s\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
        "shape = { box = { min = [0, 0, %g], max = [2, 2, %g] } }\n"
        "mesh = { divisions = [2, 2, 40] }\nvelocity = [0, 0, %g]\n"
        "bulk_viscosity = { linear = 0, quadratic = 0 }\n",
        side, left ? -10.05 : 0.05, left ? -0.05 : 10.05, left ? 5.0 : -5.0);
    s += body;
  }
  s += "[[constraints]]\nnodes = { box = { min = [-1, -1, -20], max = [3, 3, 20] } }\n"
       "fixed = [\"x\", \"y\"]\n[[contact]]\nbodies = [\"left\", \"right\"]\n";
  return s;
}

// Reference: two identical elastic bars meeting head-on stay in contact for 2 L / c (the
// compression wave's return trip) and separate with their speeds exchanged, momentum zero
// throughout. Pass: momentum within 1e-12 of one block's, contact time within 5 % of 2 L / c,
// kinetic + internal energy after separation within 2 % of the start (the node pairs of the
// first contact meet plastically: a loss of the order of the interface layer's share of the
// mass, 1/80 here), the balance with the sliding energy within 1 %.
TEST(MeshContact, IdenticalBlocksHeadOnSeparateAfterTwoWaveTransits) {
  const core::Scene scene = core::parse_scene(head_on_scene(), "head_on.toml");
  FeSolver solver(scene);
  const core::Energies e0 = solver.energies();
  const double p_body = std::abs(e0.bodies[0].momentum.z);
  double first = -1.0, last = -1.0, worst_momentum = 0.0, peak = 0.0;
  while (solver.time() < 0.02) {
    solver.step(std::min(solver.stable_time_step(), 0.02 - solver.time()));
    const core::Energies e = solver.energies();
    worst_momentum =
        std::max(worst_momentum, core::norm(e.bodies[0].momentum + e.bodies[1].momentum) / p_body);
    const double f = core::norm(solver.mesh_contacts()[0].normal_force);
    peak = std::max(peak, f);
    if (f > 0.0) {
      if (first < 0.0) first = solver.time();
      last = solver.time();
    }
  }
  const core::Energies e = solver.energies();
  const double c = steel_bar_wave_speed();
  const double expected = 2.0 * 10.0 / c;
  const double duration = last - first;
  const double kept = (e.kinetic + e.internal) / (e0.kinetic + e0.internal);
  const double balance = (e.total() - e0.total()) / e0.total();
  // The interface pressure rho c v on the 4 mm^2 face.
  const double force = 7.85e-3 * c * 5.0 * 4.0;
  std::printf(
      "head-on: contact %.4g us (2L/c %.4g us, %+.2f %%), peak force %.1f N (rho c v A "
      "%.1f N), momentum %.1e, kinetic + internal kept %.4f, sliding %.4g, balance %.1e\n",
      1e3 * duration, 1e3 * expected, 100.0 * (duration / expected - 1.0), peak, force,
      worst_momentum, kept, e.sliding, balance);
  EXPECT_LT(worst_momentum, 1e-12);
  EXPECT_NEAR(duration, expected, 0.05 * expected);
  EXPECT_NEAR(peak, force, 0.05 * force);
  EXPECT_GT(kept, 0.98);
  EXPECT_LT(std::abs(balance), 0.01);
  EXPECT_LT(e.bodies[0].momentum.z / p_body, -0.95);  // the left block turned back
}

// A steel block (10 x 10 x 4 mm, 4 x 4 x 2 hexahedra) on a fixed rigid plate of hexahedra under
// gravity g = 10 mm/ms^2 (scaled so the slide takes 1300 steps), sliding at 1 m/s with
// Coulomb friction mu.
std::string sliding_scene(double mu, const char* plate) {
  char s[1400];
  std::snprintf(
      s, sizeof s,
      "[run]\nend_time = 0.3\ngravity = [0, 0, -10]\n%s"
      "[[bodies]]\nname = \"block\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [10, 10, 4] } }\n"
      "mesh = { divisions = [4, 4, 2] }\nvelocity = [1, 0, 0]\n"
      "[[bodies]]\nname = \"plate\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [-5, -5, -2], max = [25, 15, 0] } }\n"
      "mesh = { divisions = [6, 4, 1] }\n%s\n"
      "[[contact]]\nbodies = [\"block\", \"plate\"]\nfriction = %g\n",
      kSteel, plate, mu);
  return s;
}

// Reference: a block sliding on a plane under Coulomb friction decelerates at mu g and stops
// after v^2 / (2 mu g) (= 0.1 mm for v = 1 m/s, mu = 0.5, g = 10 mm/ms^2). Pass: the distance
// within 2 %; friction's work equals the kinetic energy lost within 2 %; the history's force
// on the block along x is -mu m g while it slides (within 2 %); the energy balance within 1 %.
TEST(MeshContact, ABlockSlidingOnARigidPlateStopsAtTheCoulombDistance) {
  const double mu = 0.5, g = 10.0, v = 1.0;
  const core::Scene scene =
      core::parse_scene(sliding_scene(mu, "rigid = { fixed = [\"all\"] }"), "slide.toml");
  FeSolver solver(scene);
  const std::string plan = solver.plan().describe();
  EXPECT_NE(plan.find("rigid bodies"), std::string::npos) << plan;
  const core::Energies e0 = solver.energies();
  const double mass = e0.bodies[0].mass;
  double travel = 0.0, drag = 0.0;
  int drag_samples = 0;
  while (solver.time() < 0.3) {
    const double dt = std::min(solver.stable_time_step(), 0.3 - solver.time());
    solver.step(dt);
    const core::Energies e = solver.energies();
    const double vx = e.bodies[0].momentum.x / mass;
    travel += vx * dt;
    if (solver.time() > 0.05 && solver.time() < 0.15) {
      drag += solver.mesh_contacts()[0].tangential_force.x;
      ++drag_samples;
    }
  }
  const core::Energies e = solver.energies();
  const double expected = v * v / (2.0 * mu * g);
  const double balance = (e.total() - e0.total() - e.external_work) / e0.kinetic;
  drag /= drag_samples;
  std::printf(
      "sliding: stopped after %.5g mm (v^2 / 2 mu g %.5g mm, %+.2f %%), final speed "
      "%.2e, friction work %.5g vs kinetic energy %.5g, drag %.5g N (mu m g %.5g), "
      "balance %.1e\n",
      travel, expected, 100.0 * (travel / expected - 1.0), e.bodies[0].momentum.x / mass,
      e.friction, 0.5 * mass * v * v, drag, mu * mass * g, balance);
  EXPECT_NEAR(travel, expected, 0.02 * expected);
  EXPECT_LT(std::abs(e.bodies[0].momentum.x / mass), 0.01 * v);
  EXPECT_NEAR(e.friction, 0.5 * mass * v * v, 0.02 * 0.5 * mass * v * v);
  EXPECT_NEAR(-drag, mu * mass * g, 0.02 * mu * mass * g);
  EXPECT_LT(std::abs(balance), 0.01);
}

// Reference: a free rigid body keeps its momentum; hitting a deformable block, the two share
// the momentum exactly (the impulses are equal and opposite). A rigid steel cube (4 x 4 x 4 mm)
// at 10 m/s strikes a resting steel block (8 x 8 x 4 mm) of four times its mass, at the default
// step factor 0.9 and at 0.3. Pass: total momentum within 1e-12 of the start throughout; the
// cube's nodes stay rigid (the distance between two opposite corners unchanged to 1e-12); the
// balance with the sliding energy within 3 % at 0.9 and 1 % at 0.3. The block, 4 elements
// across, hourglasses: its hourglass energy is 31 % of the start's, and the balance's error is
// first order in the step (measured -2.4 %, -0.38 %, -0.04 % at factors 0.9, 0.3, 0.1).
class RigidCubeOnABlock : public ::testing::TestWithParam<double> {};

TEST_P(RigidCubeOnABlock, AFreeRigidBodyHandsItsMomentumToADeformableBlock) {
  std::string s =
      "[run]\nend_time = 0.01\nelement_time_step_factor = " + std::to_string(GetParam()) + "\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"cube\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0.05], max = [4, 4, 4.05] } }\nmesh = { divisions = [2, 2, "
       "2] }\n"
       "velocity = [0, 0, -10]\nrigid = true\n"
       "[[bodies]]\nname = \"block\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [-2, -2, -4], max = [6, 6, 0] } }\nmesh = { divisions = [4, 4, 4] "
       "}\n"
       "[[contact]]\nbodies = [\"cube\", \"block\"]\n";
  const core::Scene scene = core::parse_scene(s, "rigid_cube.toml");
  FeSolver solver(scene);
  const core::Energies e0 = solver.energies();
  const core::Vec3 p0 = e0.bodies[0].momentum + e0.bodies[1].momentum;
  const FeNodes& nodes = solver.nodes();
  const RigidBody& cube = solver.rigid_bodies().at(0);
  const std::size_t a = static_cast<std::size_t>(cube.nodes.front());
  const std::size_t b = static_cast<std::size_t>(cube.nodes.back());
  const double diagonal = core::norm(nodes.position[a] - nodes.position[b]);
  double worst = 0.0, worst_shape = 0.0;
  while (solver.time() < 0.01) {
    solver.step(std::min(solver.stable_time_step(), 0.01 - solver.time()));
    const core::Energies e = solver.energies();
    worst = std::max(worst,
                     core::norm(e.bodies[0].momentum + e.bodies[1].momentum - p0) / core::norm(p0));
    worst_shape =
        std::max(worst_shape,
                 std::abs(core::norm(nodes.position[a] - nodes.position[b]) - diagonal) / diagonal);
  }
  const core::Energies e = solver.energies();
  const double balance = (e.total() - e0.total() - e.external_work) / e0.total();
  std::printf(
      "rigid cube on a block, step factor %.1f: momentum %.1e, cube's shape %.1e, cube now "
      "%.4g m/s, block %.4g m/s, sliding %.4g of %.4g, hourglass %.4g, balance %.1e\n",
      GetParam(), worst, worst_shape, e.bodies[0].momentum.z / e.bodies[0].mass,
      e.bodies[1].momentum.z / e.bodies[1].mass, e.sliding, e0.kinetic, e.hourglass, balance);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_shape, 1e-12);
  EXPECT_LT(e.bodies[0].momentum.z / e.bodies[0].mass, -0.0);  // still moving down, slower
  EXPECT_GT(e.bodies[0].momentum.z / e.bodies[0].mass, -10.0 * 0.9);
  EXPECT_LT(e.bodies[1].momentum.z, 0.0);  // the block was pushed down
  EXPECT_LT(std::abs(balance), GetParam() > 0.5 ? 0.03 : 0.01);
}

INSTANTIATE_TEST_SUITE_P(MeshContact, RigidCubeOnABlock, ::testing::Values(0.9, 0.3));

// The columns of `name` in the model's force columns, in order.
std::vector<std::size_t> force_columns_of(const FeModel& model, const std::string& name) {
  std::vector<std::size_t> out;
  const std::vector<std::string> columns = model.force_columns();
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].compare(0, name.size() + 1, name + ".") == 0) out.push_back(c);
  return out;
}

// Reference: Newton's third law and the impulse-momentum theorem. A steel block (8 x 8 x 4 mm)
// strikes a fixed rigid anvil at 10 m/s through penalty contact; a free rigid cube strikes a
// resting block. Pass, on every step: the anvil's resultant (anvil.fx, .fy, .fz) equals minus the
// contact's force on its first body, the block, within 1e-10 of the largest contact force; the
// anvil's reaction (anvil.rfx, .rfy, .rfz) is minus its resultant to the same tolerance, its
// moments too; the free cube's force times dt^n sums to its change of momentum within 1e-10; a
// force probe on the anvil records its 12 columns. (Before this was fixed the rigid bodies
// reported only gravity and program loads: zero here.)
TEST(MeshContact, RigidBodiesReportTheContactForceAndTheirSupportsReaction) {
  std::string s = "[run]\nend_time = 0.02\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"block\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0.05], max = [8, 8, 4.05] } }\n"
       "mesh = { divisions = [4, 4, 2] }\nvelocity = [0, 0, -10]\n"
       "[[bodies]]\nname = \"anvil\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [-2, -3, -4], max = [9, 10, 0] } }\n"
       "mesh = { divisions = [3, 3, 2] }\nrigid = { fixed = [\"all\"] }\n"
       "[[contact]]\nname = \"impact\"\nbodies = [\"block\", \"anvil\"]\n"
       "[[probes]]\nname = \"anvil\"\nforce = \"anvil\"\n";
  const core::Scene scene = core::parse_scene(s, "anvil.toml");
  FeModel model(scene);
  const std::vector<std::size_t> contact = force_columns_of(model, "impact");
  const std::vector<std::size_t> anvil = force_columns_of(model, "anvil");
  ASSERT_EQ(contact.size(), 5u);
  ASSERT_EQ(anvil.size(), 12u);
  std::vector<double> f;
  double largest = 0.0, worst_third_law = 0.0, worst_reaction = 0.0, worst_moment = 0.0;
  while (model.time() < 0.02 * (1.0 - 1e-12)) {
    model.step(std::min(model.stable_time_step(), 0.02 - model.time()));
    model.force_values(f);
    for (int a = 0; a < 3; ++a) {
      const double on_block = f[contact[static_cast<std::size_t>(a)]];
      const double on_anvil = f[anvil[static_cast<std::size_t>(a)]];
      largest = std::max(largest, std::abs(on_block));
      worst_third_law = std::max(worst_third_law, std::abs(on_anvil + on_block));
      worst_reaction =
          std::max(worst_reaction, std::abs(f[anvil[static_cast<std::size_t>(6 + a)]] + on_anvil));
      worst_moment = std::max(worst_moment, std::abs(f[anvil[static_cast<std::size_t>(9 + a)]] +
                                                     f[anvil[static_cast<std::size_t>(3 + a)]]));
    }
  }
  std::printf(
      "fixed rigid anvil: largest contact force %.5g N; |anvil + contact| %.2e, |reaction + "
      "resultant| %.2e, moments %.2e\n",
      largest, worst_third_law, worst_reaction, worst_moment);
  // rho c v A of the block's 64 mm^2 face bounds the force from above; it must be of that order.
  EXPECT_GT(largest, 0.1 * 7.85e-3 * steel_bar_wave_speed() * 10.0 * 64.0);
  EXPECT_LT(worst_third_law, 1e-10 * largest);
  EXPECT_LT(worst_reaction, 1e-10 * largest);
  EXPECT_LT(worst_moment, 1e-10 * largest * 10.0);

  // A free rigid anvil: the impulse-momentum theorem.
  std::string free_anvil = s;
  free_anvil.replace(free_anvil.find("rigid = { fixed = [\"all\"] }"), 27, "rigid = true");
  const core::Scene second = core::parse_scene(free_anvil, "free_anvil.toml");
  FeModel free_model(second);
  ASSERT_EQ(force_columns_of(free_model, "anvil").size(), 6u);  // no supports, no reaction
  const core::Vec3 p0 = free_model.energies().bodies[1].momentum;
  core::Vec3 impulse;
  while (free_model.time() < 0.02 * (1.0 - 1e-12)) {
    const double dt = std::min(free_model.stable_time_step(), 0.02 - free_model.time());
    const double dt_force = free_model.solver().force_step(dt);
    free_model.step(dt);
    free_model.force_values(f);
    const std::vector<std::size_t> c = force_columns_of(free_model, "anvil");
    impulse += dt_force * core::Vec3{f[c[0]], f[c[1]], f[c[2]]};
  }
  const core::Vec3 gained = free_model.energies().bodies[1].momentum - p0;
  std::printf("free rigid anvil: momentum gained %.6g, sum of force dt %.6g\n", gained.z,
              impulse.z);
  EXPECT_LT(gained.z, 0.0);  // pushed down by the block
  EXPECT_LT(core::norm(impulse - gained), 1e-10 * core::norm(gained));
}

struct Patch {
  double force = 0.0, weight = 0.0;  // mean contact force, the upper block's weight
  std::vector<double> szz;           // mean sigma_zz of the column's top-layer elements
  double deepest = 0.0;              // deepest penetration of the upper block's bottom nodes
};

// A steel block (10 x 10 x 5 mm, n x n x 2 hexahedra) resting on a steel column of the same
// footprint (10 x 10 x 5 mm, 4 x 4 x 2 hexahedra, its bottom held along z) under gravity
// g = 10 mm/ms^2; n = 0: the two as one welded body (4 x 4 x 4). Both start unloaded, so they
// ring about the static state: the means over the second millisecond are the static values.
Patch run_patch(int n) {
  std::string s = "[run]\nend_time = 2\ngravity = [0, 0, -10]\n";
  s += kSteel;
  if (n == 0) {
    s += "[[bodies]]\nname = \"base\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
         "shape = { box = { min = [0, 0, -5], max = [10, 10, 5] } }\nmesh = { divisions = [4, 4, "
         "4] }\n";
  } else {
    s += "[[bodies]]\nname = \"base\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
         "shape = { box = { min = [0, 0, -5], max = [10, 10, 0] } }\nmesh = { divisions = [4, 4, "
         "2] }\n"
         "[[bodies]]\nname = \"top\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
         "shape = { box = { min = [0, 0, 0], max = [10, 10, 5] } }\nmesh = { divisions = [" +
         std::to_string(n) + ", " + std::to_string(n) +
         ", 2] }\n"
         "[[contact]]\nbodies = [\"top\", \"base\"]\n";
  }
  s += "[[constraints]]\nnodes = { plane = { point = [0, 0, -5], normal = [0, 0, 1] } }\n"
       "fixed = [\"z\"]\nbody = \"base\"\n";
  const core::Scene scene = core::parse_scene(s, "patch.toml");
  FeSolver solver(scene);
  const FeNodes& nodes = solver.nodes();
  const HexElements& hexes = solver.hexahedra();
  Patch out;
  out.weight = 7.85e-3 * 500.0 * 10.0;
  // The column's top layer (z in [-2.5, 0]) in a fixed order, and its top nodes on their 5 x 5
  // grid (2.5 mm apart).
  std::vector<std::pair<double, std::size_t>> layer;
  const ElementBatch& base = hexes.batches.at(0);
  for (std::size_t e = base.begin; e < base.end; ++e) {
    Vec3 c;
    for (std::int32_t k : hexes.nodes[e])
      c += 0.125 * nodes.initial_position[static_cast<std::size_t>(k)];
    if (c.z > -2.5 && c.z < 0.0) layer.emplace_back(c.x + 100.0 * c.y, e);
  }
  std::sort(layer.begin(), layer.end());
  EXPECT_EQ(layer.size(), 16u);
  std::size_t grid[5][5] = {};
  std::vector<std::size_t> bottom;  // the upper block's bottom nodes
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Vec3& x0 = nodes.initial_position[i];
    if (std::abs(x0.z) > 1e-9) continue;
    if (nodes.body[i] == 0)
      grid[std::lround(x0.x / 2.5)][std::lround(x0.y / 2.5)] = i;
    else
      bottom.push_back(i);
  }
  out.szz.assign(layer.size(), 0.0);
  double window = 0.0;
  while (solver.time() < 2.0) {
    const double dt = std::min(solver.stable_time_step(), 2.0 - solver.time());
    solver.step(dt);
    for (std::size_t i : bottom) {
      const Vec3& x = nodes.position[i];
      const int a = std::clamp(static_cast<int>(x.x / 2.5), 0, 3);
      const int b = std::clamp(static_cast<int>(x.y / 2.5), 0, 3);
      const double u = x.x / 2.5 - a, v = x.y / 2.5 - b;
      const double z = (1 - u) * (1 - v) * nodes.position[grid[a][b]].z +
                       u * (1 - v) * nodes.position[grid[a + 1][b]].z +
                       u * v * nodes.position[grid[a + 1][b + 1]].z +
                       (1 - u) * v * nodes.position[grid[a][b + 1]].z;
      out.deepest = std::max(out.deepest, z - x.z);
    }
    if (solver.time() > 1.0) {
      if (!solver.mesh_contacts().empty())
        out.force += solver.mesh_contacts()[0].normal_force.z * dt;
      for (std::size_t k = 0; k < layer.size(); ++k)
        out.szz[k] += hexes.stress[layer[k].second].zz * dt;
      window += dt;
    }
  }
  out.force /= window;
  for (double& v : out.szz) v /= window;
  return out;
}

// Reference: the contact carries the upper block's weight m g, and a frictionless interface
// loads the column below as the welded body does (the column's stresses, discretisation and
// self-weight included, are the welded body's). Pass: the mean contact force within 1 % of
// m g; every top-layer element's mean sigma_zz within 1 % of the pressure m g / A of the
// welded body's; no node of the upper block's bottom below the column's top surface
// (bilinear between its nodes) by more than 1e-6 of an element at any step (s = 1 closes the
// predicted penetration each step: the stated depth is zero). Meshes matching (4 x 4 on
// 4 x 4). With meshes that do not match (3 x 3 on 4 x 4) the force and depth pass the same,
// but node-to-face contact shares the load by the shape functions at the nodes, not by the
// integral of the tractions, and does not pass the pressure part (measured 13.7 % of m g / A;
// a mortar method would): 15 % guards what it reaches.
TEST(MeshContact, PatchTestABlockRestingOnAnotherTransmitsItsWeightUniformly) {
  const Patch welded = run_patch(0);
  for (int n : {4, 3}) {
    const Patch p = run_patch(n);
    const double pressure = p.weight / 100.0;
    double worst = 0.0;
    for (std::size_t k = 0; k < p.szz.size(); ++k)
      worst = std::max(worst, std::abs(p.szz[k] - welded.szz[k]) / pressure);
    std::printf(
        "patch test, %d x %d on 4 x 4: mean contact force %.5g N (m g %.5g, %+.3f %%), "
        "top-layer sigma_zz within %.3f %% of m g / A from the welded body's, deepest "
        "penetration %.2e mm\n",
        n, n, p.force, p.weight, 100.0 * (p.force / p.weight - 1.0), 100.0 * worst, p.deepest);
    EXPECT_NEAR(p.force, p.weight, 0.01 * p.weight);
    EXPECT_LT(worst, n == 4 ? 0.01 : 0.15);
    EXPECT_LT(p.deepest, 1e-6 * 2.5);
  }
}

TEST(MeshContact, BadInputNamesTheFileLineAndKey) {
  const std::string base =
      std::string("[run]\nend_time = 1\n") + kSteel +
      "[[bodies]]\nname = \"a\"\ndiscretisation = \"hexahedra\"\n"
      "material = \"steel\"\nshape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\n"
      "mesh = { divisions = [1, 1, 1] }\n"
      "[[bodies]]\nname = \"b\"\ndiscretisation = \"hexahedra\"\n"
      "material = \"steel\"\nshape = { box = { min = [0, 0, 2], max = [1, 1, 3] } }\n"
      "mesh = { divisions = [1, 1, 1] }\n";
  // Contact naming an unknown body.
  std::string text = base + "[[contact]]\nbodies = [\"a\", \"c\"]\n";
  std::string msg = test::error_of(text, "scene.toml");
  EXPECT_NE(
      msg.find("scene.toml:" + std::to_string(test::line_of(text, "bodies = [\"a\", \"c\"]"))),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find("contact[0].bodies"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown body \"c\"; bodies: \"a\", \"b\""), std::string::npos) << msg;
  // A penalty scale out of range.
  text = base + "[[contact]]\nbodies = [\"a\", \"b\"]\npenalty = 1.5\n";
  msg = test::error_of(text);
  EXPECT_NE(msg.find("scene.toml:" + std::to_string(test::line_of(text, "penalty = 1.5"))),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("contact[0].penalty"), std::string::npos) << msg;
  EXPECT_NE(msg.find("allowed: 0 < value <= 1"), std::string::npos) << msg;
  // An absorbing boundary on a rigid body, and a constraint holding its nodes.
  std::string rigid = base;
  rigid.replace(rigid.find("name = \"a\""), 10, "name = \"a\"\nrigid = true");
  text = rigid +
         "[[absorbing]]\nbody = \"a\"\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } "
         "}\n";
  msg = test::error_of(text);
  EXPECT_NE(msg.find("absorbing[0].body"), std::string::npos) << msg;
  EXPECT_NE(msg.find("is rigid"), std::string::npos) << msg;
  text = rigid +
         "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
         "fixed = [\"z\"]\n";
  try {
    const core::Scene scene = core::parse_scene(text, "scene.toml");
    FeSolver solver(scene);
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    msg = e.what();
    EXPECT_NE(msg.find("scene.toml:" + std::to_string(test::line_of(text, "[[constraints]]"))),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find("of rigid body \"a\""), std::string::npos) << msg;
  }
  // A body of particles on a grid, for the next two.
  const std::string particles =
      std::string("[run]\nend_time = 1\n[grid]\ncell = 1\nmin = [-2, -2, -2]\nmax = [4, 4, 4]\n") +
      kSteel +
      "[[bodies]]\nname = \"p\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\n";
  // A rigid body of particles.
  text = particles + "rigid = true\n";
  msg = test::error_of(text);
  EXPECT_NE(msg.find("scene.toml:" + std::to_string(test::line_of(text, "rigid = true"))),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("bodies.p.rigid"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a rigid body is made of hexahedra"), std::string::npos) << msg;
  // A rigid body in grid contact with particles.
  text =
      particles +
      "[[bodies]]\nname = \"r\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 2], max = [1, 1, 3] } }\nmesh = { divisions = [1, 1, 1] }\n"
      "rigid = true\n[[contact]]\nbodies = [\"p\", \"r\"]\n";
  msg = test::error_of(text);
  EXPECT_NE(msg.find("contact[0].bodies"), std::string::npos) << msg;
  EXPECT_NE(msg.find("body \"r\" is rigid"), std::string::npos) << msg;
  // A grid-only key on a contact between meshes.
  text = base + "[[contact]]\nbodies = [\"a\", \"b\"]\ndistance_factor = 0.5\n";
  msg = test::error_of(text);
  EXPECT_NE(msg.find("contact[0].distance_factor"), std::string::npos) << msg;
  // A wall on a rigid body.
  text = base + "[[walls]]\npoint = [0, 0, -1]\nnormal = [0, 0, 1]\nbodies = [\"r\"]\n";
  text.replace(text.find("name = \"a\""), 10, "name = \"r\"\nrigid = true");
  msg = test::error_of(text);
  EXPECT_NE(msg.find("walls[0].bodies"), std::string::npos) << msg;
  EXPECT_NE(msg.find("is rigid"), std::string::npos) << msg;
}

}  // namespace
}  // namespace afemp::fem

namespace afemp::fem {
namespace {

// One body of two separate blocks (an LS-DYNA deck: one part, 2 x 2 x 2 hexahedra of 1 mm
// each), the upper 0.01 mm above the lower, whose bottom is held along z; gravity
// g = 10 mm/ms^2; `contact`: the body's self-contact.
double self_contact_run(const std::string& contact, double& penetration) {
  const test::ScratchDir dir;
  std::string k = "*KEYWORD\n*NODE\n";
  int id = 0;
  for (double z0 : {0.0, 2.01})
    for (int kz = 0; kz <= 2; ++kz)
      for (int ky = 0; ky <= 2; ++ky)
        for (int kx = 0; kx <= 2; ++kx)
          k += std::to_string(++id) + "," + std::to_string(kx) + "," + std::to_string(ky) + "," +
               std::to_string(z0 + kz) + "\n";
  k += "*ELEMENT_SOLID\n";
  int e = 0;
  for (int block = 0; block < 2; ++block)
    for (int kz = 0; kz < 2; ++kz)
      for (int ky = 0; ky < 2; ++ky)
        for (int kx = 0; kx < 2; ++kx) {
          auto n = [&](int i, int j, int l) { return 27 * block + 1 + i + 3 * j + 9 * l; };
          k += std::to_string(++e) + ",1";
          for (int v : {n(kx, ky, kz), n(kx + 1, ky, kz), n(kx + 1, ky + 1, kz), n(kx, ky + 1, kz),
                        n(kx, ky, kz + 1), n(kx + 1, ky, kz + 1), n(kx + 1, ky + 1, kz + 1),
                        n(kx, ky + 1, kz + 1)}) {
            k += ',';
            k += std::to_string(v);
          }
          k += "\n";
        }
  k += "*END\n";
  const std::string deck = dir.write("blocks.k", k);
  const std::string text =
      std::string("[run]\nend_time = 1\ngravity = [0, 0, -10]\n") + kSteel +
      "[[bodies]]\nname = \"blocks\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { mesh = { file = \"" +
      deck +
      "\" } }\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "fixed = [\"z\"]\n" +
      contact;
  const core::Scene scene = core::parse_scene(text, dir.file("blocks.toml"));
  FeSolver solver(scene);
  const FeNodes& nodes = solver.nodes();
  double mean = 0.0, window = 0.0;
  penetration = 0.0;
  while (solver.time() < 1.0) {
    const double dt = std::min(solver.stable_time_step(), 1.0 - solver.time());
    solver.step(dt);
    // The upper block's bottom nodes (28..36) against the lower block's top ones (19..27)
    // at the same x, y.
    for (std::size_t i = 18; i < 27; ++i)
      penetration = std::max(penetration, nodes.position[i].z - nodes.position[i + 9].z);
    if (solver.time() > 0.5 && !solver.mesh_contacts().empty()) {
      mean += solver.mesh_contacts()[0].normal_sum * dt;
      window += dt;
    }
  }
  return window > 0.0 ? mean / window : 0.0;
}

// Reference: two parts of one body that meet carry each other like two bodies do: the upper
// block's weight m g = 7.85e-3 x 8 x 10 N. Pass: with the body's self-contact the mean force
// it transmits over the second half-millisecond within 2 % of m g and no penetration beyond
// 1e-4 of an element (measured 4.5e-5 mm; a body's own faces share one pass, so each gap is
// closed from both sides in turn); without it the upper block falls into the lower one
// (more than 0.1 mm).
TEST(MeshContact, SelfContactHoldsOnePartOfABodyOnAnother) {
  double deep = 0.0;
  const double force = self_contact_run("[[contact]]\nbodies = [\"blocks\"]\n", deep);
  const double weight = 7.85e-3 * 8.0 * 10.0;
  double through = 0.0;
  self_contact_run("", through);
  std::printf(
      "self-contact: mean force %.5g N (m g %.5g, %+.2f %%), deepest %.2e mm; without "
      "it the blocks overlap by %.3g mm\n",
      force, weight, 100.0 * (force / weight - 1.0), deep, through);
  EXPECT_NEAR(force, weight, 0.02 * weight);
  EXPECT_LT(deep, 1e-4);
  EXPECT_GT(through, 0.1);
}

}  // namespace
}  // namespace afemp::fem

namespace afemp::fem {
namespace {

// Reference: the head-on blocks' interface force rho c v A (942 N) while they are in contact.
// Pass: a force probe on the contact records fz on the left block within 5 % of -942 N at its
// largest (the right block pushes it back); a probe naming no contact is an error listing the
// scene's.
TEST(MeshContact, AForceProbeRecordsTheContactForce) {
  std::string text = head_on_scene();
  text += "[[probes]]\nname = \"interface\"\nforce = \"left-right\"\n";
  text = text.replace(text.find("end_time = 0.02"), 15, "end_time = 0.014");
  const core::Scene scene = core::parse_scene(text, "probe.toml");
  FeModel model(scene);
  const core::RunSummary s = analysis::run(model, scene, {});
  ASSERT_EQ(s.probes.size(), 1u);
  const core::ProbeSeries& p = s.probes[0];
  ASSERT_EQ(p.columns, (std::vector<std::string>{"fx", "fy", "fz", "normal", "tangential"}));
  double lowest = 0.0;
  for (std::size_t r = 0; r < p.rows(); ++r) lowest = std::min(lowest, p.at(r, 2));
  const double force = 7.85e-3 * steel_bar_wave_speed() * 5.0 * 4.0;
  std::printf("force probe: %zu rows, fz down to %.1f N (rho c v A %.1f N)\n", p.rows(), lowest,
              force);
  EXPECT_NEAR(-lowest, force, 0.05 * force);
  text += "[[probes]]\nname = \"nothing\"\nforce = \"left-middle\"\n";
  const core::Scene bad = core::parse_scene(text, "probe.toml");
  FeModel again(bad);
  try {
    analysis::run(again, bad, {});
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("probes[1].force"), std::string::npos) << m;
    EXPECT_NE(m.find("those of this scene: \"left-right\""), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace afemp::fem
