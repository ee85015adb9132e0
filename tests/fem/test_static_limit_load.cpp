// A static solve loaded past its limit load (fem/static_solve.hpp, StaticFailure): the failing
// load step, its iteration, its residual against the tolerance and the element that yields
// most are named, and the state of the last converged load step is handed back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

// A bar 4 x 1 x 1 of four hexahedra along x (part 'bar', perfectly plastic J2, yield 250) on
// symmetry planes x, y, z = 0 (uniaxial stress, whose limit force is exactly 250 A), pulled at
// x = 4 by 300, 1.2 times it, in 4 load steps: steps 1-3 (75, 150, 225) are elastic, step 4 has
// no equilibrium. The StaticFailure names load step 4 of 4, a residual above its tolerance and
// a hexahedron of 'bar' as the element that yields most (all four yield alike); its last
// converged state is step 3's at load factor 0.75: sigma_xx = 225 at every Gauss point and the
// end's extension 225 L / E, to 1e-10 (the patch test's exactness), with no plastic strain.
TEST(StaticFailure, BarPulledPastItsLimitLoadKeepsTheLastConvergedStep) {
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {4, 1, 1}}, {4, 1, 1});
  mesh.part_names = {"bar"};
  core::Material m = test::steel();
  m.strength = core::J2Plasticity{250.0, 0.0};
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  for (std::int32_t n : test::node_set(mesh, "xmin")) problem.prescribed.push_back({n, 0, 0.0});
  for (std::int32_t n : test::node_set(mesh, "ymin")) problem.prescribed.push_back({n, 1, 0.0});
  for (std::int32_t n : test::node_set(mesh, "zmin")) problem.prescribed.push_back({n, 2, 0.0});
  problem.nodal_forces.assign(mesh.nodes.size(), core::Vec3{});
  for (std::int32_t n : test::node_set(mesh, "xmax")) problem.nodal_forces[n].x = 300.0 / 4.0;
  NewtonSettings settings;
  settings.load_steps = 4;
  try {
    solve_static(problem, settings);
    FAIL() << "no error";
  } catch (const StaticFailure& e) {
    const std::string what = e.what();
    const StaticFailureDetails& d = e.details();
    std::printf("%s\n", what.c_str());
    EXPECT_EQ(d.load_step, 4);
    EXPECT_EQ(d.load_steps, 4);
    EXPECT_GT(d.residual, d.tolerance * d.reference);
    EXPECT_EQ(d.most_yielding.kind, YieldingElement::Kind::hexahedron);
    EXPECT_EQ(d.most_yielding.part, "bar");
    EXPECT_GT(d.most_yielding.plastic_strain_increment, 0.0);
    for (const char* part :
         {"load step 4 of 4", "iteration", "tolerance", "hexahedron", "'bar'", "load factor 0.75"})
      EXPECT_NE(what.find(part), std::string::npos) << part;

    const StaticResult& last = d.last_converged;
    EXPECT_EQ(last.load_factor, 0.75);
    double extension = 0.0, stress = 0.0, plastic = 0.0;
    for (std::int32_t n : test::node_set(mesh, "xmax"))
      extension =
          std::max(extension, std::abs(last.displacement[n].x / (225.0 * 4.0 / 200e3) - 1.0));
    for (std::size_t el = 0; el < last.stress.size(); ++el)
      for (int g = 0; g < 8; ++g) {
        stress = std::max(stress, std::abs(last.stress[el][g].xx / 225.0 - 1.0));
        plastic = std::max(plastic, last.plastic_strain[el][g]);
      }
    std::printf(
        "last converged (load factor %.2f): extension error %.2e, stress error %.2e, "
        "plastic strain %.2e; %zu Newton rows kept\n",
        last.load_factor, extension, stress, plastic, last.iterations.size());
    EXPECT_LT(extension, 1e-10);
    EXPECT_LT(stress, 1e-10);
    EXPECT_EQ(plastic, 0.0);
    // Steps 1-3's rows (a solve and the check of its result each, at least) and the failing
    // step's.
    const auto rows_of = [&](int step) {
      return std::count_if(last.iterations.begin(), last.iterations.end(),
                           [&](const NewtonIteration& it) { return it.load_step == step; });
    };
    for (int step = 1; step <= 3; ++step) EXPECT_GE(rows_of(step), 2) << step;
    EXPECT_GE(rows_of(4), 2);
  }
}

// Three perfectly plastic trusses in series along x (yield 250; areas 0.1, 0.08, 0.12; the
// middle one part 'neck', the others part 'shank'), pulled by 1.2 times the neck's limit force
// 250 x 0.08 = 20 (below the others' 25 and 30) in 2 load steps: step 2's first plastic iterate
// leaves the neck no stiffness (E_t = 0), so the tangent is not positive definite. The failure
// names the neck's truss (line 1) as the element that yields most, and keeps step 1's state
// (the force 12 in every truss: stress 12 / area, to 1e-12).
TEST(StaticFailure, TrussChainPastTheNecksLimitNamesTheNeck) {
  MeshData mesh;
  mesh.nodes = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  mesh.lines = {{0, 1}, {1, 2}, {2, 3}};
  mesh.line_part = {0, 1, 0};
  mesh.line_area = {0.1, 0.08, 0.12};
  mesh.part_names = {"shank", "neck"};
  core::Material m = test::steel();
  m.strength = core::J2Plasticity{250.0, 0.0};
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m, m};
  for (int i = 0; i < 3; ++i) problem.prescribed.push_back({0, i, 0.0});
  for (std::int32_t n = 1; n < 4; ++n)
    for (int i = 1; i < 3; ++i) problem.prescribed.push_back({n, i, 0.0});
  problem.nodal_forces = {{}, {}, {}, {1.2 * 20.0, 0.0, 0.0}};
  NewtonSettings settings;
  settings.load_steps = 2;
  try {
    solve_static(problem, settings);
    FAIL() << "no error";
  } catch (const StaticFailure& e) {
    const std::string what = e.what();
    const StaticFailureDetails& d = e.details();
    std::printf("%s\n", what.c_str());
    EXPECT_EQ(d.load_step, 2);
    EXPECT_EQ(d.most_yielding.kind, YieldingElement::Kind::truss);
    EXPECT_EQ(d.most_yielding.index, 1);
    EXPECT_EQ(d.most_yielding.part, "neck");
    for (const char* part :
         {"load step 2 of 2", "not positive definite", "truss (line) 1", "'neck'"})
      EXPECT_NE(what.find(part), std::string::npos) << part;
    EXPECT_EQ(d.last_converged.load_factor, 0.5);
    for (std::size_t l = 0; l < 3; ++l)
      EXPECT_NEAR(d.last_converged.line_stress[l] * mesh.line_area[l], 12.0, 1e-12 * 12.0);
  }
}

}  // namespace
}  // namespace afemp::fem
