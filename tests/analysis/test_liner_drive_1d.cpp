// The one-dimensional cylindrical drive (analysis/liner_drive_1d.hpp) against Gurney's
// formulas where they hold (the cylinder test, and a ring imploding far from the axis, where its
// slice is a flat tamped sandwich), its energy kept, and what it gives the example shaped
// charge's liner on its way to the axis against the PER estimate's collapse velocities
// (docs/explosives.md, "What the explosive gives on the way to the axis").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "analysis/liner_drive_1d.hpp"
#include "analysis/shaped_charge_per.hpp"
#include "conical_charge_example.hpp"

namespace afemp::analysis {
namespace {

using test::copper;
using test::pbx9501;
using test::steel;

// Cooper (1996) gives sqrt(2E) = 2.90 km/s for PBX 9404, the nearest explosive in his table
// (docs/explosives.md).
constexpr double gurney_sqrt_2e = 2900.0;

double cylinder_test(double zones_per_mm, double& energy_ratio, bool all_at_once = false) {
  Ring1d x = pbx9501(), c = copper();
  x.inner = 0.0;
  x.outer = c.inner = 12.7;
  c.outer = 15.3;
  Drive1dSettings s;
  s.zones_per_length = zones_per_mm;
  s.end_time = 0.1;
  s.stop_outer_radius = 3.0 * 15.3;
  s.lighting_time = [all_at_once](double r) { return all_at_once ? -1.0 : r / 8800.0; };
  const Drive1dResult run = cylindrical_drive_1d({x, c}, 1, s);
  energy_ratio = run.energy_ratio;
  return run.history.back().mean_velocity;
}

TEST(LinerDrive1d, CylinderTestReachesGurneysVelocityAndKeepsEnergy) {
  // Gurney's cylinder, V = sqrt(2E) (M/C + 1/2)^(-1/2) (Cooper 1996), for the tube expanded
  // three-fold, where the cylinder test's wall is within a few per cent of its final speed.
  const double m_over_c = 8.93e-3 * (15.3 * 15.3 - 12.7 * 12.7) / (1.84e-3 * 12.7 * 12.7);
  const double gurney = gurney_sqrt_2e / std::sqrt(m_over_c + 0.5);
  double energy10 = 0.0, energy20 = 0.0;
  const double v10 = cylinder_test(10.0, energy10);
  const double v20 = cylinder_test(20.0, energy20);
  std::printf(
      "cylinder test: %.0f and %.0f m/s at 10 and 20 zones per mm; Gurney %.0f m/s; "
      "energy kept to %.2e, %.2e\n",
      v10, v20, gurney, energy10 - 1.0, energy20 - 1.0);
  // Within 8 %: Gurney's formulas hold to a few per cent, and sqrt(2E) is PBX 9404's (+5.3 %
  // here when written). The programmed burn's front costs 0.4 % of the energy.
  EXPECT_NEAR(v20 / gurney, 1.0, 0.08);
  EXPECT_NEAR(v10 / v20, 1.0, 0.005);
  EXPECT_NEAR(energy20, 1.0, 0.01);
  // Lit all at once, with no burning front, the scheme keeps energy to its time-centring.
  double energy_at_once = 0.0;
  (void)cylinder_test(10.0, energy_at_once, true);
  std::printf("lit all at once: energy kept to %.2e\n", energy_at_once - 1.0);
  EXPECT_NEAR(energy_at_once, 1.0, 1e-3);
}

TEST(LinerDrive1d, ARingFarFromTheAxisMeetsTheFlatTampedSandwich) {
  // A copper ring 2 mm thick at a radius of 2 m under 13 mm of PBX 9501 and 2 mm of steel, lit
  // at the liner's face and burning outwards at D. Far from the axis the slice is Gurney's flat
  // tamped sandwich (Kennedy 1970), to 8 % as above (+6.1 % when written).
  Ring1d l = copper(), x = pbx9501(), c = steel();
  const double r0 = 2000.0;
  l.inner = r0;
  l.outer = x.inner = r0 + 2.0;
  x.outer = c.inner = r0 + 15.0;
  c.outer = r0 + 17.0;
  Drive1dSettings s;
  s.zones_per_length = 10.0;
  s.end_time = 0.012;  // the liner has moved about 20 mm, the products grown several-fold
  s.lighting_time = [r0](double r) { return (r - r0 - 2.0) / 8800.0; };
  s.stop_inner_radius = 0.0;
  const Drive1dResult run = cylindrical_drive_1d({l, x, c}, 0, s);
  const double v = -run.history.back().mean_velocity;
  const double sandwich = gurney_sqrt_2e * gurney_tamped_sandwich(8.93e-3 * 2.0 / (1.84e-3 * 13.0),
                                                                  7.85e-3 * 2.0 / (1.84e-3 * 13.0));
  std::printf("flat tamped sandwich: the ring at %.0f m/s after %.1f mm; Gurney %.0f m/s\n", v,
              r0 - run.history.back().inner_radius, sandwich);
  EXPECT_NEAR(v / sandwich, 1.0, 0.08);
  EXPECT_NEAR(run.energy_ratio, 1.0, 0.01);
}

TEST(LinerDrive1d, TheExampleLinerMeetsTheAxisFarBelowThePerEstimatesVelocity) {
  const ConicalCharge q = test::example_charge();  // sqrt(2E) 2900 m/s, as above
  std::printf(
      "z (mm) | r_i | the estimate's V0 | 1-D largest | at the axis (us) | ratio | PER "
      "jet with the 1-D V0\n");
  double fastest_jet = 0.0, tip_coarse = 0.0;
  for (double z : {21.0, 22.5, 23.71, 25.0, 27.0, 30.0, 32.5, 35.0, 40.0, 45.0}) {
    const SliceDrive d = liner_slice_drive(q, pbx9501(), copper(), steel(), z, 10.0);
    ASSERT_TRUE(d.reached_axis) << z;
    const double ratio = d.largest_velocity / d.element.collapse_velocity;
    std::printf("%5.2f | %5.2f | %4.0f | %4.0f | %4.0f (%.2f) | %.2f | %4.0f\n", z,
                d.element.inner_radius, d.element.collapse_velocity, d.largest_velocity,
                d.axis_velocity, 1e3 * d.axis_time, ratio, d.jet.jet_velocity);
    fastest_jet = std::max(fastest_jet, d.jet.jet_velocity);
    if (z == 23.71) tip_coarse = d.largest_velocity;
    // Where the estimate's tip element lies (23.71 mm) and ahead of it, the ring reaches under
    // a third of the estimate's velocity (0.22-0.24 when written); to 35 mm, under 70 %
    // (0.30-0.67); towards the base, where the explosive is thin and the way long, under 90 %.
    EXPECT_LT(ratio, z < 24.0 ? 1.0 / 3.0 : (z <= 35.0 ? 0.7 : 0.9)) << z;
  }
  // The tip element at twice the zones: the figures are the scheme's, not its zoning's.
  const SliceDrive fine = liner_slice_drive(q, pbx9501(), copper(), steel(), 23.71, 20.0);
  EXPECT_NEAR(tip_coarse / fine.largest_velocity, 1.0, 0.02);
  const LinerElement tip = per_tip_element(q);
  std::printf(
      "PER with the 1-D collapse velocities: fastest jet %.0f m/s; with Gurney's "
      "(the V9 estimate): %.0f m/s\n",
      fastest_jet, tip.collapse.jet_velocity);
  // 4165 against 7699 m/s when written.
  EXPECT_LT(fastest_jet, 0.6 * tip.collapse.jet_velocity);
}

}  // namespace
}  // namespace afemp::analysis
