// The PER estimate of a shaped charge's jet tip (analysis/shaped_charge_per.hpp) against values
// worked by hand: Gurney's sandwich in its open-faced and symmetric limits, Lavrentiev's
// collapse (no deflection: Vj = V0 cot(alpha / 2)), and one element of examples/shaped_charge
// worked through step by step (docs/explosives.md, "The PER estimate"), and the tip as the
// elements' merger, which keeps their momentum.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/shaped_charge_per.hpp"
#include "conical_charge_example.hpp"

namespace afemp::analysis {
namespace {

constexpr double degree = std::numbers::pi / 180.0;
using test::example_charge;

TEST(ShapedChargePer, GurneySandwichMeetsItsOpenFacedAndSymmetricForms) {
  // Open-faced, M/C = 0.5: (((1 + 1)^3 + 1) / (6 * 1.5) + 0.5)^(-1/2) = 1.5^(-1/2).
  EXPECT_NEAR(gurney_tamped_sandwich(0.5, 0.0), 1.0 / std::sqrt(1.5), 1e-12);
  // Symmetric, M = N = C / 2: (2 * 0.5 + 1/3)^(-1/2).
  EXPECT_NEAR(gurney_tamped_sandwich(0.5, 0.5), 1.0 / std::sqrt(4.0 / 3.0), 1e-12);
}

TEST(ShapedChargePer, WithoutDeflectionTheJetIsLavrentievs) {
  // A sweep far faster than the wall: delta -> 0, beta -> alpha, Vj = V0 cot(alpha / 2),
  // Vs = V0 tan(alpha / 2).
  const PerCollapse c = per_steady_collapse(1000.0, 30.0 * degree, 1e16);
  EXPECT_NEAR(c.jet_velocity, 1000.0 / std::tan(15.0 * degree), 1e-6);
  EXPECT_NEAR(c.slug_velocity, 1000.0 * std::tan(15.0 * degree), 1e-6);
}

TEST(ShapedChargePer, AnElementOfTheExampleAsWorkedByHand) {
  // At z = 25: r_o = (25 - 15.359) tan 30 = 5.5662, r_i = r_o - 2 / cos 30 = 3.2568;
  // C/M = 1.84 (400 - 30.983) / (8.93 (30.983 - 10.607)) = 3.7316; N/C = 7.85 (484 - 400) /
  // (1.84 * 369.017) = 0.9712; A = (1 + 2 / 3.7316) / (1 + 2 * 0.9712) = 0.5221, V_G = 2900
  // (0.2502 + 0.2647 + 0.2680)^(-1/2) = 3277.7; reach sqrt(2 * 3.7e4 * 3.7607 / (8.93e-3 * 2))
  // = 3947.4, so V0 = 3277.7; the ray to (5.5662, 25) is 12.55 degrees off the axis, 17.45
  // off the wall: U = 8800 / cos 17.45 = 9224.4; delta = asin(3277.7 / 18448.8) = 10.234
  // degrees, beta = 50.468; Vj = 3277.7 cos 15 / sin 25.234 = 7426.6, Vs = 3277.7 sin 15 /
  // cos 25.234 = 937.8.
  const LinerElement e = per_liner_element(example_charge(), 25.0);
  EXPECT_NEAR(e.outer_radius, 5.5662, 1e-4);
  EXPECT_NEAR(e.inner_radius, 3.2568, 1e-4);
  EXPECT_NEAR(e.c_over_m, 3.7316, 1e-4);
  EXPECT_NEAR(e.n_over_c, 0.9712, 1e-4);
  EXPECT_NEAR(e.gurney_velocity, 3277.7, 0.1);
  EXPECT_NEAR(e.reach_velocity, 3947.4, 0.1);
  EXPECT_EQ(e.collapse_velocity, e.gurney_velocity);
  EXPECT_NEAR(e.sweep_velocity, 9224.4, 0.1);
  EXPECT_NEAR(e.collapse.delta / degree, 10.234, 1e-3);
  EXPECT_NEAR(e.collapse.beta / degree, 50.468, 1e-3);
  EXPECT_NEAR(e.collapse.jet_velocity, 7426.6, 0.1);
  EXPECT_NEAR(e.collapse.slug_velocity, 937.8, 0.1);
}

TEST(ShapedChargePer, TheTipIsWhereTheGurneyVelocityMeetsTheReach) {
  // Toward the apex the Gurney velocity rises and the reach falls; the fastest jet comes from
  // the element where they meet: z = 23.71 (r_i = 2.511, C/M = 4.584, V0 = 3463.5 against a
  // reach of 3466.4), U = 9279.9, delta = 10.755 degrees, Vj = 7699.2.
  const LinerElement tip = per_tip_element(example_charge());
  EXPECT_NEAR(tip.z, 23.71, 0.01);
  EXPECT_NEAR(tip.collapse.jet_velocity, 7699.2, 0.5);
  EXPECT_NEAR(tip.gurney_velocity, tip.reach_velocity, 5.0);
}

TEST(ShapedChargePer, TheMergedTipKeepsTheElementsMomentum) {
  // The elements from the inner apex (19.359) to the fastest (23.71) and on while their jets
  // outrun the gathered tip, merged with their mass and momentum kept. Worked independently (a
  // short script with the formulas of docs/explosives.md, elements every 0.01 mm): the last
  // element to join is at z = 27.05, the tip's jet 0.5661 g for the whole charge, at 7020.6 m/s,
  // 8.8 % below the fastest element's 7699.2.
  const ConicalCharge q = example_charge();
  const MergedTip tip = per_merged_tip(q);
  EXPECT_NEAR(tip.last_z, 27.05, 0.011);
  EXPECT_NEAR(2.0 * std::numbers::pi * tip.jet_mass, 0.5661, 0.0005);
  EXPECT_NEAR(tip.velocity, 7020.6, 1.0);
  // Momentum: the tip's is the sum of its elements' (each ring's jet share sin^2(beta / 2)).
  const double inner_apex = per_inner_apex(q);
  double mass = 0.0, momentum = 0.0;
  for (int k = 1; inner_apex + k * per_element_step <= tip.last_z + 1e-9; ++k) {
    const LinerElement e = per_liner_element(q, inner_apex + k * per_element_step);
    const double share = std::pow(std::sin(0.5 * e.collapse.beta), 2);
    const double ring = 0.5 * q.liner_density *
                        (std::pow(e.outer_radius, 2) - std::pow(e.inner_radius, 2)) *
                        per_element_step;
    mass += share * ring, momentum += share * ring * e.collapse.jet_velocity;
  }
  EXPECT_NEAR(tip.jet_mass, mass, 1e-12 * mass);
  EXPECT_NEAR(tip.velocity, momentum / mass, 1e-9 * tip.velocity);
  // It ends where the next element's jet no longer catches it, and it is slower than the fastest.
  EXPECT_LT(per_liner_element(q, tip.last_z + per_element_step).collapse.jet_velocity,
            tip.velocity);
  EXPECT_GE(per_liner_element(q, tip.last_z).collapse.jet_velocity, tip.velocity);
  EXPECT_LT(tip.velocity, per_tip_element(q).collapse.jet_velocity);
}

}  // namespace
}  // namespace afemp::analysis
