// The axisymmetric grid (mpm/axisymmetric.hpp): rings that hold a solid's volume exactly, the
// breathing of a thin ring against its closed-form period (which needs both hoop terms), and
// the scene file's refusals of what has no axisymmetric form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "analysis/liner_drive_1d.hpp"
#include "analysis/reference_checks.hpp"
#include "conical_charge_example.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_model.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

std::string ring_scene(const std::string& grid_extra, const std::string& body_extra) {
  return R"([run]
end_time = 0.05
[grid]
cell = 0.25
min = [0, 0, -1]
max = [12, 0, 2]
axisymmetric = true
)" + grid_extra +
         R"(
[materials.m]
density = 8e-3
E = 1e5
nu = 0
[[bodies]]
name = "ring"
material = "m"
shape = { box = { min = [9.75, -1, 0], max = [10.25, 1, 1] } }
)" + body_extra;
}

// Reference: a ring of rings of r-z area (h/2)^2 at radii (i + 1/2) h/2 fills the solid's
// volume pi (R_o^2 - R_i^2) L exactly when the radii are whole multiples of the spacing:
// sum 2 pi r_i d^2 over the rows. Tolerance 1e-12 (rounding).
TEST(Axisymmetric, RingsHoldTheSolidsVolumeAndMass) {
  const core::Scene scene = core::parse_scene(ring_scene("", ""), "ring.toml");
  EXPECT_DOUBLE_EQ(scene.mpm.grid.min.y, -0.125);
  EXPECT_DOUBLE_EQ(scene.mpm.grid.max.y, 0.125);
  const Particles p = generate_particles(scene);
  ASSERT_EQ(p.size(), 4u * 8u);  // 4 across the wall, 8 along z, one row of rings
  double volume = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.position[i].y, 0.0);
    volume += p.volume[i];
    mass += p.mass[i];
  }
  const double exact = std::numbers::pi * (10.25 * 10.25 - 9.75 * 9.75) * 1.0;
  EXPECT_NEAR(volume, exact, 1e-12 * exact);
  EXPECT_NEAR(mass, 8e-3 * exact, 1e-12 * 8e-3 * exact);
}

