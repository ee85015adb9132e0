// Rigid planar walls in the implicit solves (fem/wall_constraints.hpp, an exact active set): a
// block resting on a wall under its own weight against the closed form of a column under its
// weight, a block pressed against an inclined wall (uniform stress, exact), a cantilever whose
// tip comes down on a wall against the same cantilever with that tip prescribed, and the
// refusals (friction, a moving wall). In the Newmark solve: a block at rest on a wall stays at
// rest, and a bar that strikes a wall rebounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>

#include "static_test_support.hpp"

namespace afemp::fem {
namespace {

std::vector<std::int32_t> all_nodes(const MeshData& mesh) {
  std::vector<std::int32_t> nodes(mesh.nodes.size());
  std::iota(nodes.begin(), nodes.end(), 0);
  return nodes;
}

PlanarWall wall(core::Vec3 point, core::Vec3 normal, std::vector<std::int32_t> nodes) {
  PlanarWall w;
  w.spec.point = point;
  w.spec.normal = normal;
  w.nodes = std::move(nodes);
  return w;
}

// A column 1 x 1 x 4 (4 x 4 x 16 elements) standing on the wall z = 0 (which lists every node)
// under gravity g = 10 along -z, held against sliding and turning on the wall by the symmetry
// planes x = 0 and y = 0 (rollers, which let it expand sideways).
struct Column {
  static constexpr double width = 1.0, height = 4.0, g = 10.0;
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {width, width, height}}, {4, 4, 16});
  StaticProblem problem(const core::Material& m) const {
    StaticProblem p;
    p.mesh = &mesh;
    p.materials = {m};
    for (std::int32_t n : test::node_set(mesh, "xmin")) p.prescribed.push_back({n, 0, 0.0});
    for (std::int32_t n : test::node_set(mesh, "ymin")) p.prescribed.push_back({n, 1, 0.0});
    p.gravity = {0.0, 0.0, -g};
    p.walls = {wall({0, 0, 0}, {0, 0, 1}, all_nodes(mesh))};
    return p;
  }
};

// nu = 0: the column's closed form, sigma_zz = -rho g (h - z) and no other stress, has flat
// cross-sections (with nu > 0 they become paraboloids, u_z gaining nu rho g (x^2 + y^2) / 2E:
// Timoshenko & Goodier 1970, the bar under its own weight, which a flat frictionless base
// cannot take) and is the exact solution on the wall. Each z-layer of trilinear elements is
// then the 1-D bar of linear elements with consistent loads, exact at the nodes:
// u_z = -(rho g / E)(h z - z^2 / 2), to 1e-10 of its largest; its strain is constant over an
// element's height, so the mean of an element's Gauss points is the closed form at its
// centroid, to 1e-10 of rho g h, and each point is within rho g h_e / (2 sqrt 3) of the closed
// form at its own height. The wall's force is the weight rho g V, to 1e-12 of it (equilibrium:
// gravity's consistent forces sum to it, and the rollers take only x and y), and only the
// base's 25 nodes touch the wall.
TEST(StaticWalls, ColumnRestsOnAWallUnderItsWeight) {
  const Column column;
  core::Material m = test::steel();
  m.poisson_ratio = 0.0;
  const StaticResult r = solve_static(column.problem(m));
  const double rho_g = m.density * Column::g, h = Column::height, h_e = h / 16.0;
  const double weight = rho_g * Column::width * Column::width * h;

  const double top = rho_g / m.youngs_modulus * 0.5 * h * h;
  double u_error = 0.0;
  for (std::size_t n = 0; n < column.mesh.nodes.size(); ++n) {
    const double z = column.mesh.nodes[n].z;
    const double exact = -rho_g / m.youngs_modulus * (h * z - 0.5 * z * z);
    u_error = std::max({u_error, std::abs(r.displacement[n].z - exact),
                        std::abs(r.displacement[n].x), std::abs(r.displacement[n].y)});
  }
  double mean_error = 0.0, point_error = 0.0, other = 0.0;
  for (std::size_t e = 0; e < column.mesh.hexahedra.size(); ++e) {
    double mean = 0.0, zc = 0.0;
    for (int g = 0; g < 8; ++g) {
      const core::SymTensor& s = r.stress[e][g];
      const double z = test::gauss_point(column.mesh, e, g).z;
      mean += 0.125 * s.zz;
      zc += 0.125 * z;
      point_error = std::max(point_error, std::abs(s.zz + rho_g * (h - z)));
      other = std::max(
          {other, std::abs(s.xx), std::abs(s.yy), std::abs(s.xy), std::abs(s.yz), std::abs(s.xz)});
    }
    mean_error = std::max(mean_error, std::abs(mean + rho_g * (h - zc)));
  }
  const int contacts = r.iterations.back().contacts;
  std::printf(
      "column on a wall (nu = 0): wall force (%.3g, %.3g, %.12g), weight %.12g (error %.2e); u "
      "error %.2e of the top's; element-mean sigma_zz error %.2e, Gauss points %.4f, other "
      "stresses %.2e of rho g h; %d nodes on the wall, %zu Newton rows\n",
      r.wall_force[0].x, r.wall_force[0].y, r.wall_force[0].z, weight,
      std::abs(r.wall_force[0].z / weight - 1.0), u_error / top, mean_error / (rho_g * h),
      point_error / (rho_g * h), other / (rho_g * h), contacts, r.iterations.size());
  ASSERT_EQ(r.wall_force.size(), 1u);
  EXPECT_LT(std::abs(r.wall_force[0].z / weight - 1.0), 1e-12);
  EXPECT_LT(std::abs(r.wall_force[0].x) + std::abs(r.wall_force[0].y), 1e-12 * weight);
  EXPECT_LT(u_error, 1e-10 * top);
  EXPECT_LT(mean_error, 1e-10 * rho_g * h);
  EXPECT_LT(point_error, rho_g * h_e / (2.0 * std::sqrt(3.0)) * (1.0 + 1e-9));
  EXPECT_LT(other, 1e-10 * rho_g * h);
  EXPECT_EQ(contacts, 25);
}

