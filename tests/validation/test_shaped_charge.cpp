// The shaped charge of examples/shaped_charge, validation case V9 (validation label): a
// 60-degree copper liner, 2 mm thick, driven by a 40 mm PBX 9501 charge, quarter model, 20 us.
// Three runs: 0.75 mm cells (the example) with and without splitting, and 0.6 mm cells with
// splitting; and the axisymmetric form of the charge (axisymmetric.toml) at four cell sizes. Each
// ctest test is a process of its own, so under ctest the 0.75 mm run with splitting runs in both;
// `afemp_validation --gtest_filter='ShapedCharge.*'` runs it once.
//
// References and marks (docs/validation.md, V9):
// - The jet's tip velocity against the PER estimate worked from the charge's geometry alone
//   (analysis/shaped_charge_per.hpp, docs/explosives.md "The PER estimate": Gurney collapse
//   velocities, Taylor's deflection, the steady collapse of Pugh, Eichelberger & Rostoker
//   1952): 7.70 km/s. Within 15 % at every cell size, and converged: each finer run within 3 %
//   of the coarser (0.75 -> 0.6 -> 0.5 mm). V9 is not met for all that: at 0.4 mm (not run
//   here: about an hour) the head falls 4.2 % further, to -17.2 % of the estimate
//   (examples/shaped_charge/README.md). The tip velocity is that of the head of the
//   coherent jet at 20 us: scanning the jet (the liner's particles within 3 mm of the axis) in
//   1 mm slices from its front back, the first two neighbouring slices that each hold at least
//   0.02 % of the liner's mass per mm; their mass-weighted mean axial velocity. Ahead of the
//   head a needle of apex material runs along the axis: about 5 mg (0.05 % of the quarter
//   liner's 10 g), whose speed does not converge (7.5, 6.8 and 6.4 km/s at the three sizes);
//   it is printed, with the leading 0.05 % and 0.5 % of the liner's mass that earlier forms
//   of this test took as the tip (examples/shaped_charge/README.md says why they changed).
// - Splitting keeps the stretched jet continuous (the claim of the 2020 MPM paper on explosion
//   and impact, docs/references.md, item 3): with the liner splitting along the jet's axis
//   every cell of the column of cells on the axis from the liner's base (z = 50) to the head
//   holds a liner particle, at every cell size (at 0.75 and 0.6 mm to the needle's tip too);
//   without splitting the 0.75 mm jet leaves empty cells there (its particles drift more than a
//   cell apart).
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

// The jet's mass along the axis: the liner's particles within 3 mm of the axis beyond z = 50,
// in 1 mm bins of z (bin k holds k <= z < k + 1), each bin's mass and momentum along z.
struct AxisBins {
  std::map<long, std::pair<double, double>> bins;  // k -> (mass, mass * vz)
  double mass(long k) const {
    const auto it = bins.find(k);
    return it == bins.end() ? 0.0 : it->second.first;
  }
  double momentum(long k) const {
    const auto it = bins.find(k);
    return it == bins.end() ? 0.0 : it->second.second;
  }
};

AxisBins axis_bins(const Particles& p) {
  AxisBins a;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    if (p.body[i] != 1 || std::hypot(x.x, x.y) >= 3.0 || x.z <= 50.0) continue;
    auto& b = a.bins[std::lround(std::floor(x.z))];
    b.first += p.mass[i], b.second += p.mass[i] * p.velocity[i].z;
  }
  return a;
}

// The head of the coherent jet: scanning 1 mm bins from the front back, the first two
// neighbouring bins that each hold at least `line_mass` (mass per mm); its velocity is their
// mass-weighted mean vz. What lies ahead of it is the needle: its mass and mean vz.
struct Head {
  double z = 0.0;   // the front of the head's leading bin
  double vz = 0.0;  // m/s
  double needle_mass = 0.0, needle_vz = 0.0;
};

