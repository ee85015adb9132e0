// The Drucker-Prager soil model (drucker_prager.cpp) against closed forms, units mm, ms, g, MPa:
// a sand of E = 100 MPa, nu = 0.3 (G = 38.46, K = 83.33 MPa), phi = 30 deg, c = 0.01 MPa,
// fitted through Mohr-Coulomb's outer edges. The references: the fits' formulas (de Souza Neto,
// Peric & Owen 2008, ch. 6) evaluated by hand, and Mohr-Coulomb itself in principal
// stresses; the return of a strain-driven point onto the cone at three confining pressures with
// the plastic strain along the potential's gradient; the tension cutoff, the corner and the
// apex; the energy the point books; the scene keys and their errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <variant>

#include "afemp/errors.hpp"
#include "core/materials/material.hpp"
#include "core/scene.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
using Fit = DruckerPrager::Fit;

Material sand(double psi_degrees, double tension_cutoff = -1.0) {
  DruckerPrager dp;
  dp.q_phi = DruckerPrager::cone_slope(Fit::outer, 30.0 * kDegree);
  dp.k_phi = DruckerPrager::cone_cohesion(Fit::outer, 30.0 * kDegree, 0.01);
  dp.q_psi = DruckerPrager::cone_slope(Fit::outer, psi_degrees * kDegree);
  dp.tension_cutoff = tension_cutoff < 0.0 ? dp.k_phi / dp.q_phi : tension_cutoff;
  Material m;
  m.name = "sand";
  m.density = 2.0e-3;
  m.youngs_modulus = 100.0;
  m.poisson_ratio = 0.3;
  m.strength = dp;
  m.validate();
  return m;
}

double tau(const SymTensor& stress) {
  const SymTensor s = stress.deviator();
  return std::sqrt(0.5 * double_dot(s, s));
}

double yield(const DruckerPrager& dp, const SymTensor& stress) {
  return tau(stress) + dp.q_phi * stress.mean() - dp.k_phi;
}

PointUpdate step(const Material& m, PointState& p, const SymTensor& d_eps) {
  return constitutive_update(m, std::get<DruckerPrager>(m.strength), NoEos{}, false, p, d_eps, 1.0);
}

PointState at_pressure(const Material& m, double p) {
  PointState s;
  s.density = m.density;
  s.stress = -p * SymTensor::identity();
  return s;
}