// Reference: a thin ring (radius R, wall t << R, free ends, nu = 0) held at first under a
// pressure p breathes about R (1 + p / E) with the period T = 2 pi R sqrt(rho / E): its hoop
// stress E (r - R) / R pulls each ring back by sigma / (rho r) (the hoop force), and only the
// hoop rate v_r / r strains it so. With nu = 0 the radial and axial waves do not load the hoop
// mode. The wall's thickness changes T by about (t / R)^2 / 12 (0.02 % here). Tolerance 1.5 %
// on the period from the mean radial velocity's sign changes, and 5 % on the swing 2 p R / E.
TEST(Axisymmetric, AThinRingBreathesWithItsClosedFormPeriod) {
  const core::Scene scene = core::parse_scene(ring_scene("", "pressure = 200\n"), "ring.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const double R = 10.0, E = 1e5, rho = 8e-3;
  const double period = 2.0 * std::numbers::pi * R * std::sqrt(rho / E);
  auto mean = [&](bool velocity) {
    const Particles& p = solver.particles();
    double m = 0.0, s = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      m += p.mass[i];
      s += p.mass[i] * (velocity ? p.velocity[i].x : p.position[i].x);
    }
    return s / m;
  };
  const double r0 = mean(false);
  std::vector<double> crossings;  // times at which the mean radial velocity changes sign
  double last = 0.0, largest = 0.0;
  while (solver.time() < 2.2 * period) {
    const double t = solver.time();
    solver.step(0.5 * solver.stable_time_step());
    const double v = mean(true);
    if (last > 0.0 && v <= 0.0) crossings.push_back(t + (solver.time() - t) * last / (last - v));
    if (last < 0.0 && v >= 0.0) crossings.push_back(t + (solver.time() - t) * last / (last - v));
    if (v != 0.0) last = v;
    largest = std::max(largest, mean(false) - r0);
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured = crossings[3] - crossings[1];
  std::printf(
      "thin ring breathing: period %.5f ms (closed form %.5f ms, %+.2f %%), largest "
      "expansion %.5f mm (closed form %.5f mm)\n",
      measured, period, 100.0 * (measured / period - 1.0), largest, 2.0 * 200.0 * R / E);
  EXPECT_NEAR(measured, period, 0.015 * period);
  // The ring swings from R to R (1 + 2 p / E) and back.
  EXPECT_NEAR(largest, 2.0 * 200.0 * R / E, 0.05 * 2.0 * 200.0 * R / E);
}

// Reference: the Taylor bar's experiment (examples/taylor_bar/README.md: L 16.2, D 13.5,
// W 10.1 mm) within V2's mark, a mean error of at most 0.03 (the quarter model of mpm.toml:
// 0.0150), from examples/taylor_bar/axisymmetric.toml; the energy balance within 2 %.
// The mushroom's spread D is the hoop terms' doing: without them it would not hold.
TEST(Axisymmetric, TheTaylorBarMatchesTheExperimentWithinThreePercentMeanError) {
  const core::Scene scene =
      core::read_scene(std::string(AFEMP_SOURCE_DIR) + "/examples/taylor_bar/axisymmetric.toml");
  MpmModel sim(scene);
  const core::RunSummary s = analysis::run(sim, scene, {});
  ASSERT_TRUE(s.taylor.has_value());
  std::printf(
      "axisymmetric Taylor bar: L %.2f D %.2f W %.2f, mean error %.4f, energy %+.2f %%, "
      "%zu particles, %ld steps, %.2f s\n",
      s.taylor->length, s.taylor->impact_diameter, s.taylor->bulge_diameter, s.taylor_error,
      100.0 * s.energy_error, s.particles, s.steps, s.wall_seconds);
  EXPECT_LE(s.taylor_error, 0.03);
  EXPECT_LT(s.max_energy_error, 0.02);
  // A ring has no net momentum across the axis (its particles' x velocity is radial).
  EXPECT_EQ(s.final.bodies.at(0).momentum.x, 0.0);
  EXPECT_NE(s.final.bodies.at(0).momentum.z, 0.0);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string refusal(const std::string& text) {
  try {
    (void)core::parse_scene(text, "axi.toml");
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

// Reference: conservation. A solid rod of rings (radius 1.5, 4 long) pulled apart along the
// axis, its halves started at -/+ 40 m/s and welded, a soft, nearly strengthless solid that
// flows: its rings stretch along z and split (mpm/particle_splitting.cpp), each into two rings
// at its radius with half its mass, except within one cell of the axis. Mass is kept exactly
// (tolerance 1e-12, rounding), the z momentum stays zero (1e-9 of either half's), the energy
// balance within 1 % at the end and 2 % throughout (1.06 % when written, as the halves meet on
// one field), and the stable step within a factor 2 of its start (a split on the axis
// let pieces run away: mpm/axisymmetric.hpp).
TEST(Axisymmetric, RingsSplitAlongZKeepingMassMomentumAndTheStep) {
  const std::string text = R"([run]
end_time = 0.05
[grid]
cell = 0.25
min = [0, 0, -6]
max = [4, 0, 10]
axisymmetric = true
[mpm]
splitting = { axes = ["z"] }
[materials.m]
density = 1e-3
E = 100
nu = 0.3
strength = { model = "j2", yield = 0.2 }
[[bodies]]
name = "low"
material = "m"
shape = { cylinder = { base = [0, 0, 0], radius = 1.5, length = 2 } }
velocity = [0, 0, -40]
[[bodies]]
name = "high"
material = "m"
shape = { cylinder = { base = [0, 0, 2], radius = 1.5, length = 2 } }
velocity = [0, 0, 40]
[[contact]]
bodies = ["low", "high"]
method = "weld"
)";
  const core::Scene scene = core::parse_scene(text, "rod.toml");
  MpmModel sim(scene);
  const Particles& p0 = sim.solver().particles();
  double mass0 = 0.0;
  for (std::size_t i = 0; i < p0.size(); ++i) mass0 += p0.mass[i];
  const core::RunSummary s = analysis::run(sim, scene, {});
  const Particles& p = sim.solver().particles();
  double mass = 0.0, momentum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    mass += p.mass[i];
    momentum += p.mass[i] * p.velocity[i].z;
  }
  std::printf(
      "axisymmetric splitting: %zu rings to %zu; mass %.3e of its start; z momentum %.2e "
      "of a half's; energy %+.3f %%; step %.3e .. %.3e ms\n",
      s.particles, p.size(), mass / mass0 - 1.0, momentum / (0.5 * mass0 * 40.0),
      100.0 * s.energy_error, s.min_dt, s.max_dt);
  EXPECT_GT(p.size(), s.particles + s.particles / 4);
  EXPECT_NEAR(mass, mass0, 1e-12 * mass0);
  EXPECT_NEAR(momentum, 0.0, 1e-9 * 0.5 * mass0 * 40.0);
  EXPECT_LT(std::abs(s.energy_error), 0.01);
  EXPECT_LT(std::abs(s.max_energy_error), 0.02);
  EXPECT_GT(s.min_dt, 0.5 * s.max_dt);
}

// Reference: the splitting rule itself (mpm/particle_splitting.cpp). A rod of rings at rest,
// every ring's length along z set to twice its start: at the next step each ring one cell or
// more from the axis splits in two along z (two rings at its radius, half its mass each) and
// each ring nearer the axis stays whole. Counted exactly.
TEST(Axisymmetric, RingsWithinOneCellOfTheAxisDoNotSplit) {
  const core::Scene scene = core::parse_scene(R"([run]
end_time = 1
[grid]
cell = 0.25
min = [0, 0, -1]
max = [3, 0, 3]
axisymmetric = true
[mpm]
splitting = { axes = ["z"] }
[materials.m]
density = 1e-3
E = 100
nu = 0.3
[[bodies]]
name = "rod"
material = "m"
shape = { cylinder = { base = [0, 0, 0], radius = 1.5, length = 2 } }
)",
                                              "rod.toml");
  MpmSolver solver(scene, generate_particles(scene));
  Particles& p = solver.mutable_particles();
  const std::size_t start = p.size();
  std::size_t near = 0;
  for (std::size_t i = 0; i < start; ++i) {
    p.length[i].z = 2.0 * p.length0[i].z;
    if (p.position[i].x < 0.25) ++near;
  }
  ASSERT_GT(near, 0u);
  solver.step(solver.stable_time_step());
  const Particles& after = solver.particles();
  std::size_t near_after = 0;
  for (std::size_t i = 0; i < after.size(); ++i)
    if (after.position[i].x < 0.25) ++near_after;
  EXPECT_EQ(after.size(), start + (start - near));
  EXPECT_EQ(near_after, near);
}

// Reference: an independent code. The example shaped charge's slice at z = 23.71 mm (the PER
// estimate's tip element; docs/explosives.md) as a band 0.8 mm tall between symmetric faces: a
// copper ring from r 2.512 to 4.822 mm, PBX 9501 to 20 mm, steel to 22, welded, lit from the
// charge's lighting point 23.71 mm below. Nothing flows along z, so it is the one-dimensional
// slice that analysis/liner_drive_1d computes with a Lagrangian hydrocode sharing no code with
// the solver (analysis::liner_drive_1d, 10 zones per mm: the copper ring's largest mean inward
// velocity 805 m/s). The ring's largest mean radial velocity here within 10 % of the
// hydrocode's (748 m/s when written, -7.1 %; 745 m/s at 0.05 mm cells). When it peaks is not
// asserted: the plateau's top moved from 5.1 to 4.3 us at 0.05 mm (the hydrocode: 4.9 us).
TEST(Axisymmetric, AShapedChargeSliceImplodesAsAOneDimensionalHydrocodeDrivesIt) {
  const std::string text = R"([run]
end_time = 0.0055
[grid]
cell = 0.1
min = [0, 0, 0]
max = [30, 0, 0.8]
axisymmetric = true
boundary = { xmax = "outflow", zmin = "symmetric", zmax = "symmetric" }
[mpm]
scheme = "USAVG"
[materials.pbx9501]
density = 1.84e-3
strength = { model = "fluid" }
eos = { model = "jwl", A = 8.524e5, B = 1.802e4, R1 = 4.6, R2 = 1.3, omega = 0.38, E0 = 1.02e4 }
burn = { D = 8800, pcj = 3.7e4 }
[materials.copper]
density = 8.93e-3
E = 124e3
nu = 0.35
strength = { model = "j2", yield = 120 }
eos = { model = "mie-gruneisen", c0 = 3940, s = 1.49, gamma0 = 2.0 }
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "j2", yield = 500 }
eos = { model = "mie-gruneisen", c0 = 4569, s = 1.49, gamma0 = 2.17 }
[[bodies]]
name = "liner"
material = "copper"
shape = { box = { min = [2.512, -1, 0], max = [4.822, 1, 0.8] } }
[[bodies]]
name = "charge"
material = "pbx9501"
shape = { box = { min = [4.822, -1, 0], max = [20, 1, 0.8] } }
particles_per_cell = 2
[[bodies]]
name = "case"
material = "steel"
shape = { box = { min = [20, -1, 0], max = [22, 1, 0.8] } }
[[detonations]]
point = [0, 0, -23.71]
[[contact]]
bodies = ["charge", "liner"]
method = "weld"
)";
  const core::Scene scene = core::parse_scene(text, "slice.toml");
  MpmSolver solver(scene, generate_particles(scene));
  double largest = 0.0, at = 0.0;
  while (solver.time() < scene.run.end_time) {
    solver.step(solver.stable_time_step());
    const Particles& p = solver.particles();
    double m = 0.0, mv = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body[i] == 0) {
        m += p.mass[i];
        mv += p.mass[i] * p.velocity[i].x;
      }
    if (-mv / m > largest) {
      largest = -mv / m;
      at = solver.time();
    }
  }
  const analysis::SliceDrive hydrocode =
      analysis::liner_slice_drive(analysis::test::example_charge(), analysis::test::pbx9501(),
                                  analysis::test::copper(), analysis::test::steel(), 23.71, 10.0);
  std::printf(
      "shaped charge slice at 23.71 mm: the liner's largest mean inward velocity %.0f m/s "
      "at %.2f us (the 1-D hydrocode: %.0f m/s at %.2f us)\n",
      largest, 1e3 * at, hydrocode.largest_velocity, 1e3 * hydrocode.largest_at);
  EXPECT_NEAR(largest, hydrocode.largest_velocity, 0.10 * hydrocode.largest_velocity);
}