// The same column with nu = 0.3: the wall's force is still the weight to 1e-12 (equilibrium),
// every base node stays on the wall (the flattening of the base's paraboloid redistributes the
// pressure on it by about nu rho g width / 2, well below rho g h), and away from the base the
// closed form holds again (Saint-Venant): above z = width, the element means of sigma_zz within
// 1 % of rho g h of it.
TEST(StaticWalls, ColumnWithPoissonExpansionMatchesItsWeightAwayFromTheBase) {
  const Column column;
  const core::Material m = test::steel();
  const StaticResult r = solve_static(column.problem(m));
  const double rho_g = m.density * Column::g, h = Column::height;
  const double weight = rho_g * Column::width * Column::width * h;
  double far = 0.0, near = 0.0;
  for (std::size_t e = 0; e < column.mesh.hexahedra.size(); ++e) {
    double mean = 0.0, zc = 0.0;
    for (int g = 0; g < 8; ++g) {
      mean += 0.125 * r.stress[e][g].zz;
      zc += 0.125 * test::gauss_point(column.mesh, e, g).z;
    }
    (zc > Column::width ? far : near) =
        std::max(zc > Column::width ? far : near, std::abs(mean + rho_g * (h - zc)));
  }
  const int contacts = r.iterations.back().contacts;
  std::printf(
      "column on a wall (nu = 0.3): wall force error %.2e of the weight; element-mean sigma_zz "
      "error %.4f of rho g h above z = width, %.4f below; %d nodes on the wall\n",
      std::abs(r.wall_force[0].z / weight - 1.0), far / (rho_g * h), near / (rho_g * h), contacts);
  EXPECT_LT(std::abs(r.wall_force[0].z / weight - 1.0), 1e-12);
  EXPECT_LT(far, 0.01 * rho_g * h);
  EXPECT_EQ(contacts, 25);
}

