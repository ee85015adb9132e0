// Rigid walls met at the particles' boundary (mpm/particle_wall_contact.cpp). Units mm, ms, g,
// N, MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scene_errors.hpp"

namespace afemp::mpm {
namespace {

// Elastic steel: rho 7.85e-3, E 2.1e5, nu 0.3.
constexpr const char* kSteel = "[materials.steel]\ndensity = 7.85e-3\nE = 2.1e5\nnu = 0.3\n";

// A steel column, 1 x 1 x 10 mm, held across by symmetric side faces (uniaxial strain), its
// lower end on a rigid wall at z = 0, moving onto it at 5 m/s. `wall` is either a [[walls]]
// entry (the particle wall) or empty with the grid's zmin face a "wall" (the grid form).
std::string column_scene(bool particle_wall) {
  std::string s = "[run]\nend_time = 0.01\n[grid]\ncell = 0.25\n";
  s += particle_wall ? "min = [0, 0, -1]\n" : "min = [0, 0, 0]\n";
  s += "max = [1, 1, 11]\nboundary = { xmin = \"symmetric\", xmax = \"symmetric\", ymin = "
       "\"symmetric\", ymax = \"symmetric\"";
  s += particle_wall ? " }\n" : ", zmin = \"wall\" }\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"column\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0], max = [1, 1, 10] } }\nvelocity = [0, 0, -5]\n";
  if (particle_wall)
    s += "[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nbodies = [\"column\"]\n";
  return s;
}

struct Impact {
  double duration = 0.0, plateau = 0.0, rebound = 0.0, balance = 0.0;
};

// Runs the column until it has left the wall; the contact lasts from the first to the last
// step the column's momentum rose (its impulse over the step, for both forms alike).
Impact impact(bool particle_wall) {
  const core::Scene scene = core::parse_scene(column_scene(particle_wall), "column.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const core::Energies e0 = solver.energies();
  const double mass = e0.bodies[0].mass;
  double first = -1.0, last = -1.0, pz = e0.bodies[0].momentum.z;
  std::vector<std::array<double, 3>> steps;  // start, end, force
  while (solver.time() < 0.01) {
    const double dt = solver.stable_time_step();
    const double t0 = solver.time();
    solver.step(dt);
    const core::Energies e = solver.energies();
    const double force = (e.bodies[0].momentum.z - pz) / dt;
    pz = e.bodies[0].momentum.z;
    if (particle_wall) {
      EXPECT_NEAR(solver.wall_forces()[0].z, force, 1e-9 * std::abs(force) + 1e-9);
    }
    if (force > 1e-6 * mass) {
      if (first < 0.0) first = t0;
      last = solver.time();
    }
    steps.push_back({t0, solver.time(), force});
  }
  // The force's mean over the middle half of the contact (the first step's catch of the end
  // layer and the release left out).
  const double quarter = 0.25 * (last - first);
  double impulse = 0.0, span = 0.0;
  for (const auto& [a, b, f] : steps)
    if (a >= first + quarter && b <= last - quarter) {
      impulse += f * (b - a);
      span += b - a;
    }
  const core::Energies e = solver.energies();
  return {last - first, impulse / span, e.bodies[0].momentum.z / mass,
          (e.total() - e0.total() - e.external_work) / e0.kinetic};
}

// Reference (1-D elastic impact on a rigid wall): the column stays in contact for 2 L / c_L
// (c_L = sqrt((K + 4G/3) / rho) = 6001 m/s: 3.333 us), presses with rho c_L v A = 235.5 N and
// leaves at +5 m/s. Pass: contact time within 5 %, the force's plateau within 5 %, the energy
// balance within 3 % (the wall is fixed: it books no work; the catch of the end layer of
// particles, 1/80 of the mass here, is inelastic, as a kinematic wall's is) and the rebound
// within 5 % (the column also leaves ringing: 4.77 m/s measured, 4.79 with the grid's wall
// face, which is printed beside it).
TEST(ParticleWalls, ColumnOnARigidWallRestsTwoWaveTransits) {
  const double c = std::sqrt(2.1e5 * 0.7 / (1.3 * 0.4 * 7.85e-3));
  const double duration = 2.0 * 10.0 / c, force = 7.85e-3 * c * 5.0 * 1.0;
  const Impact wall = impact(true), grid = impact(false);
  std::printf(
      "column on a rigid wall: particle wall %.4g us (2L/c %.4g, %+.2f %%), plateau %.4g N "
      "(rho c v A %.4g, %+.2f %%), rebound %.4g m/s, balance %.1e; grid wall face %.4g us "
      "(%+.2f %%), plateau %.4g N, rebound %.4g m/s\n",
      1e3 * wall.duration, 1e3 * duration, 100.0 * (wall.duration / duration - 1.0), wall.plateau,
      force, 100.0 * (wall.plateau / force - 1.0), wall.rebound, wall.balance, 1e3 * grid.duration,
      100.0 * (grid.duration / duration - 1.0), grid.plateau, grid.rebound);
  EXPECT_NEAR(wall.duration, duration, 0.05 * duration);
  EXPECT_NEAR(wall.plateau, force, 0.05 * force);
  EXPECT_NEAR(wall.rebound, 5.0, 0.05 * 5.0);
  EXPECT_LT(std::abs(wall.balance), 0.03);
}

// A steel block (10 x 10 x 4 mm of particles) resting on a rigid wall under gravity
// g = 10 mm/ms^2 (scaled, as in the mesh contact's test, so the slide takes a few thousand
// steps), sliding at 1 m/s with Coulomb friction mu = 0.5.
// Reference: it decelerates at mu g and stops after v^2 / (2 mu g) = 0.1 mm. Pass: the
// distance within 2 %, the wall's tangential force mu m g within 2 % while it slides, and
// the energy friction dissipated (booked as sliding energy) equal to the kinetic energy lost
// within 3 %.
TEST(ParticleWalls, ABlockSlidingOnAWallStopsAtTheCoulombDistance) {
  const double mu = 0.5, g = 10.0, v = 1.0;
  std::string s =
      "[run]\nend_time = 0.3\ngravity = [0, 0, -10]\n[grid]\ncell = 1\n"
      "min = [-2, -2, -2]\nmax = [14, 12, 6]\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"block\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0], max = [10, 10, 4] } }\nvelocity = [1, 0, 0]\n"
       "[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nfriction = 0.5\nbodies = [\"block\"]\n";
  const core::Scene scene = core::parse_scene(s, "slide.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const core::Energies e0 = solver.energies();
  const double mass = e0.bodies[0].mass;
  double travel = 0.0, drag = 0.0;
  int samples = 0;
  while (solver.time() < 0.3) {
    const double dt = std::min(solver.stable_time_step(), 0.3 - solver.time());
    solver.step(dt);
    const double vx = solver.energies().bodies[0].momentum.x / mass;
    travel += vx * dt;
    if (solver.time() > 0.05 && solver.time() < 0.15) {
      drag += solver.wall_forces()[0].x;
      ++samples;
    }
  }
  drag /= samples;
  const core::Energies e = solver.energies();
  const double expected = v * v / (2.0 * mu * g);
  std::printf(
      "particles sliding on a wall: stopped after %.5g mm (v^2 / 2 mu g %.5g, %+.2f %%), final "
      "speed %.2e, drag %.5g N (mu m g %.5g), friction %.5g vs kinetic energy %.5g\n",
      travel, expected, 100.0 * (travel / expected - 1.0), e.bodies[0].momentum.x / mass, drag,
      mu * mass * g, e.friction, 0.5 * mass * v * v);
  EXPECT_NEAR(travel, expected, 0.02 * expected);
  EXPECT_LT(std::abs(e.bodies[0].momentum.x / mass), 0.01 * v);
  EXPECT_NEAR(-drag, mu * mass * g, 0.02 * mu * mass * g);
  EXPECT_NEAR(e.friction, 0.5 * mass * v * v, 0.03 * 0.5 * mass * v * v);
  EXPECT_DOUBLE_EQ(e.sliding, e.friction);
}