// Reference: the scene format (docs/scene-format.md, "Axisymmetric grids"): the grid lies in
// y = 0 from the axis, has no faces across the plane, and what has no axisymmetric form is
// refused naming its key.
TEST(Axisymmetric, TheSceneFileRefusesWhatHasNoAxisymmetricForm) {
  std::string why = refusal(replaced(ring_scene("", ""), "max = [12, 0, 2]", "max = [12, 12, 2]"));
  EXPECT_NE(why.find("grid.min"), std::string::npos) << why;
  EXPECT_NE(why.find("must be 0"), std::string::npos) << why;
  why = refusal(ring_scene("boundary = { ymin = \"free\" }\n", ""));
  EXPECT_NE(why.find("grid.boundary.ymin"), std::string::npos) << why;
  why = refusal(ring_scene("boundary = { xmin = \"fixed\" }\n", ""));
  EXPECT_NE(why.find("the axis"), std::string::npos) << why;
  why = refusal(ring_scene("", "velocity = [10, 0, 0]\n"));
  EXPECT_NE(why.find("bodies.ring.velocity"), std::string::npos) << why;
  why = refusal(ring_scene("", "") + "[mpm]\nshape_function = \"gimp\"\n");
  EXPECT_NE(why.find("mpm.shape_function"), std::string::npos) << why;
  why = refusal(ring_scene("", "") + "[mpm]\nsplitting = { axes = [\"x\", \"z\"] }\n");
  EXPECT_NE(why.find("mpm.splitting.axes"), std::string::npos) << why;
  EXPECT_NE(why.find("along z only"), std::string::npos) << why;
  why = refusal(ring_scene("", "") + "[mpm]\nsplitting = {}\n");  // all three axes
  EXPECT_NE(why.find("mpm.splitting.axes"), std::string::npos) << why;
  EXPECT_EQ(refusal(ring_scene("", "") + "[mpm]\nsplitting = { axes = [\"z\"] }\n"), "");
  why = refusal(ring_scene("", "") +
                "[[bodies]]\nname = \"rod\"\nmaterial = \"m\"\nshape = { cylinder = { base = [1, "
                "0, 0], radius = 0.5, length = 1 } }\n");
  EXPECT_NE(why.find("bodies.rod.shape"), std::string::npos) << why;
  EXPECT_NE(why.find("does not turn about the z axis"), std::string::npos) << why;
}

}  // namespace
}  // namespace afemp::mpm