TEST(DruckerPrager, FitsMatchTheirClosedFormsAndMohrCoulomb) {
  // Reference 1: the fits' formulas at phi = 30 deg, c = 10 by hand: outer q = 2 sqrt(3) / 5,
  // k = 12; inner q = 2 sqrt(3) / 7, k = 60 / 7; plane strain q = sqrt(3 / 13),
  // k = 30 / sqrt(13). 1e-15 relative.
  const double phi = 30.0 * kDegree;
  struct Expected {
    Fit fit;
    double q, k;
  };
  for (const Expected& e :
       {Expected{Fit::outer, 2.0 * std::sqrt(3.0) / 5.0, 12.0},
        Expected{Fit::inner, 2.0 * std::sqrt(3.0) / 7.0, 60.0 / 7.0},
        Expected{Fit::plane_strain, std::sqrt(3.0 / 13.0), 30.0 / std::sqrt(13.0)}}) {
    EXPECT_NEAR(DruckerPrager::cone_slope(e.fit, phi), e.q, 1e-15 * e.q);
    EXPECT_NEAR(DruckerPrager::cone_cohesion(e.fit, phi, 10.0), e.k, 1e-14 * e.k);
  }
  // Reference 2: Mohr-Coulomb, (s1 - s3) + (s1 + s3) sin phi = 2 c cos phi (tension positive,
  // s1 >= s2 >= s3), at phi = 35 deg, c = 0.02 and three mean stresses. The outer cone holds
  // its triaxial-compression states (s1 = s2), the inner cone its triaxial-extension states
  // (s2 = s3), and the plane-strain cone is the one inscribed: its tau is the least tau of
  // Mohr-Coulomb around the deviatoric plane (scanned over 2e5 Lode directions). 1e-12 and
  // 1e-9 relative.
  const double phi2 = 35.0 * kDegree, c = 0.02, sn = std::sin(phi2), cs = std::cos(phi2);
  for (const double mean : {0.01, -0.5, -3.0}) {
    // A principal deviator direction d (s_i = mean + r d_i) reaches Mohr-Coulomb at
    // r = 2 (c cos phi - mean sin phi) / ((d1 - d3) + (d1 + d3) sin phi).
    auto mc_tau = [&](double d1, double d2, double d3) {
      const double r = 2.0 * (c * cs - mean * sn) / ((d1 - d3) + (d1 + d3) * sn);
      return r * std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3));
    };
    auto dp_tau = [&](Fit fit) {
      return DruckerPrager::cone_cohesion(fit, phi2, c) -
             DruckerPrager::cone_slope(fit, phi2) * mean;
    };
    const double compression = mc_tau(1.0, 1.0, -2.0), extension = mc_tau(2.0, -1.0, -1.0);
    EXPECT_NEAR(dp_tau(Fit::outer), compression, 1e-12 * compression) << mean;
    EXPECT_NEAR(dp_tau(Fit::inner), extension, 1e-12 * extension) << mean;
    double least = compression;
    for (int i = 0; i <= 200000; ++i) {
      const double a = (i / 200000.0) * std::numbers::pi / 3.0 - std::numbers::pi / 6.0;
      // Lode angle a in [-30, 30] deg: d1 >= d2 >= d3, sum zero.
      const double d1 = std::cos(a - std::numbers::pi / 6.0);
      const double d3 = -std::cos(a + std::numbers::pi / 6.0);
      least = std::min(least, mc_tau(d1, -d1 - d3, d3));
    }
    EXPECT_NEAR(dp_tau(Fit::plane_strain), least, 1e-9 * least) << mean;
    EXPECT_LT(dp_tau(Fit::plane_strain), extension);
  }
}

