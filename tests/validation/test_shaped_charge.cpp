// The shaped charge of examples/shaped_charge, validation case V9 (validation label): a
// 60-degree copper liner, 2 mm thick, driven by a 40 mm PBX 9501 charge, quarter model, 20 us.
// Three runs: 0.75 mm cells (the example) with and without splitting, and 0.6 mm cells with
// splitting. Each ctest test is a process of its own, so under ctest the 0.75 mm run with
// splitting runs in both; `afemp_validation --gtest_filter='ShapedCharge.*'` runs it once.
//
// References and marks (docs/validation.md, V9):
// - The jet's tip velocity against the PER estimate worked from the charge's geometry alone
//   (analysis/shaped_charge_per.hpp, docs/explosives.md "The PER estimate": Gurney collapse
//   velocities, Taylor's deflection, the steady collapse of Pugh, Eichelberger & Rostoker
//   1952): 7.70 km/s. Within 15 % at both cell sizes, and converged: the two within 3 %. The
//   tip velocity here is the mass-weighted mean axial velocity of the jet's leading 0.05 % of
//   the liner's mass (about 5 mg of the quarter's 10 g: its particles within 3 mm of the axis,
//   taken from the front back) at 20 us: a mass, so the same material at either cell size and with
//   or without splitting, and a stray particle barely moves it. The leading 0.5 % (the
//   "head", printed) has its centroid 34 mm behind the foremost particle in this thin jet
//   and averages over its velocity gradient.
// - Splitting keeps the stretched jet continuous (the claim of the 2020 MPM paper on explosion
//   and impact, docs/references.md, item 3): with the liner splitting along the jet's axis
//   every cell of the column of cells on the axis from the liner's base (z = 50) to the tip
//   holds a liner particle, at both cell sizes; without splitting the 0.75 mm jet leaves empty
//   cells there (its particles drift more than a cell apart).
// - Energy balance within 3 % (the chemical energy released booked as a source), every run.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "afemp/energies.hpp"
#include "analysis/shaped_charge_per.hpp"
#include "core/scene.hpp"
#include "example_text.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

// The liner's particles in the column of cells on the axis (0 <= x, y < h), beyond z = 50.
struct Column {
  double tip = 0.0;    // the largest z
  double front = 0.0;  // the top of the last cell reached from z = 50 without an empty cell
  int empty = 0;       // empty cells between z = 50 and the tip
};

Column axis_column(const Particles& p, double h) {
  Column c;
  std::set<long> cells;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    if (p.body[i] != 1 || x.x >= h || x.y >= h || x.z <= 50.0) continue;
    cells.insert(std::lround(std::floor(x.z / h)));
    c.tip = std::max(c.tip, x.z);
  }
  const long first = std::lround(std::floor(50.0 / h)) + 1;
  const long last = std::lround(std::floor(c.tip / h));
  long k = first;
  while (k <= last && cells.count(k)) ++k;
  c.front = static_cast<double>(k) * h;
  for (; k <= last; ++k) c.empty += cells.count(k) == 0;
  return c;
}

// The jet's leading mass: the liner's particles within 3 mm of the axis, taken from the
// largest z back until `mass` is reached; their mass-weighted mean z and axial velocity.
struct Tip {
  double z = 0.0;
  double vz = 0.0;  // m/s
};

Tip leading_mass(const Particles& p, double mass) {
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == 1 && std::hypot(p.position[i].x, p.position[i].y) < 3.0) near.push_back(i);
  std::sort(near.begin(), near.end(), [&](std::size_t a, std::size_t b) {
    return p.position[a].z > p.position[b].z || (p.position[a].z == p.position[b].z && a < b);
  });
  double m = 0.0, mz = 0.0, mv = 0.0;
  for (std::size_t k = 0; k < near.size() && m < mass; ++k) {
    const std::size_t i = near[k];
    m += p.mass[i], mz += p.mass[i] * p.position[i].z, mv += p.mass[i] * p.velocity[i].z;
  }
  return m > 0.0 ? Tip{mz / m, mv / m} : Tip{};
}

