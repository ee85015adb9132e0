// Drucker-Prager soil in runs, units mm, ms, g, MPa (sand: rho 2e-3, E = 100, nu = 0.3,
// phi = 30 deg, c = 0.01): a laterally confined column 10 x 10 x 100 mm under gravity, as MPM
// particles and as hexahedra, starts at its geostatic stress (initial_stress, K0 = 0.5) and
// stays at rest; the same column started unstressed oscillates, which is the scale the test
// holds the geostatic one to. Then a column loaded by gravity from zero stress flows
// plastically: its energy balances, and internal energy less plastic (and bulk-viscous) work is
// the elastic energy its stresses hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp {
namespace {

constexpr double kRho = 2.0e-3, kG = 9.81e-3, kHeight = 100.0, kK0 = 0.5;

const std::string kSand = R"(
[materials.sand]
density = 2.0e-3
E = 100
nu = 0.3
strength = { model = "drucker-prager", friction_angle = 30, cohesion = 0.01, dilatancy_angle = 5, fit = "outer" }
)";

std::string run_header(double end_time, bool gravity) {
  return "[run]\nend_time = " + std::to_string(end_time) + "\n" +
         (gravity ? "gravity = [0, 0, -9.81e-3]\n" : "");
}

const std::string kInitialStress =
    "initial_stress = { model = \"geostatic\", K0 = 0.5, surface = 100 }\n";

// Largest speed over the run, and the stress at the end at the point nearest mid-height.
struct ColumnResult {
  double max_speed = 0.0;
  core::SymTensor centre{};
  double centre_z = 0.0;
};

ColumnResult mpm_column(bool geostatic) {
  const core::Scene scene = core::parse_scene(run_header(1.0, true) + R"(
[grid]
cell = 10
min = [0, 0, 0]
max = [10, 10, 110]
boundary = { xmin = "symmetric", xmax = "symmetric", ymin = "symmetric", ymax = "symmetric", zmin = "symmetric" }
)" + kSand + R"(
[[bodies]]
name = "column"
material = "sand"
shape = { box = { min = [0, 0, 0], max = [10, 10, 100] } }
)" + (geostatic ? kInitialStress : ""),
                                              "k0_column_mpm.toml");
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  ColumnResult r;
  for (int n = 0; n < 400; ++n) {
    solver.step(solver.stable_time_step());
    for (const Vec3& v : solver.particles().velocity) r.max_speed = std::max(r.max_speed, norm(v));
  }
  const auto& p = solver.particles();
  std::size_t best = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(p.position[i].z - 50.0) < std::abs(p.position[best].z - 50.0)) best = i;
  r.centre = p.stress[best];
  r.centre_z = p.position[best].z;
  return r;
}

ColumnResult fe_column(bool geostatic, const char* element) {
  // Rollers on the four sides and the base.
  struct Roller {
    const char* plane;
    const char* axis;
  };
  std::string rollers;
  for (const Roller& r : {Roller{"point = [0, 0, 0], normal = [1, 0, 0]", "x"},
                          Roller{"point = [10, 0, 0], normal = [1, 0, 0]", "x"},
                          Roller{"point = [0, 0, 0], normal = [0, 1, 0]", "y"},
                          Roller{"point = [0, 10, 0], normal = [0, 1, 0]", "y"},
                          Roller{"point = [0, 0, 0], normal = [0, 0, 1]", "z"}})
    rollers += std::string("[[constraints]]\nnodes = { plane = { ") + r.plane +
               ", tolerance = 1e-9 } }\nfixed = [\"" + r.axis + "\"]\n";
  const core::Scene scene = core::parse_scene(run_header(1.0, true) + kSand + R"(
[[bodies]]
name = "column"
discretisation = "hexahedra"
material = "sand"
shape = { box = { min = [0, 0, 0], max = [10, 10, 100] } }
mesh = { divisions = [1, 1, 10] }
element = ")" + std::string(element) + "\"\n" + (geostatic ? kInitialStress : "") +
                                                  rollers,
                                              "k0_column_fe.toml");
  fem::FeSolver solver(scene);
  ColumnResult r;
  for (int n = 0; n < 400; ++n) {
    solver.step(solver.stable_time_step());
    for (const Vec3& v : solver.nodes().velocity) r.max_speed = std::max(r.max_speed, norm(v));
  }
  const auto& h = solver.hexahedra();
  const std::size_t per = h.points() / h.size();
  double best = 1e300;
  for (std::size_t e = 0; e < h.size(); ++e) {
    double z = 0.0;
    for (std::int32_t n : h.nodes[e]) z += solver.nodes().position[static_cast<std::size_t>(n)].z;
    z /= 8.0;
    if (std::abs(z - 45.0) < best) {
      best = std::abs(z - 45.0);
      r.centre_z = z;
      core::SymTensor mean{};
      for (std::size_t g = 0; g < per; ++g) mean += (1.0 / per) * h.stress[e * per + g];
      r.centre = mean;
    }
  }
  return r;
}

