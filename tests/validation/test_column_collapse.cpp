// Collapse of a granular column against a back wall in plane strain (label `validation`):
// examples/column_collapse/scene.toml, the aluminium-rod experiment of Bui, Fukagawa, Sako & Ohno
// (2008), a column 200 mm long and 100 mm high (a = 0.5), Drucker-Prager with the paper's constants
// (phi 19.8 deg, c 0, plane-strain fit, no dilatancy, E 0.84 MPa, nu 0.3), starting from its
// geostatic stress (K0 = 1 - sin phi), on a base with Coulomb friction tan phi met at the
// particles' boundary, uGIMP with APIC, 5 mm cells. The final free surface is measured on the
// particles (analysis/deposit_metrics.hpp: bins of one cell, the top particle plus half a spacing).
// Reference: the experiment's final surface, which the paper gives only as a plot. Its values here
// are read from the third-party digitisation of that plot in the ti-DEMPM repository
// (Yihao-Shi/ti-DEMPM, Validation/MPM/Figure_4.png, "Experiment (Bui et al.): Final geometry"),
// read back from the PNG (examples/column_collapse/README.md): height 100 mm at the wall, 76.8 /
// 47.3 / 22.8 mm at x = 100 / 200 / 300 mm, and the surface down to 10 mm (0.1 h0) at L10 = 367 mm.
// Pass marks: L10 within 10 %; the wall height within 5 mm (the column's top corner stays in place
// in the experiment, h_inf / h0 = 1 for a <= 0.65, Nguyen, Bui & Fukagawa 2015); the heights at
// 100, 200, 300 mm within 10 mm (0.1 h0, the reading error of a twice-digitised plot and the rods'
// 1-1.5 mm size included); the deposit at rest (kinetic energy below 1e-4 of the work gravity did).
// Energy: APIC's transfers smooth away velocity that no column of the balance books (the run
// summary says so), so the balance shows a loss, -7.8 % at 5 mm cells (V1's elastic bar with APIC:
// -9.3 %); the check is that no energy is created (error below +1 %) and that the loss stays below
// 15 %. The same scene with FLIP closes its balance to 0.02 % (README). Measured at 5 mm cells
// (afemp run, 1 thread, the shared 2-core VM): L10 380.4 mm (+3.7 %), h(0) 100.0, h(100) 77.8,
// h(200) 48.3, h(300) 22.6, farthest particle 522 mm, at rest (1.4e-6), balance -7.8 %. At 5 mm
// the surface near 10 mm is two cells high, and a particle row more or less in the thin tail (it
// slopes about 1 in 15) would move L10 by about 40 mm: the 10 % mark is a real test of the tail,
// not a loose one. The wall time is printed, not asserted.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "analysis/deposit_metrics.hpp"
#include "analysis/reference_checks.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "example_text.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::mpm {
namespace {

constexpr double L10_ref = 367.0, wall_ref = 100.0;
constexpr double x_ref[3] = {100.0, 200.0, 300.0}, h_ref[3] = {76.8, 47.3, 22.8};

struct Deposit {
  double L10 = 0.0, wall = 0.0, h[3] = {}, tip = 0.0;
  double rest = 0.0;  // final kinetic energy / work of gravity
  core::RunSummary summary;
};

Deposit run_collapse(const std::string& text, const std::string& name, double cell) {
  const core::Scene scene = core::parse_scene(text, name);
  MpmModel model(scene);
  Deposit d;
  d.summary = analysis::run(model, scene, {});
  const double skin = 0.25 * cell;  // half the spacing of 2 particles per cell
  const analysis::DepositProfile p = analysis::deposit_profile(
      model.body_points(0).position, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, cell, skin);
  d.L10 = analysis::runout_to_height(p, 10.0);
  d.wall = analysis::surface_height(p, 0.0);
  for (int k = 0; k < 3; ++k) d.h[k] = analysis::surface_height(p, x_ref[k]);
  d.tip = p.tip;
  const core::RunSummary& s = d.summary;
  d.rest = s.final.kinetic / s.final.external_work;
  std::printf(
      "%s: L10 %.1f mm (ref %.0f, %+.1f %%, tolerance 10 %%); wall height %.1f mm (ref %.0f "
      "+- 5); h(100) %.1f (ref %.1f), h(200) %.1f (ref %.1f), h(300) %.1f (ref %.1f) +- 10; "
      "farthest particle %.0f mm (ref about 500, not asserted)\n",
      name.c_str(), d.L10, L10_ref, 100.0 * (d.L10 / L10_ref - 1.0), d.wall, wall_ref, d.h[0],
      h_ref[0], d.h[1], h_ref[1], d.h[2], h_ref[2], d.tip);
  std::printf(
      "  t %.0f ms, %ld steps, %zu particles, %.1f s wall on %d thread(s); kinetic energy at "
      "the end %.2e of gravity's work; energy error %+.2f %% (largest %.2f %%)\n",
      s.time, s.steps, s.particles, s.wall_seconds, core::thread_count(), d.rest,
      100.0 * s.energy_error, 100.0 * s.max_energy_error);
  std::fflush(stdout);
  return d;
}

void expect_deposit(const Deposit& d) {
  EXPECT_NEAR(d.L10, L10_ref, 0.10 * L10_ref);
  EXPECT_NEAR(d.wall, wall_ref, 5.0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(d.h[k], h_ref[k], 10.0) << "x " << x_ref[k];
  EXPECT_LT(d.rest, 1e-4);
  EXPECT_LT(d.summary.energy_error, 0.01);
  EXPECT_GT(d.summary.energy_error, -0.15);
}

TEST(ColumnCollapse, FinalSurfaceMatchesBuiEtAlExperiment) {
  expect_deposit(run_collapse(test::example_text("column_collapse/scene.toml"), "5 mm cells", 5.0));
}

}  // namespace
}  // namespace afemp::mpm