// A unit cube (2 x 2 x 2 elements) turned so that its face z = 0 lies on the wall through the
// origin with the normal n = (1, 2, 2) / 3, pressed against it by p = 100 on its opposite face.
// Frictionless, the wall takes only n: the exact solution is the uniform uniaxial stress
// sigma = -p n n, which trilinear elements represent exactly (the patch test). The tangential
// rigid-body modes are held by the corner on the origin (x and y prescribed: on the wall, it
// keeps z free for the wall, which then holds it) and by one component of the corner at Q e_x
// (against the turn about n): three constraints for three modes, so they take no force. Every
// Gauss point's stress within 1e-10 p of -p n n, the wall's force p A n to 1e-12, the top's
// normal displacement -p / E (the cube's shortening), and the 9 base nodes on the wall.
TEST(StaticWalls, CubePressedAgainstAnInclinedWallIsInUniformUniaxialStress) {
  const core::Vec3 n{1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};
  const core::Vec3 t1 = (1.0 / std::sqrt(2.0)) * core::Vec3{0.0, 1.0, -1.0};
  const core::Vec3 t2 = core::cross(n, t1);
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {1, 1, 1}}, {2, 2, 2});
  for (core::Vec3& x : mesh.nodes) x = x.x * t1 + x.y * t2 + x.z * n;
  const double p = 100.0;
  const core::Material m = test::steel();
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  for (const auto& face : faces_on_nodes(mesh, test::node_set(mesh, "zmax")))
    problem.pressures.push_back({face, p});
  std::int32_t origin = -1, corner = -1;
  for (std::size_t k = 0; k < mesh.nodes.size(); ++k) {
    if (core::norm(mesh.nodes[k]) < 1e-12) origin = static_cast<std::int32_t>(k);
    if (core::norm(mesh.nodes[k] - t1) < 1e-12) corner = static_cast<std::int32_t>(k);
  }
  ASSERT_GE(origin, 0);
  ASSERT_GE(corner, 0);
  problem.prescribed = {{origin, 0, 0.0}, {origin, 1, 0.0}, {corner, 2, 0.0}};
  problem.walls = {wall({0, 0, 0}, n, all_nodes(mesh))};
  const StaticResult r = solve_static(problem);

  double stress = 0.0;
  for (const auto& element : r.stress)
    for (const core::SymTensor& s : element) {
      const core::SymTensor exact{-p * n.x * n.x, -p * n.y * n.y, -p * n.z * n.z,
                                  -p * n.y * n.z, -p * n.x * n.z, -p * n.x * n.y};
      const core::SymTensor d = s - exact;
      stress = std::max({stress, std::abs(d.xx), std::abs(d.yy), std::abs(d.zz), std::abs(d.yz),
                         std::abs(d.xz), std::abs(d.xy)});
    }
  const core::Vec3 force_error = r.wall_force[0] - p * n;
  double shortening = 0.0;
  for (std::int32_t k : test::node_set(mesh, "zmax"))
    shortening = std::max(
        shortening, std::abs(core::dot(n, r.displacement[k]) / (-p / m.youngs_modulus) - 1.0));
  const int contacts = r.iterations.back().contacts;
  std::printf(
      "cube on an inclined wall: stress error %.2e of p, wall force (%.9g, %.9g, %.9g) (error "
      "%.2e of p A), top's normal displacement error %.2e, %d nodes on the wall\n",
      stress / p, r.wall_force[0].x, r.wall_force[0].y, r.wall_force[0].z,
      core::norm(force_error) / p, shortening, contacts);
  EXPECT_LT(stress, 1e-10 * p);
  EXPECT_LT(core::norm(force_error), 1e-12 * p);
  EXPECT_LT(shortening, 1e-10);
  EXPECT_EQ(contacts, 9);
}

