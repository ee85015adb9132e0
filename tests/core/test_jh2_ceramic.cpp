// The Johnson-Holmquist ceramic model, JH-2 (johnson_holmquist_ceramic.cpp), against the closed
// forms of Johnson & Holmquist (1994), SI units: the intact and fractured strength surfaces at
// three pressures and two damage states, the pressure law and its bulking pressure, the point
// update (yield at the intact surface, damage, bulking, the fractured surface once D = 1, the
// tension limit), the history it keeps and the scene keys. Strength constants: the AD995
// alumina set as it is usually quoted from Johnson & Holmquist (1994) (A 0.93, B 0.31, M = N =
// 0.6, T 0.2 GPa, HEL 2.79 GPa, PHEL 1.46 GPa, D1 0.005, D2 1); the pressure law takes a cubic
// (K1 233, K2 -593, K3 2800 GPa) so that every term is exercised. The closed forms here are
// the paper's equations evaluated by hand (Python, double precision), not by the model.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>

#include "afemp/errors.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

constexpr double kG = 90.16e9, kPhel = 1.46e9, kSigmaHel = 1.995e9;  // 3/2 (HEL - PHEL)

JohnsonHolmquist2 alumina() {
  JohnsonHolmquist2 s;
  s.A = 0.93;
  s.B = 0.31;
  s.M = 0.6;
  s.N = 0.6;
  s.tensile_strength = 0.2e9;
  s.hel = 2.79e9;
  s.hel_pressure = kPhel;
  s.beta = 1.0;
  s.D1 = 0.005;
  s.D2 = 1.0;
  return s;
}

Jh2Pressure cubic() {
  return {233e9, -593e9, 2800e9};
}

Material ceramic() {
  Material m;
  m.name = "alumina";
  m.density = 3700.0;
  m.strength = alumina();
  m.eos = cubic();
  m.set_shear_and_bulk_modulus(kG, 233e9);
  m.validate();
  return m;
}

// One update to compression mu with the deviatoric increment de_dev (the volume change the
// solvers pass is rho_old / rho_new - 1).
void step_to(const Material& m, PointState& p, double mu, const SymTensor& de_dev = {}) {
  const double rho_new = m.density * (1.0 + mu);
  const double d_vol = p.density / rho_new - 1.0;
  p.density = rho_new;
  constitutive_update(m, std::get<JohnsonHolmquist2>(m.strength), std::get<Jh2Pressure>(m.eos),
                      false, p, de_dev + (d_vol / 3.0) * SymTensor::identity(), 1.0);
}

TEST(JohnsonHolmquist2, IntactAndFracturedStrengthAtThreePressures) {
  // Reference: eqs 1-3 with T* = 0.2 / 1.46 and C = 0: sigma_i* = A (P* + T*)^N,
  // sigma_f* = B P*^M, and halfway between them at D = 1/2; 1e-14 relative.
  const JohnsonHolmquist2 s = alumina();
  const double p_star[3] = {0.25, 1.0, 3.0};
  const double intact[3] = {0.5261387683047647, 1.0044679588507313, 1.8466752214022997};
  const double fractured[3] = {0.13493533731089924, 0.31, 0.5992864339288464};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(s.normalised_strength(p_star[i], 0.0, 0.0), intact[i], 1e-14 * intact[i]);
    EXPECT_NEAR(s.normalised_strength(p_star[i], 1.0, 0.0), fractured[i], 1e-14 * fractured[i]);
    const double half = 0.5 * (intact[i] + fractured[i]);
    EXPECT_NEAR(s.normalised_strength(p_star[i], 0.5, 0.0), half, 1e-14 * half);
  }
  // SFMAX caps the fractured surface only; in tension the fractured material has no strength.
  JohnsonHolmquist2 capped = s;
  capped.max_fractured_strength = 0.2;
  EXPECT_DOUBLE_EQ(capped.normalised_strength(3.0, 1.0, 0.0), 0.2);
  EXPECT_DOUBLE_EQ(capped.normalised_strength(3.0, 0.0, 0.0), intact[2]);
  EXPECT_DOUBLE_EQ(s.normalised_strength(-0.05, 1.0, 0.0), 0.0);
  // The rate factor 1 + C ln(epsdot / epsdot_0), 1 below the reference rate.
  JohnsonHolmquist2 rate = s;
  rate.C = 0.007;
  EXPECT_NEAR(rate.normalised_strength(1.0, 0.0, 100.0),
              intact[1] * (1.0 + 0.007 * std::log(100.0)), 1e-14);
  EXPECT_DOUBLE_EQ(rate.normalised_strength(1.0, 0.0, 0.5), intact[1]);
  // Fracture strain, eq 5: D1 (P* + T*)^D2.
  EXPECT_NEAR(s.fracture_strain(1.0), 0.005 * (1.0 + 0.2 / 1.46), 1e-17);
  EXPECT_DOUBLE_EQ(s.fracture_strain(-0.2), 0.0);
  EXPECT_DOUBLE_EQ(s.hel_strength(), kSigmaHel);
}