// Reference: a wall moving at constant velocity u into a free block at rest pushes it; the
// block's momentum gain equals the impulse the wall reports (its force summed over the steps,
// to 1e-9), and the wall's work (the external work) equals the block's gain in kinetic and
// internal energy within 2 % (what the kinematic catch of the end layer dissipates).
TEST(ParticleWalls, AMovingWallDoesTheWorkItsImpulseCarries) {
  std::string s =
      "[run]\nend_time = 0.02\n[grid]\ncell = 0.25\nmin = [0, 0, -1]\n"
      "max = [1, 1, 11]\nboundary = { xmin = \"symmetric\", xmax = \"symmetric\", "
      "ymin = \"symmetric\", ymax = \"symmetric\" }\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"column\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0], max = [1, 1, 10] } }\n"
       "[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nvelocity = [0, 0, 2]\n"
       "bodies = [\"column\"]\n";
  const core::Scene scene = core::parse_scene(s, "push.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const core::Energies e0 = solver.energies();
  double impulse = 0.0;
  while (solver.time() < 0.002) {
    const double dt = solver.stable_time_step();
    solver.step(dt);
    impulse += dt * solver.wall_forces()[0].z;
  }
  const core::Energies e = solver.energies();
  const double gain = e.kinetic + e.internal - e0.kinetic - e0.internal;
  std::printf("moving wall: impulse %.6g, momentum %.6g; work %.6g, energy gained %.6g\n", impulse,
              e.bodies[0].momentum.z, e.external_work, gain);
  EXPECT_GT(impulse, 0.0);
  EXPECT_NEAR(e.bodies[0].momentum.z, impulse, 1e-9 * impulse);
  EXPECT_NEAR(e.external_work, gain, 0.02 * gain);
}

// Reference: the scene check (afemp check, afemp run and a scene built in code) takes a wall
// naming a body of particles as the parser does; it refused one as "made of particles".
TEST(ParticleWalls, AWallNamingParticlesPassesTheSceneCheck) {
  EXPECT_NO_THROW(core::check_scene(core::parse_scene(column_scene(true), "column.toml")));
}

TEST(ParticleWalls, AWallWithoutBodiesInAParticleSceneIsAnError) {
  std::string s =
      "[run]\nend_time = 0.01\n[grid]\ncell = 0.25\nmin = [0, 0, -1]\n"
      "max = [1, 1, 11]\n";
  s += kSteel;
  s += "[[bodies]]\nname = \"column\"\nmaterial = \"steel\"\n"
       "shape = { box = { min = [0, 0, 0], max = [1, 1, 10] } }\n"
       "[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\n";
  // Reference: the error names the file, the wall's line, the key and what to do.
  const std::string e = afemp::test::error_of(s, "walls.toml");
  const std::string line = "walls.toml:" + std::to_string(afemp::test::line_of(s, "[[walls]]"));
  EXPECT_NE(e.find(line), std::string::npos) << e;
  EXPECT_NE(e.find("walls.bodies"), std::string::npos) << e;
  EXPECT_NE(e.find("name the particle bodies"), std::string::npos) << e;
}

}  // namespace
}  // namespace afemp::mpm
