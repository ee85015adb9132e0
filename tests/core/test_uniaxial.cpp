// Uniaxial-stress update (core/materials/uniaxial_update.hpp) against closed forms of a bar:
// Hooke's law with Young's modulus, the bilinear curve of linear hardening (tangent
// E H / (E + H)), Johnson-Cook flow stress, elastic unloading, and zero lateral stress with an EOS.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/material_fixtures.hpp"
#include "core/materials/uniaxial_update.hpp"

namespace afemp::core {
namespace {

using fixtures::at_rest;
using fixtures::copper;
using fixtures::steel;

constexpr double kDt = 1e-4;

// Lateral stresses within the update's tolerance of the axial scale.
void expect_lateral_free(const PointState& p, const UniaxialUpdate& u, double axial_scale) {
  EXPECT_TRUE(u.converged);
  EXPECT_LE(std::abs(p.stress.yy), kUniaxialLateralTolerance * axial_scale);
  EXPECT_LE(std::abs(p.stress.zz), kUniaxialLateralTolerance * axial_scale);
}

TEST(UniaxialStress, ElasticBarFollowsYoungsModulusNotPWaveModulus) {
  // Reference: sigma = E eps (not (K + 4G/3) eps), lateral increment -nu d_eps exactly (the
  // first trial; 1e-14 rel), density rho0 / prod(1 + (1 - 2 nu) d_eps). Tol 1e-10 relative.
  const Material m = steel();
  PointState point = at_rest(m);
  const double d_eps = 1e-5;
  double density = m.density;
  for (int i = 1; i <= 10; ++i) {
    const UniaxialUpdate u = uniaxial_update(m, point, d_eps, kDt);
    density /= 1.0 + (1.0 - 2.0 * m.poisson_ratio) * d_eps;
    const double sigma = m.youngs_modulus * i * d_eps;
    EXPECT_NEAR(point.stress.xx, sigma, 1e-10 * sigma);
    expect_lateral_free(point, u, sigma);
    EXPECT_EQ(u.trials, 1);
    EXPECT_NEAR(u.lateral_strain_increment, -m.poisson_ratio * d_eps, 1e-14 * d_eps);
    EXPECT_NEAR(point.density, density, 1e-14 * density);
  }
}

TEST(UniaxialStress, LinearHardeningFollowsBilinearTangentModulus) {
  // Reference: sigma = Y + E_t (eps - Y/E) past yield, E_t = E H / (E + H); axial plastic
  // strain = equivalent = (sigma - Y) / H; lateral strain -nu sigma / E - eps_p / 2 (plastic
  // flow is isochoric). Radial return is exact for this proportional path, so 1e-8 relative
  // at every increment, the yield point falling inside increment 11. r(d_l) is linear on the
  // plastic branch, so the secant converges by the third trial.
  const double yield = 250.0, h = 2.0e3;
  const Material m = steel(J2Plasticity{yield, h});
  const double e = m.youngs_modulus, nu = m.poisson_ratio;
  const double e_t = e * h / (e + h);
  PointState point = at_rest(m);
  const double d_eps = 1.2e-4;
  double lateral = 0.0;
  int most_trials = 0;
  for (int i = 1; i <= 60; ++i) {
    const UniaxialUpdate u = uniaxial_update(m, point, d_eps, kDt);
    lateral += u.lateral_strain_increment;
    most_trials = std::max(most_trials, u.trials);
    const double eps = i * d_eps;
    const double sigma = eps <= yield / e ? e * eps : yield + e_t * (eps - yield / e);
    const double eps_p = eps <= yield / e ? 0.0 : (sigma - yield) / h;
    ASSERT_NEAR(point.stress.xx, sigma, 1e-8 * sigma) << "increment " << i;
    ASSERT_NEAR(point.plastic_strain, eps_p, 1e-8 * eps) << "increment " << i;
    ASSERT_NEAR(lateral, -nu * sigma / e - 0.5 * eps_p, 1e-8 * eps) << "increment " << i;
    expect_lateral_free(point, u, sigma);
  }
  EXPECT_GT(point.plastic_strain, 0.005);  // eps_y = 1.25e-3, eps = 7.2e-3
  EXPECT_LE(most_trials, 3);
}

TEST(UniaxialStress, PerfectPlasticityCapsAxialStressAtYield) {
  // Reference: H = 0: sigma = Y once eps > Y/E (1e-10 rel), and plastic increments are
  // isochoric: d_l = -d_eps / 2 (1e-8 rel), density unchanged (1e-14 rel).
  const double yield = 250.0;
  const Material m = steel(J2Plasticity{yield, 0.0});
  PointState point = at_rest(m);
  const double d_eps = 2e-4;
  for (int i = 1; i <= 30; ++i) {
    const double density = point.density;
    const UniaxialUpdate u = uniaxial_update(m, point, d_eps, kDt);
    expect_lateral_free(point, u, yield);
    if ((i - 1) * d_eps > yield / m.youngs_modulus) {
      EXPECT_NEAR(point.stress.xx, yield, 1e-10 * yield) << "increment " << i;
      EXPECT_NEAR(u.lateral_strain_increment, -0.5 * d_eps, 1e-8 * d_eps) << "increment " << i;
      EXPECT_NEAR(point.density, density, 1e-14 * density) << "increment " << i;
    }
  }
  EXPECT_NEAR(point.plastic_strain, 30 * d_eps - yield / m.youngs_modulus, 1e-10);
}

TEST(UniaxialStress, JohnsonCookAxialStressIsFlowStressAtPlasticStrain) {
  // Reference: with C = 0 and no thermal term, sigma = A + B eps_p^n at the point's plastic
  // strain, which is the axial plastic strain eps - sigma / E (both 1e-8 rel), to 5 %
  // strain in compression (the sign only flips the stress). At most 5 trials per increment.
  Material m = copper();
  JohnsonCook& jc = std::get<JohnsonCook>(m.strength);
  jc.C = 0.0;
  jc.m = 0.0;
  m.eos = NoEos{};
  ASSERT_FALSE(m.has_thermal_term());
  PointState point = at_rest(m);
  const double d_eps = -5e-4;
  int most_trials = 0, plastic_increments = 0;
  for (int i = 1; i <= 100; ++i) {
    const UniaxialUpdate u = uniaxial_update(m, point, d_eps, kDt);
    most_trials = std::max(most_trials, u.trials);
    const double sigma = -point.stress.xx;
    expect_lateral_free(point, u, sigma);
    if (point.plastic_strain == 0.0) continue;
    ++plastic_increments;
    const double flow = jc.A + jc.B * std::pow(point.plastic_strain, jc.n);
    ASSERT_NEAR(sigma, flow, 1e-8 * flow) << "increment " << i;
    const double axial_plastic = -i * d_eps - sigma / m.youngs_modulus;
    ASSERT_NEAR(point.plastic_strain, axial_plastic, 1e-8 * axial_plastic) << "increment " << i;
  }
  EXPECT_GT(plastic_increments, 95);  // yield at |eps| = A / E = 7.3e-4
  EXPECT_LE(most_trials, 5);
}

TEST(UniaxialStress, UnloadingFromPlasticStateIsElasticWithSlopeE) {
  // Reference: after plastic loading, each unloading increment changes sigma by E d_eps
  // (1e-10 of the peak), keeps the plastic strain exactly and has d_l = -nu d_eps
  // (1e-10 rel), for linear hardening and Johnson-Cook alike. The Johnson-Cook rate and
  // thermal terms are off: an overstress from rate hardening would keep flowing on unloading.
  Material jc = copper();
  std::get<JohnsonCook>(jc.strength).C = 0.0;
  std::get<JohnsonCook>(jc.strength).m = 0.0;
  jc.eos = NoEos{};
  for (const Material& m : {steel(J2Plasticity{250.0, 2.0e3}), jc}) {
    PointState point = at_rest(m);
    for (int i = 0; i < 40; ++i) uniaxial_update(m, point, 2e-4, kDt);
    const double peak = point.stress.xx, eps_p = point.plastic_strain;
    ASSERT_GT(eps_p, 0.0) << m.name;
    const double d_eps = -1e-5;
    for (int i = 1; i <= 10; ++i) {
      const UniaxialUpdate u = uniaxial_update(m, point, d_eps, kDt);
      EXPECT_NEAR(point.stress.xx, peak + m.youngs_modulus * i * d_eps, 1e-10 * peak) << m.name;
      EXPECT_EQ(point.plastic_strain, eps_p) << m.name;
      EXPECT_NEAR(u.lateral_strain_increment, -m.poisson_ratio * d_eps, 1e-10 * -d_eps) << m.name;
    }
  }
}

TEST(UniaxialStress, MieGruneisenPointKeepsLateralStressZero) {
  // Reference: copper with Johnson-Cook (rate and heating on) and Mie-Grueneisen, stretched
  // and compressed 3 % at 100 /ms: the lateral stress stays below 1e-10 of the axial stress
  // at every increment, within at most 5 trials.
  const Material m = copper();
  ASSERT_TRUE(m.has_thermal_term());
  for (const double d_eps : {3e-4, -3e-4}) {
    PointState point = at_rest(m);
    int most_trials = 0;
    for (int i = 0; i < 100; ++i) {
      const UniaxialUpdate u = uniaxial_update(m, point, d_eps, kDt);
      most_trials = std::max(most_trials, u.trials);
      expect_lateral_free(point, u, std::abs(point.stress.xx));
    }
    EXPECT_GT(point.plastic_strain, 0.02);
    EXPECT_GT(point.temperature, m.thermal.initial_temperature);
    EXPECT_LE(most_trials, 5) << "d_eps " << d_eps;
  }
}

TEST(UniaxialStress, SmallStrainModulusWithEosIsNineKGOverThreeKPlusG) {
  // Reference: with an EOS the bar modulus is 9 K G / (3 K + G), K = rho0 c0^2 at the
  // reference state (1e-12 rel); an elastic bar at 1e-4 strain follows it to 1e-3 (the
  // Hugoniot's curvature and the Grueneisen term are O(eps) corrections). Without an EOS
  // the same formula returns E (1e-14 rel).
  Material m = copper();
  m.strength = Elastic{};
  const PointState rest = at_rest(m);
  const double k = 8.93e-3 * 3940.0 * 3940.0, g = m.shear_modulus();
  const double e_bar = 9.0 * k * g / (3.0 * k + g);
  EXPECT_NEAR(uniaxial_modulus(m, rest), e_bar, 1e-12 * e_bar);
  PointState point = rest;
  for (int i = 0; i < 10; ++i) uniaxial_update(m, point, 1e-5, kDt);
  EXPECT_NEAR(point.stress.xx, e_bar * 1e-4, 1e-3 * e_bar * 1e-4);
  const Material s = steel();
  EXPECT_NEAR(uniaxial_modulus(s, at_rest(s)), s.youngs_modulus, 1e-14 * s.youngs_modulus);
}

}  // namespace
}  // namespace afemp::core