struct Jet {
  Column at12, at20;
  Tip tip16, tip20;          // the leading tip_share of the liner's mass
  Tip head20;                // the leading head_share
  double front_speed = 0.0;  // m/s: the continuous front's advance from 12 to 20 us
  double tip_speed = 0.0;    // m/s: the leading mass's advance from 16 to 20 us
  double energy_error = 0.0;
  double seconds = 0.0;
  std::size_t particles = 0;
};

constexpr double tip_share = 0.0005;  // of the liner's mass
constexpr double head_share = 0.005;

Jet run_jet(const std::string& text) {
  const core::Scene scene = core::parse_scene(text, "scene.toml");
  const double h = scene.mpm.grid.cell;
  MpmSolver solver(scene, generate_particles(scene));
  const core::Energies e0 = solver.energies();
  double liner_mass = 0.0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i)
    if (solver.particles().body[i] == 1) liner_mass += solver.particles().mass[i];
  double max_kinetic = e0.kinetic;
  const auto start = std::chrono::steady_clock::now();
  auto advance = [&](double end) {
    while (solver.time() < end - 1e-12) {
      solver.step(std::min(solver.stable_time_step(), end - solver.time()));
      max_kinetic = std::max(max_kinetic, solver.energies().kinetic);
    }
  };
  Jet jet;
  advance(0.012);
  jet.at12 = axis_column(solver.particles(), h);
  advance(0.016);
  jet.tip16 = leading_mass(solver.particles(), tip_share * liner_mass);
  advance(0.020);
  jet.at20 = axis_column(solver.particles(), h);
  jet.tip20 = leading_mass(solver.particles(), tip_share * liner_mass);
  jet.head20 = leading_mass(solver.particles(), head_share * liner_mass);
  jet.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  jet.energy_error = core::energy_balance_error(solver.energies(), e0, max_kinetic);
  jet.front_speed = (jet.at20.front - jet.at12.front) / 0.008;
  jet.tip_speed = (jet.tip20.z - jet.tip16.z) / 0.004;
  jet.particles = solver.particles().size();
  return jet;
}

// Each run once, shared by the tests: (cell, splitting) -> its jet.
const Jet& jet_run(const std::string& cell, bool splitting) {
  static std::map<std::pair<std::string, bool>, Jet> runs;
  const auto key = std::pair{cell, splitting};
  if (!runs.count(key)) {
    std::string text = test::example_text("shaped_charge/scene.toml");
    if (cell != "0.75") text = test::replaced(text, "cell = 0.75", "cell = " + cell);
    if (!splitting)
      text = test::replaced(text, "splitting = { bodies = [\"liner\"], axes = [\"z\"] }", "");
    runs[key] = run_jet(text);
    const Jet& jet = runs[key];
    std::printf(
        "%s mm cells, splitting %s: at 20 us the liner reaches z = %.1f mm on the axis, "
        "continuous to %.1f mm (%d empty cells beyond); continuous front's advance 12-20 us "
        "%.0f m/s; leading %.2f %% of the liner's mass at z = %.1f mm, mean vz %.0f m/s (its "
        "advance 16-20 us %.0f m/s), leading %.1f %% at z = %.1f mm, mean vz %.0f m/s; %zu "
        "particles at the end; energy balance %+.2f %%; "
        "%.0f s\n",
        cell.c_str(), splitting ? "on" : "off", jet.at20.tip, jet.at20.front, jet.at20.empty,
        jet.front_speed, 100.0 * tip_share, jet.tip20.z, jet.tip20.vz, jet.tip_speed,
        100.0 * head_share, jet.head20.z, jet.head20.vz, jet.particles, 100.0 * jet.energy_error,
        jet.seconds);
    std::fflush(stdout);
  }
  return runs[key];
}