Head coherent_head(const AxisBins& a, double line_mass) {
  Head h;
  double m = 0.0, mv = 0.0;
  for (auto it = a.bins.rbegin(); it != a.bins.rend(); ++it) {
    const long k = it->first;
    if (it->second.first >= line_mass && a.mass(k - 1) >= line_mass) {
      h.z = static_cast<double>(k + 1);
      h.vz = (it->second.second + a.momentum(k - 1)) / (it->second.first + a.mass(k - 1));
      break;
    }
    m += it->second.first, mv += it->second.second;
  }
  h.needle_mass = m;
  h.needle_vz = m > 0.0 ? mv / m : 0.0;
  return h;
}

struct Jet {
  Column at12, at20;
  Head head;                   // the coherent jet's head at 20 us
  Tip lead_small, lead_large;  // the leading 0.05 % and 0.5 % of the liner's mass at 20 us
  AxisBins bins20;             // the jet's mass along the axis at 20 us
  double liner_mass = 0.0;
  double front_speed = 0.0;  // m/s: the continuous front's advance from 12 to 20 us
  double energy_error = 0.0;
  double seconds = 0.0;
  std::size_t particles = 0;
};

constexpr double head_line_mass = 0.0002;  // of the liner's mass, per mm

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
  advance(0.020);
  jet.at20 = axis_column(solver.particles(), h);
  jet.bins20 = axis_bins(solver.particles());
  jet.head = coherent_head(jet.bins20, head_line_mass * liner_mass);
  jet.lead_small = leading_mass(solver.particles(), 0.0005 * liner_mass);
  jet.lead_large = leading_mass(solver.particles(), 0.005 * liner_mass);
  jet.liner_mass = liner_mass;
  jet.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  jet.energy_error = core::energy_balance_error(solver.energies(), e0, max_kinetic);
  jet.front_speed = (jet.at20.front - jet.at12.front) / 0.008;
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
        "%.0f m/s; the head at z = %.0f mm, vz %.0f m/s; the needle ahead of it %.2f mg, mean vz "
        "%.0f m/s; leading 0.05 %% of the liner's mass at z = %.1f mm, mean vz %.0f m/s, "
        "leading 0.5 %% at z = %.1f mm, mean vz %.0f m/s; %zu particles at the end; energy "
        "balance %+.2f %%; %.0f s\n",
        cell.c_str(), splitting ? "on" : "off", jet.at20.tip, jet.at20.front, jet.at20.empty,
        jet.front_speed, jet.head.z, jet.head.vz, 1e3 * jet.head.needle_mass, jet.head.needle_vz,
        jet.lead_small.z, jet.lead_small.vz, jet.lead_large.z, jet.lead_large.vz, jet.particles,
        100.0 * jet.energy_error, jet.seconds);
    // The jet along the axis at 20 us, 2 mm slices from its front back: where the needle ends
    // and the head begins.
    std::printf("  2 mm slices from the front (z from, mass mg, mean vz m/s):");
    const long front = jet.bins20.bins.rbegin()->first;
    for (long k = front; k > front - 50; k -= 2) {
      const double m = jet.bins20.mass(k) + jet.bins20.mass(k - 1);
      const double mv = jet.bins20.momentum(k) + jet.bins20.momentum(k - 1);
      std::printf(" [%ld %.2f %.0f]", k - 1, 1e3 * m, m > 0.0 ? mv / m : 0.0);
    }
    std::printf("\n");
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
  const double reference = per.collapse.jet_velocity;
  std::printf(
      "V9 PER estimate %.0f m/s (the element at z = %.2f mm, V0 %.0f m/s, delta %.2f deg, "
      "beta %.2f deg)\n",
      reference, per.z, per.collapse_velocity, per.collapse.delta * 180.0 / std::numbers::pi,
      per.collapse.beta * 180.0 / std::numbers::pi);
  const Jet* coarser = nullptr;
  for (const char* cell : {"0.75", "0.6", "0.5"}) {
    const Jet& jet = jet_run(cell, true);
    std::printf(
        "V9 tip velocity (the coherent jet's head at 20 us) at %s mm: %.0f m/s, %+.1f %% "
        "of the PER estimate (mark 15 %%)",
        cell, jet.head.vz, 100.0 * (jet.head.vz / reference - 1.0));
    if (coarser)
      std::printf("; change from the coarser %+.1f %% (mark 3 %%)",
                  100.0 * (jet.head.vz / coarser->head.vz - 1.0));
    std::printf("\n");
    std::fflush(stdout);
    EXPECT_NEAR(jet.head.vz, reference, 0.15 * reference) << cell << " mm";
    if (coarser) {
      EXPECT_LT(std::abs(jet.head.vz / coarser->head.vz - 1.0), 0.03) << cell << " mm";
    }
    // The jet whole from the liner's base to its head; a needle ahead of it holds less than
    // 0.1 % of the liner's mass.
    EXPECT_GE(jet.at20.front, jet.head.z) << cell << " mm";
    EXPECT_LT(jet.head.needle_mass, 0.001 * jet.liner_mass) << cell << " mm";
    EXPECT_LT(std::abs(jet.energy_error), 0.03) << cell << " mm";
    coarser = &jet;
  }
}