TEST(Jh2Pressure, PolynomialAndBulkingPressureAtThreeStates) {
  // Reference: eq 6, K1 mu + dP in tension and the cubic plus dP in compression; eq 7,
  // dP = -K1 mu + sqrt((K1 mu + dP_old)^2 + 2 beta K1 dU); 1e-14 relative.
  const Jh2Pressure eos = cubic();
  EXPECT_NEAR(eos.pressure(-0.01, 0.0), -2.33e9, 1e-14 * 2.33e9);
  EXPECT_NEAR(eos.pressure(0.02, 50e6), 4495200000.0, 1e-14 * 4.5e9);
  EXPECT_NEAR(eos.pressure(0.1, 50e6), 20220000000.0, 1e-14 * 2.0e10);
  EXPECT_NEAR(eos.bulking_pressure(0.0, 0.0, 1e5, 1.0), 215870331.44922903, 1e-14 * 2.2e8);
  EXPECT_NEAR(eos.bulking_pressure(0.01, 20e6, 2e5, 1.0), 39746821.920012474, 1e-9 * 4e7);
  EXPECT_NEAR(eos.bulking_pressure(-0.005, 10e6, 3e5, 0.5), 2349873410.960006, 1e-14 * 2.4e9);
  // No energy released, no bulking gained.
  EXPECT_NEAR(eos.bulking_pressure(0.02, 30e6, 0.0, 1.0), 30e6, 1e-6);
  // rho dp/drho = (1 + mu)(K1 + 2 K2 mu + 3 K3 mu^2), (1 + mu) K1 in tension.
  EXPECT_NEAR(eos.tangent_bulk_modulus(0.05),
              1.05 * (233e9 - 2 * 593e9 * 0.05 + 3 * 2800e9 * 0.0025), 1e-14 * 2.3e11);
  EXPECT_NEAR(eos.tangent_bulk_modulus(-0.01), 0.99 * 233e9, 1e-14 * 2.3e11);
}

TEST(JohnsonHolmquist2, PointYieldsOnTheIntactSurfaceDamagesBulksAndEndsOnTheFracturedOne) {
  // A point compressed to mu = 0.01 (P = K1 mu + K2 mu^2 + K3 mu^3, elastic), then sheared at
  // that volume in small increments. Reference: at the first increment that flows, the von
  // Mises stress is sigma_HEL sigma_i*(P*) (eq 2, D = 0 at its start); the damage it adds is
  // d eps_p / eps_f(P*) (eqs 4, 5) and the bulking pressure eq 7 with the energy
  // dU = (sigma_y(0)^2 - sigma_y(D)^2) / (6 G) at that pressure; once fully damaged, sigma_HEL
  // sigma_f*(P*) (eq 3) at the pressure with the bulking built. 1e-10 relative.
  const Material m = ceramic();
  const JohnsonHolmquist2 s = alumina();
  const Jh2Pressure eos = cubic();
  PointState p;
  p.density = m.density;
  const double mu = 0.01;
  step_to(m, p, mu);
  const double p0 = eos.pressure(mu, 0.0);
  ASSERT_NEAR(pressure(p.stress), p0, 1e-12 * p0);
  ASSERT_EQ(p.damage, 0.0);
  const SymTensor shear{0, 0, 0, 0, 0, 2e-5};  // engineering shear 4e-5 per increment
  int flowing = -1;
  for (int i = 0; i < 4000 && flowing < 0; ++i) {
    const double eps_p = p.plastic_strain;
    step_to(m, p, mu, shear);
    if (p.plastic_strain > eps_p) flowing = i;
  }
  ASSERT_GE(flowing, 0);
  const double p_star = p0 / kPhel;
  const double yield = kSigmaHel * s.normalised_strength(p_star, 0.0, 0.0);
  EXPECT_NEAR(von_mises(p.stress), yield, 1e-10 * yield);
  const double d = p.plastic_strain / s.fracture_strain(p_star);
  EXPECT_NEAR(p.damage, d, 1e-12 * d);
  const double y_d = kSigmaHel * s.normalised_strength(p_star, d, 0.0);
  const double du = (yield * yield - y_d * y_d) / (6.0 * kG);
  const double bulking = eos.bulking_pressure(mu, 0.0, du, 1.0);
  ASSERT_EQ(m.history_count(), 1u);
  EXPECT_EQ(m.history_name(0), "bulking_pressure");
  EXPECT_NEAR(p.history[0], bulking, 1e-10 * bulking);
  std::printf(
      "JH-2 at mu = 0.01: P = %.4f GPa, yields at q = %.4f GPa (closed form %.4f), "
      "D = %.3e, bulking %.4f MPa\n",
      p0 / 1e9, von_mises(p.stress) / 1e9, yield / 1e9, p.damage, p.history[0] / 1e6);

  for (int i = 0; i < 20000 && p.damage < 1.0; ++i) step_to(m, p, mu, shear);
  ASSERT_EQ(p.damage, 1.0);
  step_to(m, p, mu, shear);  // one more increment on the fractured surface
  const double p_full = eos.pressure(mu, p.history[0]);
  EXPECT_NEAR(pressure(p.stress), p_full, 1e-10 * p_full);
  const double fractured = kSigmaHel * s.normalised_strength(p_full / kPhel, 1.0, 0.0);
  EXPECT_NEAR(von_mises(p.stress), fractured, 1e-10 * fractured);
  EXPECT_GT(p.history[0], bulking);  // bulking grows with the damage
  std::printf(
      "JH-2 fully damaged: bulking %.2f MPa, P = %.4f GPa, q = %.4f GPa (closed form "
      "%.4f)\n",
      p.history[0] / 1e6, pressure(p.stress) / 1e9, von_mises(p.stress) / 1e9, fractured / 1e9);
}