TEST(DruckerPrager, ReturnsOntoTheConeAlongThePotentialAtThreePressures) {
  // A point at -p0 I takes a deviatoric strain increment (triaxial compression, no volume
  // change) far beyond yield. Reference, the closed-form return: d lambda = f* / (G + K q_phi
  // q_psi), sigma_m = -p0 - K q_psi d lambda, tau = k_phi - q_phi sigma_m; the plastic strain
  // d eps - C^-1 d sigma has volumetric over sqrt(2) times deviatoric norm equal to q_psi (the
  // potential's gradient, s / 2 tau + q_psi I / 3); f = 0 to 1e-13 of the stress. Associated
  // (psi = phi) and non-associated (psi = 10, 0 deg) flows differ as that says: psi = 0 keeps
  // the volume and the mean stress, a larger psi dilates more and ends at a larger pressure.
  const SymTensor de{-0.02, 0.01, 0.01, 0.0, 0.0, 0.0};
  for (const double psi : {30.0, 10.0, 0.0}) {
    const Material m = sand(psi);
    const auto& dp = std::get<DruckerPrager>(m.strength);
    const double g = m.shear_modulus(), k = m.bulk_modulus();
    for (const double p0 : {0.05, 0.2, 1.0}) {
      PointState p = at_pressure(m, p0);
      const SymTensor before = p.stress;
      const PointUpdate u = step(m, p, de);
      const double tau_trial = 2.0 * g * std::sqrt(0.5 * double_dot(de, de));
      const double f_trial = tau_trial - dp.q_phi * p0 - dp.k_phi;
      ASSERT_GT(f_trial, 0.0);
      const double d_lambda = f_trial / (g + k * dp.q_phi * dp.q_psi);
      const double mean = -p0 - k * dp.q_psi * d_lambda;
      const double scale = p0 + dp.k_phi;
      EXPECT_NEAR(p.stress.mean(), mean, 1e-13 * scale) << psi << " " << p0;
      EXPECT_NEAR(tau(p.stress), dp.k_phi - dp.q_phi * mean, 1e-13 * scale);
      EXPECT_NEAR(yield(dp, p.stress), 0.0, 1e-13 * scale);
      // The deviator keeps its direction (radial in the deviatoric plane).
      const SymTensor s = p.stress.deviator();
      EXPECT_NEAR(double_dot(s, de) / std::sqrt(double_dot(s, s) * double_dot(de, de)), 1.0, 1e-14);
      // Plastic strain along the potential's gradient.
      const SymTensor ds = p.stress.deviator() - before.deviator();
      const SymTensor de_p = de - (1.0 / (2.0 * g)) * ds;
      const double dv_p = -(p.stress.mean() - before.mean()) / k;
      const double dev_norm = std::sqrt(2.0 * double_dot(de_p, de_p));
      EXPECT_NEAR(dev_norm, d_lambda, 1e-12 * d_lambda);
      EXPECT_NEAR(dv_p, dp.q_psi * d_lambda, 1e-12 * d_lambda);
      // Equivalent plastic strain sqrt(2/3 d eps_p : d eps_p) = d lambda sqrt(1/3 + 2/9 q_psi^2).
      EXPECT_NEAR(p.plastic_strain,
                  d_lambda * std::sqrt(1.0 / 3.0 + 2.0 / 9.0 * dp.q_psi * dp.q_psi),
                  1e-12 * d_lambda);
      // Plastic work: the stress's trapezoidal work on the plastic strain, per unit mass (in one
      // step this large the start's pressure can make it negative with dilatancy; in the
      // solvers' small steps it is the dissipation, >= 0, below).
      const SymTensor d_eps_p = de_p + (dv_p / 3.0) * SymTensor::identity();
      const double w = 0.5 * double_dot(before + p.stress, d_eps_p) / m.density;
      EXPECT_NEAR(u.plastic_work, w, 1e-12 * std::abs(w));
      if (psi == 0.0) {
        EXPECT_NEAR(p.stress.mean(), -p0, 1e-15 * p0);
      }
    }
  }
  // The same path in 200 small steps ends on the cone as well, the pressure rising with psi,
  // and every step dissipates.
  double pressure_at[2] = {};
  for (int i = 0; i < 2; ++i) {
    const Material m = sand(i == 0 ? 0.0 : 30.0);
    PointState p = at_pressure(m, 0.2);
    for (int n = 0; n < 200; ++n) EXPECT_GE(step(m, p, 0.005 * de).plastic_work, 0.0) << n;
    EXPECT_NEAR(yield(std::get<DruckerPrager>(m.strength), p.stress), 0.0, 1e-13);
    pressure_at[i] = pressure(p.stress);
  }
  EXPECT_NEAR(pressure_at[0], 0.2, 1e-14);
  EXPECT_GT(pressure_at[1], 0.2);
}