// V9 with the axisymmetric model (examples/shaped_charge/axisymmetric.toml: the same charge in
// its r-z plane, each particle a ring, unsplit as the example is) at
// 0.4, 0.3, 0.25 and 0.2 mm cells, the head measured as above (the liner's mass is the whole
// ring's; the threshold is the same share of it). Reference and marks as above: converged
// (each finer run within 3 % of the coarser) and the energy balance within 3 % are asserted.
// The PER mark is printed, not asserted: the heads lie 23-26 % under the estimate and fall
// slowly with the cell (examples/shaped_charge/README.md, "The axisymmetric model"), so V9's
// 15 % is not met by this model either.
TEST(ShapedCharge, AxisymmetricTipVelocityConverges) {
  const double reference = per_estimate().collapse.jet_velocity;
  const std::string example = test::example_text("shaped_charge/axisymmetric.toml");
  const Jet* coarser = nullptr;
  static std::map<std::string, Jet> runs;
  for (const char* cell : {"0.4", "0.3", "0.25", "0.2"}) {
    const std::string text =
        std::string(cell) == "0.25"
            ? example
            : test::replaced(example, "cell = 0.25", "cell = " + std::string(cell));
    const Jet& jet = runs[cell] = run_jet(text);
    std::printf(
        "V9 axisymmetric, %s mm: the head at z = %.0f mm, vz %.0f m/s, %+.1f %% of the PER "
        "estimate (mark 15 %%, not asserted)",
        cell, jet.head.z, jet.head.vz, 100.0 * (jet.head.vz / reference - 1.0));
    if (coarser)
      std::printf("; change from the coarser %+.1f %% (mark 3 %%)",
                  100.0 * (jet.head.vz / coarser->head.vz - 1.0));
    std::printf(
        "; the needle ahead %.2f mg; on the axis continuous to z = %.1f mm (%d empty cells "
        "to the tip at %.1f); %zu particles at the end; energy balance %+.2f %%; %.0f s\n",
        1e3 * jet.head.needle_mass, jet.at20.front, jet.at20.empty, jet.at20.tip, jet.particles,
        100.0 * jet.energy_error, jet.seconds);
    std::fflush(stdout);
    if (coarser) {
      EXPECT_LT(std::abs(jet.head.vz / coarser->head.vz - 1.0), 0.03) << cell << " mm";
    }
    EXPECT_LT(std::abs(jet.energy_error), 0.03) << cell << " mm";
    coarser = &jet;
  }
}

}  // namespace
}  // namespace afemp::mpm