TEST(JohnsonHolmquist2, TensionIsLimitedToMinusTTimesOneMinusDamage) {
  // Reference: P >= -T (1 - D); an undamaged point pulled to mu = -0.01 (K1 mu = -2.33 GPa)
  // carries -T = -0.2 GPa, and a fully damaged one none.
  const Material m = ceramic();
  PointState p;
  p.density = m.density;
  step_to(m, p, -0.01);
  EXPECT_DOUBLE_EQ(pressure(p.stress), -0.2e9);
  PointState broken;
  broken.density = m.density;
  broken.damage = 1.0;
  step_to(m, broken, -0.01);
  EXPECT_DOUBLE_EQ(pressure(broken.stress), 0.0);
}

const std::string kMaterial = R"([run]
end_time = 1e-6

[materials.alumina]
density = 3700
G = 90.16e9
strength = { model = "johnson-holmquist-2", A = 0.93, B = 0.31, M = 0.6, N = 0.6, T = 0.2e9, HEL = 2.79e9, PHEL = 1.46e9, D1 = 0.005, D2 = 1.0 }
eos = { model = "jh2-pressure", K1 = 130.95e9 }
)";

TEST(JohnsonHolmquist2, SceneKeysReadTheModelAndNameWhatIsWrong) {
  // The material reads into the model; its bulk modulus is K1 and E, nu follow from G.
  const std::string body =
      "[[bodies]]\nname = \"tile\"\nmaterial = \"alumina\"\n"
      "shape = { box = { min = [0, 0, 0], max = [0.01, 0.01, 0.01] } }\n"
      "[grid]\ncell = 0.005\nmin = [0, 0, 0]\nmax = [0.01, 0.01, 0.01]\n";
  const Scene scene = parse_scene(kMaterial + body, "tile.toml");
  const Material& m = scene.materials.at(0);
  const auto& s = std::get<JohnsonHolmquist2>(m.strength);
  EXPECT_DOUBLE_EQ(s.hel_strength(), kSigmaHel);
  EXPECT_DOUBLE_EQ(s.beta, 1.0);
  EXPECT_NEAR(m.bulk_modulus(), 130.95e9, 1e-6 * 130.95e9);
  EXPECT_NEAR(m.shear_modulus(), 90.16e9, 1e-6 * 90.16e9);
  // PHEL must lie below the HEL (sigma_HEL > 0): the key and its line.
  std::string bad = kMaterial;
  bad.replace(bad.find("PHEL = 1.46e9"), 13, "PHEL = 3e9");
  const std::string e1 = test::error_of(bad + body, "tile.toml");
  EXPECT_NE(e1.find("tile.toml:7"), std::string::npos) << e1;
  EXPECT_NE(e1.find("materials.alumina.strength.PHEL"), std::string::npos) << e1;
  EXPECT_NE(e1.find("value < 2790000000"), std::string::npos) << e1;
  // Its pressure law goes with it, and no other model takes that law.
  std::string no_eos = kMaterial;
  no_eos.replace(no_eos.find("eos = {"),
                 no_eos.find('\n', no_eos.find("eos = {")) - no_eos.find("eos = {"),
                 "eos = { model = \"linear\" }");
  const std::string e2 = test::error_of(no_eos + body);
  EXPECT_NE(e2.find("needs eos = { model = \"jh2-pressure\", K1, K2, K3 }"), std::string::npos)
      << e2;
  // A material built in code is checked by the same ranges.
  Material code = ceramic();
  std::get<JohnsonHolmquist2>(code.strength).D1 = 0.0;
  try {
    code.validate();
    ADD_FAILURE() << "validate() accepted D1 = 0";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("D1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace afemp::core
