// The shaped charge of examples/shaped_charge (validation label): a 60-degree copper liner,
// 2 mm thick, driven by a 40 mm PBX 9501 charge, quarter model, 0.75 mm cells, 20 us (about
// 2 min on 2 threads with splitting, 1 min without).
//
// Reference: the claim of the 2020 MPM paper on explosion and impact (docs/references.md,
// item 3) that splitting keeps a stretched jet continuous, made testable. At 20 us the jet
// reaches from the liner's base plane (z = 50) to about z = 156. With the liner splitting
// along the jet's axis, every cell of the column of cells on the axis between z = 50 and the
// tip holds a liner particle; without splitting, the stretched jet leaves empty cells there
// (its particles drift more than a cell apart). Both runs keep the energy balance within 3 %
// (the mark for explosive cases; the released chemical energy booked as a source).
// This holds at the example's 0.75 mm; at 0.5 mm the split jet's tip draws away from the rest
// (examples/shaped_charge/README.md).
//
// Not asserted: the jet's tip velocity. No published value for this charge (or for the
// paper's, whose table is an image) was reachable. The test prints it, with the run's time and
// particle count: the advance of the jet's continuous front (the axis column's last cell
// reached from z = 50 without an empty cell) from 12 to 20 us, and the mean axial velocity of
// the liner particles in the front's last 1.5 mm at 20 us.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>

#include "afemp/energies.hpp"
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

struct Jet {
  Column at12, at20;
  double front_speed = 0.0;  // m/s
  double front_vz = 0.0;     // m/s
  double energy_error = 0.0;
  double seconds = 0.0;
  std::size_t particles = 0;
};

Jet run_jet(const std::string& text) {
  const core::Scene scene = core::parse_scene(text, "scene.toml");
  const double h = scene.mpm.grid.cell;
  MpmSolver solver(scene, generate_particles(scene));
  const core::Energies e0 = solver.energies();
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
  jet.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  jet.energy_error = core::energy_balance_error(solver.energies(), e0, max_kinetic);
  jet.front_speed = (jet.at20.front - jet.at12.front) / 0.008;
  const Particles& p = solver.particles();
  double m = 0.0, mv = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.position[i];
    if (p.body[i] == 1 && x.x < h && x.y < h && x.z > jet.at20.front - 1.5 && x.z <= jet.at20.front)
      m += p.mass[i], mv += p.mass[i] * p.velocity[i].z;
  }
  jet.front_vz = m > 0.0 ? mv / m : 0.0;
  jet.particles = p.size();
  return jet;
}

TEST(ShapedCharge, SplittingKeepsTheJetContinuous) {
  const std::string text = test::example_text("shaped_charge/scene.toml");
  const Jet on = run_jet(text);
  const Jet off =
      run_jet(test::replaced(text, "splitting = { bodies = [\"liner\"], axes = [\"z\"] }", ""));
  for (const auto& [name, jet] : {std::pair{"on", on}, std::pair{"off", off}})
    std::printf(
        "splitting %s: at 20 us the liner reaches z = %.1f mm on the axis, continuous "
        "to %.1f mm (%d empty cells beyond); front advance 12-20 us %.0f m/s, mean vz "
        "of its last 1.5 mm %.0f m/s; %zu particles at the end; energy balance %+.2f %%; "
        "%.0f s\n",
        name, jet.at20.tip, jet.at20.front, jet.at20.empty, jet.front_speed, jet.front_vz,
        jet.particles, 100.0 * jet.energy_error, jet.seconds);
  EXPECT_GT(on.at20.tip, 120.0);  // the jet has formed and run out 70 mm past the liner's base
  EXPECT_EQ(on.at20.empty, 0);
  EXPECT_GT(off.at20.empty, 0);
  EXPECT_LT(std::abs(on.energy_error), 0.03);
  EXPECT_LT(std::abs(off.energy_error), 0.03);
}

}  // namespace
}  // namespace afemp::mpm