// A cantilever 8 x 1 x 1 (16 x 1 x 2 elements, clamped at x = 0) under a tip force F = 10 down,
// over a wall at z = -0.05, half the free tip's deflection: the solve starts with no node on
// the wall, the unconstrained iterate crosses it, and the set settles with the tip's two base
// nodes on the wall (nodes that crossed it near the tip and are then pulled leave it). By
// superposition (linear elasticity, the set known): the wall's force R = (delta_F - gap) / c,
// delta_F the free tip's deflection at those nodes under F and c their deflection under a unit
// force shared by them, and the displacement u_F - R u_1, to 1e-9.
TEST(StaticWalls, CantileverComingDownOnAWallMatchesItsSuperposition) {
  const double force = 10.0, gap = 0.05;
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {8, 1, 1}}, {16, 1, 2});
  std::vector<std::int32_t> tip;  // the two base nodes at x = 8
  for (std::int32_t n : test::node_set(mesh, "xmax"))
    if (mesh.nodes[n].z == 0.0) tip.push_back(n);
  ASSERT_EQ(tip.size(), 2u);
  auto solve = [&](double tip_force, double base_force, bool with_wall) {
    StaticProblem p;
    p.mesh = &mesh;
    p.materials = {test::steel()};
    for (std::int32_t n : test::node_set(mesh, "xmin"))
      for (int i = 0; i < 3; ++i) p.prescribed.push_back({n, i, 0.0});
    p.nodal_forces.assign(mesh.nodes.size(), core::Vec3{});
    for (std::int32_t n : test::node_set(mesh, "xmax")) p.nodal_forces[n].z -= tip_force / 6.0;
    for (std::int32_t n : tip) p.nodal_forces[n].z -= base_force / 2.0;
    if (with_wall) p.walls = {wall({0, 0, -gap}, {0, 0, 1}, test::node_set(mesh, "zmin"))};
    return solve_static(p);
  };
  const StaticResult loaded = solve(force, 0.0, false), unit = solve(0.0, 1.0, false);
  const double delta = -loaded.displacement[tip[0]].z, c = -unit.displacement[tip[0]].z;
  const double reaction = (delta - gap) / c;
  const StaticResult r = solve(force, 0.0, true);
  double error = 0.0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    error = std::max(error, core::norm(r.displacement[n] - loaded.displacement[n] +
                                       reaction * unit.displacement[n]));
  int rounds = 0;
  for (const NewtonIteration& it : r.iterations) rounds = std::max(rounds, it.round + 1);
  const int contacts = r.iterations.back().contacts;
  std::printf(
      "cantilever on a wall: free tip deflection %.6g, wall force %.9g (superposition %.9g), "
      "displacement error %.2e of the gap, %d Newton solves, %d nodes on the wall\n",
      delta, r.wall_force[0].z, reaction, error / gap, rounds, contacts);
  EXPECT_GT(delta, 2.0 * gap * 0.9);
  EXPECT_NEAR(r.wall_force[0].z / reaction, 1.0, 1e-9);
  EXPECT_LT(error, 1e-9 * gap);
  EXPECT_EQ(contacts, 2);
  EXPECT_GE(rounds, 2);
  for (std::int32_t n : tip) EXPECT_NEAR(r.displacement[n].z, -gap, 1e-12);
}

// A wall with friction, or moving, is refused naming it: the implicit walls are frictionless
// and fixed.
TEST(StaticWalls, FrictionOrMotionIsRefusedNamingTheWall) {
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {1, 1, 1}}, {1, 1, 1});
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {test::steel()};
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int i = 0; i < 3; ++i)
      problem.prescribed.push_back({static_cast<std::int32_t>(n), i, 0.0});
  PlanarWall w = wall({0, 0, 0}, {0, 0, 1}, all_nodes(mesh));
  w.spec.where = {"scene.toml", 7};
  for (int variant = 0; variant < 2; ++variant) {
    problem.walls = {w};
    if (variant == 0)
      problem.walls[0].spec.friction = 0.2;
    else
      problem.walls[0].spec.velocity = {0, 0, 1};
    try {
      solve_static(problem);
      FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      std::printf("%s\n", what.c_str());
      EXPECT_NE(what.find("wall 0 (scene.toml:7)"), std::string::npos) << what;
      EXPECT_NE(what.find(variant == 0 ? "friction 0.2" : "moves"), std::string::npos) << what;
    }
  }
}

// Newmark: the column of ColumnRestsOnAWallUnderItsWeight (nu = 0.3) started from its static
// state at rest stays there: over 20 steps of dt = 1e-4 every velocity below 1e-9 of g dt (the
// static state's residual is at round-off) and the wall's force the weight to 1e-9 at every
// step.
TEST(NewmarkWalls, ColumnAtRestOnAWallStaysAtRest) {
  const Column column;
  const core::Material m = test::steel();
  const StaticProblem problem = column.problem(m);
  const StaticResult rest = solve_static(problem);
  NewmarkSettings settings;
  settings.time_step = 1e-4;
  settings.steps = 20;
  settings.initial_displacement = rest.displacement;
  const NewmarkResult r = solve_newmark(problem, settings);
  const double weight = m.density * Column::g * Column::height;
  double speed = 0.0, force = 0.0;
  for (const core::Vec3& v : r.velocity) speed = std::max(speed, core::norm(v));
  for (const NewmarkState& s : r.states)
    force = std::max(force, std::abs(s.wall_force[0].z / weight - 1.0));
  std::printf("column at rest (Newmark): largest speed %.2e (g dt = %.2e), wall force error %.2e\n",
              speed, Column::g * settings.time_step, force);
  EXPECT_LT(speed, 1e-9 * Column::g * settings.time_step);
  EXPECT_LT(force, 1e-9);
}