TEST(DruckerPrager, TensionCutoffCornerAndApex) {
  // Reference: the cutoff caps the mean stress at sigma_t exactly; inside the cone at sigma_t
  // the deviator is kept, beyond it the point returns to the corner (sigma_t,
  // k_phi - q_phi sigma_t); with the default cutoff, the apex k_phi / q_phi, tau = 0 there.
  const double cutoff = 0.005;
  const Material m = sand(10.0, cutoff);
  const auto& dp = std::get<DruckerPrager>(m.strength);
  const double g = m.shear_modulus();
  const double corner_tau = dp.k_phi - dp.q_phi * cutoff;
  // Pure extension.
  PointState a = at_pressure(m, 0.0);
  step(m, a, 0.001 * SymTensor::identity());
  EXPECT_DOUBLE_EQ(a.stress.mean(), cutoff);
  EXPECT_DOUBLE_EQ(tau(a.stress), 0.0);
  EXPECT_NEAR(a.plastic_strain,
              (3.0 * m.bulk_modulus() * 0.001 - cutoff) / m.bulk_modulus() * std::sqrt(2.0) / 3.0,
              1e-15);
  // Extension with a little shear: the deviator stays.
  const SymTensor shear{0.0, 0.0, 0.0, 0.0, 0.0, 0.3 * corner_tau / (2.0 * g)};
  PointState b = at_pressure(m, 0.0);
  step(m, b, 0.001 * SymTensor::identity() + shear);
  EXPECT_DOUBLE_EQ(b.stress.mean(), cutoff);
  EXPECT_NEAR(tau(b.stress), 0.3 * corner_tau, 1e-15);
  // Extension with much shear: the corner.
  PointState c = at_pressure(m, 0.0);
  step(m, c, 0.001 * SymTensor::identity() + 10.0 * shear);
  EXPECT_DOUBLE_EQ(c.stress.mean(), cutoff);
  EXPECT_NEAR(tau(c.stress), corner_tau, 1e-15);
  EXPECT_NEAR(yield(dp, c.stress), 0.0, 1e-15);
  // Shear without a volume change from a slightly compressed state: the cone alone, the mean
  // stress pushed further from the cutoff by the dilatancy.
  PointState d = at_pressure(m, 0.001);
  step(m, d, 10.0 * shear);
  EXPECT_LT(d.stress.mean(), -0.001);
  EXPECT_NEAR(yield(dp, d.stress), 0.0, 1e-15);
  // The default cutoff is the apex: tau = 0 there.
  const Material apex = sand(10.0);
  const auto& dp_apex = std::get<DruckerPrager>(apex.strength);
  PointState e = at_pressure(apex, 0.0);
  step(apex, e, 0.001 * SymTensor::identity() + 10.0 * shear);
  EXPECT_DOUBLE_EQ(e.stress.mean(), dp_apex.k_phi / dp_apex.q_phi);
  EXPECT_NEAR(tau(e.stress), 0.0, 1e-15);
}

TEST(DruckerPrager, EnergyOfALoadingCycleIsElasticPlusPlasticWork) {
  // Reference: the internal energy is the trapezoidal work of the stress; the elastic energy
  // s:s/4G + sigma_m^2/2K per unit mass, plus the plastic work booked, equals it (1e-12 of the
  // work done) over a cycle of shear, extension to the cutoff and recompression. The work is
  // per unit reference mass: the density passed makes rho (1 + tr d eps) = rho0, the volume
  // each increment acts on.
  const Material m = sand(10.0, 0.005);
  PointState p = at_pressure(m, 0.1);
  const double g = m.shear_modulus(), k = m.bulk_modulus();
  auto elastic = [&](const SymTensor& sigma) {
    const SymTensor s = sigma.deviator();
    return (double_dot(s, s) / (4.0 * g) + sigma.mean() * sigma.mean() / (2.0 * k)) / m.density;
  };
  const double e0 = elastic(p.stress);
  p.energy = e0;
  double plastic = 0.0, worst = 0.0, work = 0.0;
  for (int n = 0; n < 300; ++n) {
    const double t = n / 300.0;
    const SymTensor d_eps = t < 0.4   ? SymTensor{-2e-4, 1e-4, 1e-4, 0.0, 5e-5, 0.0}
                            : t < 0.7 ? SymTensor{1e-4, 1e-4, 1e-4, 3e-5, 0.0, 0.0}
                                      : SymTensor{-2e-4, -2e-4, -1e-4, 0.0, 0.0, -4e-5};
    const SymTensor before = p.stress;
    p.density = m.density / (1.0 + d_eps.trace());
    plastic += step(m, p, d_eps).plastic_work;
    work += std::abs(0.5 * double_dot(before + p.stress, d_eps)) / m.density;
    worst = std::max(worst, std::abs(p.energy - elastic(p.stress) - plastic));
  }
  EXPECT_GT(plastic, 0.0);
  EXPECT_LT(worst, 1e-12 * work) << "plastic " << plastic << " work " << work;
}

const std::string kSand = R"([run]
end_time = 1.0

[materials.sand]
density = 2.0e-3
E = 100
nu = 0.3
strength = { model = "drucker-prager", friction_angle = 30, cohesion = 0.01, dilatancy_angle = 10, fit = "outer", tension_cutoff = 0.005 }
)";
const std::string kBody =
    "[[bodies]]\nname = \"soil\"\nmaterial = \"sand\"\n"
    "shape = { box = { min = [0, 0, 0], max = [10, 10, 10] } }\n"
    "[grid]\ncell = 5\nmin = [0, 0, 0]\nmax = [10, 10, 10]\n";

