// The static solve from an initial state (StaticProblem::initial_stress and its kin: a phase
// after another starts from the points' stresses and plastic strains). References: a bar in
// uniaxial stress (symmetry planes at x, y, z = 0) whose initial state is a J2 point on its
// hardened yield surface, sigma_xx = 260 MPa with plastic strain (260 - 250) / H: under the
// equivalent end load it stays where it is, and under more load it flows by d sigma / H
// (linear hardening, statically determinate), as the same bar loaded from its virgin state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fem/mesh_generation.hpp"
#include "fem/static_solve.hpp"
#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

constexpr double kE = 200e3, kYield = 250.0, kH = 2000.0, kLength = 4.0;

struct Bar {
  MeshData mesh;
  StaticProblem problem;
};

// The bar [0, 4] x [0, 1] x [0, 1] of 4 B-bar hexahedra, J2 (yield 250 MPa, plastic modulus H),
// pulled by `force` N on its end x = 4 (a quarter at each of its four nodes).
void bar(double force, Bar& b) {
  b.mesh = box_mesh(core::BoxShape{{0, 0, 0}, {kLength, 1, 1}}, {4, 1, 1});
  b.mesh.part_names = {"bar"};
  b.problem.mesh = &b.mesh;
  b.problem.materials = {test::j2_steel(kH)};
  for (std::int32_t n : test::node_set(b.mesh, "xmin")) b.problem.prescribed.push_back({n, 0, 0.0});
  for (std::int32_t n : test::node_set(b.mesh, "ymin")) b.problem.prescribed.push_back({n, 1, 0.0});
  for (std::int32_t n : test::node_set(b.mesh, "zmin")) b.problem.prescribed.push_back({n, 2, 0.0});
  b.problem.nodal_forces.assign(b.mesh.nodes.size(), core::Vec3{});
  for (std::int32_t n : test::node_set(b.mesh, "xmax")) b.problem.nodal_forces[n].x = force / 4.0;
}

// The initial state sigma_xx = 260 MPa on the hardened surface.
void start_on_the_surface(Bar& b) {
  const double sigma = 260.0, plastic = (sigma - kYield) / kH;
  core::SymTensor s;
  s.xx = sigma;
  std::array<core::SymTensor, 8> stress;
  std::array<double, 8> strain;
  stress.fill(s);
  strain.fill(plastic);
  b.problem.initial_stress.assign(b.mesh.hexahedra.size(), stress);
  b.problem.initial_plastic_strain.assign(b.mesh.hexahedra.size(), strain);
}

double end_displacement(const Bar& b, const StaticResult& r) {
  double u = 0.0;
  for (std::int32_t n : test::node_set(b.mesh, "xmax")) u = std::max(u, r.displacement[n].x);
  return u;
}

TEST(StaticInitialState, BarOnItsYieldSurfaceStaysUnderTheEquivalentLoad) {
  Bar b;
  bar(260.0, b);
  start_on_the_surface(b);
  NewtonSettings settings;
  settings.load_steps = 2;
  const StaticResult r = solve_static(b.problem, settings);
  double moved = 0.0, stress = 0.0, plastic = 0.0;
  for (const core::Vec3& u : r.displacement) moved = std::max(moved, core::norm(u));
  for (std::size_t e = 0; e < r.stress.size(); ++e)
    for (int g = 0; g < 8; ++g) {
      stress = std::max(stress, std::abs(r.stress[e][g].xx / 260.0 - 1.0));
      plastic = std::max(plastic, std::abs(r.plastic_strain[e][g] - 10.0 / kH));
    }
  EXPECT_LT(moved, 1e-12);
  EXPECT_LT(stress, 1e-12);
  EXPECT_LT(plastic, 1e-15);
  // The reactions at the start and the end (the supports' forces on the bar): the plane x = 0
  // holds the 260 N pull, along -x.
  double start = 0.0, end = 0.0;
  for (std::size_t k = 0; k < b.problem.prescribed.size(); ++k)
    if (b.problem.prescribed[k].component == 0) {
      start += r.start_reaction[k];
      end += r.reaction[k];
    }
  EXPECT_NEAR(start, -260.0, 1e-9);
  EXPECT_NEAR(end, -260.0, 1e-9);
  std::printf("initial state in equilibrium: moved %.2g mm, stress %.2g, plastic %.2g\n", moved,
              stress, plastic);
}

TEST(StaticInitialState, BarOnItsYieldSurfaceFlowsAsTheVirginBarUnderMoreLoad) {
  Bar from_state, virgin;
  bar(280.0, from_state);
  start_on_the_surface(from_state);
  bar(280.0, virgin);
  NewtonSettings settings;
  settings.load_steps = 4;
  const StaticResult r = solve_static(from_state.problem, settings);
  const StaticResult v = solve_static(virgin.problem, settings);
  // From 260 to 280 MPa: elastic 20 / E and plastic 20 / H per unit length.
  const double extension = kLength * (20.0 / kE + 20.0 / kH);
  EXPECT_NEAR(end_displacement(from_state, r) / extension, 1.0, 1e-10);
  // The virgin bar: 280 / E and (280 - 250) / H, the state's start included.
  const double virgin_extension = kLength * (280.0 / kE + 30.0 / kH);
  EXPECT_NEAR(end_displacement(virgin, v) / virgin_extension, 1.0, 1e-10);
  for (std::size_t e = 0; e < r.stress.size(); ++e)
    for (int g = 0; g < 8; ++g) {
      ASSERT_NEAR(r.stress[e][g].xx, 280.0, 1e-9);
      ASSERT_NEAR(r.stress[e][g].yy, 0.0, 1e-9);
      ASSERT_NEAR(r.plastic_strain[e][g], 30.0 / kH, 1e-12);
      ASSERT_NEAR(r.stress[e][g].xx, v.stress[e][g].xx, 1e-9);
      ASSERT_NEAR(r.plastic_strain[e][g], v.plastic_strain[e][g], 1e-12);
    }
  // The stress work from the state: the trapezoidal rule over the 4 load steps of a linear
  // stress-strain path, exact: (260 + 280) / 2 x (20 / E + 20 / H) per unit volume.
  const double work = 0.5 * (260.0 + 280.0) * (20.0 / kE + 20.0 / kH);
  for (std::size_t e = 0; e < r.work.points.size(); ++e)
    for (int g = 0; g < 8; ++g) ASSERT_NEAR(r.work.points[e][g] / work, 1.0, 1e-9);
  std::printf("from the state: extension %.6g (closed form %.6g); virgin %.6g (%.6g)\n",
              end_displacement(from_state, r), extension, end_displacement(virgin, v),
              virgin_extension);
}

}  // namespace
}  // namespace afemp::fem