// The PER estimate from the example's own numbers: its shapes, materials and detonation
// point, with PBX 9501's Gurney velocity (not in the scene; docs/explosives.md).
analysis::LinerElement per_estimate() {
  const core::Scene scene =
      core::parse_scene(test::example_text("shaped_charge/scene.toml"), "scene.toml");
  auto body = [&](const std::string& name) -> const core::BodySpec& {
    return *std::find_if(scene.bodies.begin(), scene.bodies.end(),
                         [&](const core::BodySpec& b) { return b.name == name; });
  };
  const auto& charge = std::get<core::CylinderShape>(body("charge").shape);
  const auto& liner = std::get<core::CylinderShape>(body("liner").shape);
  const auto& casing = std::get<core::CylinderShape>(body("case").shape);
  const auto& explosive = scene.materials[body("charge").material];
  analysis::ConicalCharge q;
  q.charge_radius = charge.radius;
  q.case_thickness = casing.radius - charge.radius;
  q.apex_z = liner.base.z + liner.axis.z * liner.length;
  q.half_angle = std::atan((liner.radius - liner.top_radius) / liner.length);
  q.wall = liner.wall;
  q.base_z = liner.base.z;
  q.detonation_z = scene.detonations.front().point.z;
  q.explosive_density = explosive.density;
  q.liner_density = scene.materials[body("liner").material].density;
  q.case_density = scene.materials[body("case").material].density;
  q.detonation_velocity = explosive.burn->detonation_velocity;
  q.cj_pressure = explosive.burn->cj_pressure;
  q.gurney_velocity = 2900.0;  // PBX 9404's sqrt(2E), Cooper (1996)
  return analysis::per_tip_element(q);
}

TEST(ShapedCharge, SplittingKeepsTheJetContinuous) {
  const Jet& on = jet_run("0.75", true);
  const Jet& off = jet_run("0.75", false);
  EXPECT_GT(on.at20.tip, 120.0);  // the jet has formed and run out 70 mm past the liner's base
  EXPECT_EQ(on.at20.empty, 0);
  EXPECT_GT(off.at20.empty, 0);
  EXPECT_LT(std::abs(on.energy_error), 0.03);
  EXPECT_LT(std::abs(off.energy_error), 0.03);
}

TEST(ShapedCharge, TipVelocityConvergesWithin15PercentOfThePerEstimate) {
  const analysis::LinerElement per = per_estimate();
  const Jet& fine = jet_run("0.6", true);
  const Jet& coarse = jet_run("0.75", true);
  const double change = (fine.tip20.vz - coarse.tip20.vz) / coarse.tip20.vz;
  std::printf(
      "V9 tip velocity (leading %.2f %% of the liner's mass, 20 us): %.0f m/s at 0.75 mm (%.0f "
      "s), %.0f m/s at 0.6 mm (%.0f s): change %+.1f %% (mark 3 %%). PER estimate %.0f m/s "
      "(the element at z = %.2f mm, V0 %.0f m/s, delta %.2f deg, beta %.2f deg): %+.1f %% and "
      "%+.1f %% (mark 15 %%)\n",
      100.0 * tip_share, coarse.tip20.vz, coarse.seconds, fine.tip20.vz, fine.seconds,
      100.0 * change, per.collapse.jet_velocity, per.z, per.collapse_velocity,
      per.collapse.delta * 180.0 / std::numbers::pi, per.collapse.beta * 180.0 / std::numbers::pi,
      100.0 * (coarse.tip20.vz / per.collapse.jet_velocity - 1.0),
      100.0 * (fine.tip20.vz / per.collapse.jet_velocity - 1.0));
  EXPECT_LT(std::abs(change), 0.03);
  EXPECT_NEAR(coarse.tip20.vz, per.collapse.jet_velocity, 0.15 * per.collapse.jet_velocity);
  EXPECT_NEAR(fine.tip20.vz, per.collapse.jet_velocity, 0.15 * per.collapse.jet_velocity);
  EXPECT_EQ(fine.at20.empty, 0);  // the finer jet is continuous too
  EXPECT_LT(std::abs(coarse.energy_error), 0.03);
  EXPECT_LT(std::abs(fine.energy_error), 0.03);
}

}  // namespace
}  // namespace afemp::mpm