TEST(DruckerPrager, SceneKeysReadTheConeAndNameWhatIsWrong) {
  // The Mohr-Coulomb form gives the fit's cone; MPM3D's constants give it as they are.
  const Scene scene = parse_scene(kSand + kBody, "soil.toml");
  const auto& dp = std::get<DruckerPrager>(scene.materials.at(0).strength);
  EXPECT_DOUBLE_EQ(dp.q_phi, DruckerPrager::cone_slope(Fit::outer, 30.0 * kDegree));
  EXPECT_DOUBLE_EQ(dp.k_phi, DruckerPrager::cone_cohesion(Fit::outer, 30.0 * kDegree, 0.01));
  EXPECT_DOUBLE_EQ(dp.q_psi, DruckerPrager::cone_slope(Fit::outer, 10.0 * kDegree));
  EXPECT_DOUBLE_EQ(dp.tension_cutoff, 0.005);
  auto with = [&](const std::string& strength) {
    std::string s = kSand;
    const std::size_t at = s.find("strength = {");
    s.replace(at, s.find('\n', at) - at, "strength = { model = \"drucker-prager\", " + strength);
    return s + kBody;
  };
  const Scene raw = parse_scene(with("q_phi = 0.4, k_phi = 0.02, q_psi = 0.1 }"), "soil.toml");
  const auto& r = std::get<DruckerPrager>(raw.materials.at(0).strength);
  EXPECT_EQ(r.q_phi, 0.4);
  EXPECT_EQ(r.k_phi, 0.02);
  EXPECT_EQ(r.q_psi, 0.1);
  EXPECT_DOUBLE_EQ(r.tension_cutoff, 0.05);  // the apex by default
  // Errors name the key and what is allowed.
  const std::string e1 =
      test::error_of(with("friction_angle = 30, cohesion = 0.01, dilatancy_angle = 40, "
                          "fit = \"outer\" }"),
                     "soil.toml");
  EXPECT_NE(e1.find("materials.sand.strength.dilatancy_angle"), std::string::npos) << e1;
  EXPECT_NE(e1.find("0 <= value <= 30"), std::string::npos) << e1;
  const std::string e2 = test::error_of(with("friction_angle = 30, cohesion = 0.01 }"));
  EXPECT_NE(e2.find("fit"), std::string::npos) << e2;
  EXPECT_NE(e2.find("\"outer\", \"inner\", \"plane-strain\""), std::string::npos) << e2;
  const std::string e3 =
      test::error_of(with("friction_angle = 30, cohesion = 0.01, fit = \"inner\", q_phi = 0.4 }"));
  EXPECT_NE(e3.find("not both"), std::string::npos) << e3;
  const std::string e4 = test::error_of(with("q_phi = 0.4, k_phi = 0.02, q_psi = 0.5 }"));
  EXPECT_NE(e4.find("q_psi"), std::string::npos) << e4;
  EXPECT_NE(e4.find("0 <= value <= 0.4"), std::string::npos) << e4;
  const std::string e5 = test::error_of(with("q_phi = 0.4, k_phi = 0.02, tension_cutoff = 0.06 }"));
  EXPECT_NE(e5.find("0 <= value <= 0.05"), std::string::npos) << e5;
  const std::string e6 = test::error_of(with("q_phi = 0, k_phi = 0.02 }"));
  EXPECT_NE(e6.find("tension_cutoff"), std::string::npos) << e6;
  // Its pressure is linear elastic: no eos, and no failure model.
  const std::string e7 = test::error_of(kSand + "eos = { model = \"linear\" }\n" + kBody);
  EXPECT_NE(e7.find("takes no eos"), std::string::npos) << e7;
  const std::string e8 = test::error_of(kSand + "failure_strain = 0.5\n" + kBody);
  EXPECT_NE(e8.find("takes no failure model"), std::string::npos) << e8;
  // A material built in code is checked by the same ranges.
  Material code = sand(10.0);
  std::get<DruckerPrager>(code.strength).q_psi = 1.0;
  EXPECT_THROW(code.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace afemp::core