void check_column(const char* label, const ColumnResult& geostatic, const ColumnResult& loaded) {
  constexpr double speed_ratio = 1e-9, stress_tolerance = 1e-9;
  // Reference: sigma_zz = -rho g (H - z), sigma_xx = sigma_yy = K0 sigma_zz at the centre point
  // after 400 steps, to 1e-9 relative; the largest speed over them below 1e-9 of that of the
  // same column loaded from zero stress (about g H / c = 3.8e-3 mm/ms): the discrete
  // equilibrium holds to round-off (the lumped weight of each node level is what the stresses
  // of the points above and below it differ by, for particles and for both hexahedra).
  const double szz = -kRho * kG * (kHeight - geostatic.centre_z);
  std::printf(
      "K0 column %s: largest speed %.3g mm/ms (from zero stress %.3g), sigma_zz %.6g against "
      "%.6g, sigma_xx / sigma_zz %.6g at z = %.4g\n",
      label, geostatic.max_speed, loaded.max_speed, geostatic.centre.zz, szz,
      geostatic.centre.xx / geostatic.centre.zz, geostatic.centre_z);
  EXPECT_LT(geostatic.max_speed, speed_ratio * loaded.max_speed) << label;
  EXPECT_NEAR(geostatic.centre.zz, szz, stress_tolerance * std::abs(szz)) << label;
  EXPECT_NEAR(geostatic.centre.xx, kK0 * geostatic.centre.zz,
              stress_tolerance * kK0 * std::abs(szz))
      << label;
  EXPECT_NEAR(geostatic.centre.yy, geostatic.centre.xx, 1e-12) << label;
}

TEST(DruckerPragerRuns, GeostaticColumnOfParticlesStaysAtRest) {
  check_column("MPM", mpm_column(true), mpm_column(false));
}

TEST(DruckerPragerRuns, GeostaticColumnOfHexahedraStaysAtRest) {
  for (const char* element : {"one-point", "full"})
    check_column(element, fe_column(true, element), fe_column(false, element));
}

// Internal energy less plastic work, and the elastic energy the stresses hold:
// sum m (s:s/4G + sigma_m^2/2K) / rho.
double stored_elastic_energy(const core::Material& m, const std::vector<core::SymTensor>& stress,
                             const std::vector<double>& mass, const std::vector<double>& density) {
  double e = 0.0;
  for (std::size_t i = 0; i < stress.size(); ++i) {
    const core::SymTensor s = stress[i].deviator();
    const double mean = stress[i].mean();
    e += mass[i] *
         (core::double_dot(s, s) / (4.0 * m.shear_modulus()) +
          mean * mean / (2.0 * m.bulk_modulus())) /
         density[i];
  }
  return e;
}

// Runs the solver to end_time and checks the energies (the reference below).
template <class Solver, class Elastic>
void check_energies(const char* label, Solver& solver, double end_time, double balance_tolerance,
                    Elastic&& elastic) {
  const core::Energies initial = solver.energies();
  double max_kinetic = initial.kinetic;
  while (solver.time() < end_time) {
    solver.step(solver.stable_time_step());
    max_kinetic = std::max(max_kinetic, solver.energies().kinetic);
  }
  const core::Energies end = solver.energies();
  const double error = core::energy_balance_error(end, initial, max_kinetic);
  const double stored = end.internal - end.plastic - end.viscous;
  const double held = elastic(solver);
  std::printf(
      "DP collapse %s: balance %.3g, external work %.4g, plastic %.4g, viscous %.4g, hourglass "
      "%.4g, kinetic %.4g, internal - plastic - viscous %.4g against the stresses' %.4g\n",
      label, error, end.external_work, end.plastic, end.viscous, end.hourglass, end.kinetic, stored,
      held);
  EXPECT_LT(std::abs(error), balance_tolerance) << label;
  EXPECT_GT(end.plastic, 0.05 * end.external_work) << label;
  EXPECT_NEAR(stored, held, 0.01 * end.external_work) << label;
}

TEST(DruckerPragerRuns, CollapsingColumnFlowsAndBalancesItsEnergy) {
  // A 20 x 5 x 40 mm column of cohesionless sand on a frictionless base in plane strain,
  // loaded by gravity from zero stress: its free sides yield at once and it spreads. Reference:
  // over 10 ms the energy balance (core::energy_balance_error) within 0.5 %, plastic work of at
  // least 5 % of the work of gravity, and internal energy less plastic and bulk-viscous work
  // equal to the elastic energy the stresses hold, sum m (s:s/4G + sigma_m^2/2K) / rho, within
  // 1 % of the work of gravity (the work is booked per step over the current density).
  const std::string sand = [] {
    std::string s = kSand;
    s.replace(s.find("cohesion = 0.01"), 15, "cohesion = 0");
    return s;
  }();
  const std::string column = R"(
[[bodies]]
name = "column"
material = "sand"
shape = { box = { min = [0, 0, 0], max = [20, 5, 40] } }
)";
  {
    const core::Scene scene = core::parse_scene(run_header(10.0, true) + R"(
[grid]
cell = 5
min = [-40, 0, 0]
max = [60, 5, 50]
boundary = { ymin = "symmetric", ymax = "symmetric", zmin = "symmetric" }
)" + sand + column,
                                                "dp_collapse_mpm.toml");
    mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
    check_energies("MPM", solver, 10.0, 0.005, [&](const mpm::MpmSolver& s) {
      const auto& p = s.particles();
      std::vector<double> density(p.size());
      for (std::size_t i = 0; i < p.size(); ++i) density[i] = p.mass[i] / p.volume[i];
      return stored_elastic_energy(scene.materials[0], p.stress, p.mass, density);
    });
  }
  {
    const core::Scene scene = core::parse_scene(run_header(10.0, true) + sand + column + R"(
discretisation = "hexahedra"
mesh = { divisions = [4, 1, 8] }

[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1], tolerance = 1e-9 } }
fixed = ["z"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0], tolerance = 1e-9 } }
fixed = ["y"]
[[constraints]]
nodes = { plane = { point = [0, 5, 0], normal = [0, 1, 0], tolerance = 1e-9 } }
fixed = ["y"]
)",
                                                "dp_collapse_fe.toml");
    fem::FeSolver solver(scene);
    check_energies("FE", solver, 10.0, 0.005, [&](const fem::FeSolver& s) {
      const auto& h = s.hexahedra();
      return stored_elastic_energy(scene.materials[0], h.stress, h.point_mass, h.density);
    });
  }
}

}  // namespace
}  // namespace afemp