// Newmark: the bar of test_newmark.cpp (10 x 1 x 1, 20 elements, nu = 0, lateral components
// held: the 1-D bar of linear elements with consistent mass) moving at v0 = 1 onto the wall
// x = 0 that its end touches. The continuum bar stays on the wall for 2 L / c, takes the
// impulse 2 m v0 and leaves at v0 with all its energy (the elastic impact of a rod). The
// trapezoidal rule at dt = h / 2c, its end's nodes stopped on the wall on arrival (a kinematic
// wall, which takes their momentum: 1/40 of the bar's by their lumped share): the contact lasts
// 2 L / c within 5 %, the wall's impulse sum F dt is 2 m v0 within 1 %, the bar leaves with
// momentum m v0 within 3 % (the row sums of the consistent mass are the nodes' masses), and
// its energy at the end is at most the start's and at least 0.99 of it (measured: 78 steps of
// 80, impulse +0.34 %, momentum -1.8 %, energy -0.06 %).
TEST(NewmarkWalls, BarStrikingAWallReboundsAfterTwoWaveTransits) {
  const double length = 10.0, v0 = 1.0;
  MeshData mesh = box_mesh(core::BoxShape{{0, 0, 0}, {length, 1, 1}}, {20, 1, 1});
  core::Material m = test::steel();
  m.poisson_ratio = 0.0;
  StaticProblem problem;
  problem.mesh = &mesh;
  problem.materials = {m};
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int i = 1; i < 3; ++i)
      problem.prescribed.push_back({static_cast<std::int32_t>(n), i, 0.0});
  problem.walls = {wall({0, 0, 0}, {1, 0, 0}, test::node_set(mesh, "xmin"))};
  const double c = std::sqrt(m.youngs_modulus / m.density), mass = m.density * length;
  NewmarkSettings settings;
  settings.time_step = 0.5 * (length / 20.0) / c;
  settings.steps = 200;
  settings.initial_velocity.assign(mesh.nodes.size(), core::Vec3{-v0, 0.0, 0.0});
  const NewmarkResult r = solve_newmark(problem, settings);
  double impulse = 0.0;
  int contact_steps = 0;
  for (std::size_t k = 1; k < r.states.size(); ++k) {
    impulse += r.states[k].wall_force[0].x * settings.time_step;
    if (r.states[k].wall_force[0].x > 0.0) ++contact_steps;
  }
  std::vector<double> node_mass(mesh.nodes.size(), 0.0);
  for (const Hexahedron& h : mesh.hexahedra)
    for (std::int32_t a : h) node_mass[a] += m.density * (length / 20.0) / 8.0;
  double momentum = 0.0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) momentum += node_mass[n] * r.velocity[n].x;
  const double e0 = 0.5 * mass * v0 * v0, transit = 2.0 * length / c / settings.time_step;
  const double energy = (r.states.back().kinetic_energy + r.states.back().strain_energy) / e0;
  std::printf(
      "bar striking a wall: contact %d steps (2 L / c = %.1f steps), impulse %.6g (2 m v0 = "
      "%.6g), momentum after %.6g (m v0 = %.6g), energy at the end %.6f of the start's\n",
      contact_steps, transit, impulse, 2.0 * mass * v0, momentum, mass * v0, energy);
  EXPECT_NEAR(contact_steps / transit, 1.0, 0.05);
  EXPECT_NEAR(impulse / (2.0 * mass * v0), 1.0, 0.01);
  EXPECT_NEAR(momentum / (mass * v0), 1.0, 0.03);
  EXPECT_LE(energy, 1.0);
  EXPECT_GE(energy, 0.99);
  EXPECT_EQ(r.iterations.back().contacts, 0);
}

}  // namespace
}  // namespace afemp::fem
