// Equations of state against their defining formulas: Mie-Grueneisen (Ma 2005, eqs 2-21..2-26),
// LS-DYNA linear polynomial and the linear EOS, plus their tangent bulk moduli rho dp/drho.
// Units mm, ms, g, N, MPa: e in mm^2/ms^2 (= J/kg), rho in g/mm^3.
#include <gtest/gtest.h>

#include <cmath>

#include "afemp/equations_of_state.hpp"

namespace afemp::core {
namespace {

// Copper (Ma 2005 table values): rho0 = 8.93 g/cm^3, c0 = 3.94 km/s, s = 1.49, gamma0 = 1.96.
MieGruneisen copper_eos() {
  return {8.93e-3, 3940.0, 1.49, 1.96};
}

template <class Eos>
double eos_pressure(const Eos& eos, double mu, double e) {
  const EosLinearForm f = eos.form(mu);
  return f.a + f.b * e;
}

// rho dp/drho at fixed e by central differences in mu (rho = rho0 (1 + mu)).
template <class Eos>
double numerical_tangent(const Eos& eos, double mu, double e) {
  const double h = 1e-6;
  return (1.0 + mu) * (eos_pressure(eos, mu + h, e) - eos_pressure(eos, mu - h, e)) / (2.0 * h);
}

TEST(MieGruneisen, CompressedPressureMatchesCubicHugoniotFormula) {
  // Reference: eqs 2-25/2-26 with gamma = gamma0 rho0 / rho (eq 2-22), so gamma mu =
  // gamma0 mu / (1 + mu), evaluated here and by hand (C1 = rho0 c0^2 = 138625.748 MPa,
  // pH(0.1) = 16843.0700 MPa, p = pH (1 - 0.098 / 1.1) + 1.96 * 8.93e-3 * 1e5 = 17092.7856 MPa).
  // Tolerance 1e-12 relative (a few roundings).
  const MieGruneisen eos = copper_eos();
  const double mu = 0.1, e = 1.0e5;
  const double c1 = eos.rho0 * eos.c0 * eos.c0;
  const double c2 = c1 * (2.0 * eos.s - 1.0);
  const double c3 = c1 * (eos.s - 1.0) * (3.0 * eos.s - 1.0);
  const double p_hugoniot = c1 * mu + c2 * mu * mu + c3 * mu * mu * mu;
  const double gamma = eos.gamma0 / (1.0 + mu);
  const double formula = p_hugoniot * (1.0 - 0.5 * gamma * mu) + gamma * (1.0 + mu) * eos.rho0 * e;
  const double p = eos_pressure(eos, mu, e);
  EXPECT_NEAR(c1, 138625.748, 1e-12 * 138625.748);
  EXPECT_NEAR(p, formula, 1e-12 * formula);
  EXPECT_NEAR(p, 17092.78555423987, 1e-12 * 17092.78555423987);
  // The energy coefficient is gamma0 rho0 (gamma rho = gamma0 rho0, eq 2-22).
  EXPECT_DOUBLE_EQ(eos.form(mu).b, eos.gamma0 * eos.rho0);
}

TEST(MieGruneisen, TensionUsesLinearHugoniotWithoutQuadraticAndCubicTerms) {
  // Reference: pH = C1 mu for mu < 0: p(-0.05, 1e4) = C1 (-0.05)(1 + 0.049 / 0.95)
  // + gamma0 rho0 1e4 = -7113.767908 MPa by hand; the cubic form would give a different
  // value. Tol 1e-12 rel.
  const MieGruneisen eos = copper_eos();
  const double mu = -0.05, e = 1.0e4;
  const double c1 = eos.rho0 * eos.c0 * eos.c0;
  const double formula =
      c1 * mu * (1.0 - 0.5 * eos.gamma0 * mu / (1.0 + mu)) + eos.gamma0 * eos.rho0 * e;
  const double p = eos_pressure(eos, mu, e);
  EXPECT_NEAR(p, formula, 1e-12 * std::abs(formula));
  EXPECT_NEAR(p, -7113.767908000002, 1e-12 * 7113.767908000002);
  const double c2 = c1 * (2.0 * eos.s - 1.0);
  const double c3 = c1 * (eos.s - 1.0) * (3.0 * eos.s - 1.0);
  const double cubic =
      (c1 * mu + c2 * mu * mu + c3 * mu * mu * mu) * (1.0 - 0.5 * eos.gamma0 * mu / (1.0 + mu)) +
      eos.gamma0 * eos.rho0 * e;
  EXPECT_GT(std::abs(p - cubic), 100.0);  // the compression branch would be off by ~700 MPa
}

TEST(MieGruneisen, HugoniotStatesHaveTheHugoniotPressure) {
  // Reference: eq 2-23 with P0 = E0 = 0 puts a state on the reference curve at
  // e_H = pH (V0 - V) / 2 = pH mu / (2 rho0 (1 + mu)) per unit mass; eq 2-25 must then give
  // p = pH, to round-off (1e-12 rel), up to 3.5x compression.
  const MieGruneisen eos = copper_eos();
  const double c1 = eos.rho0 * eos.c0 * eos.c0;
  const double c2 = c1 * (2.0 * eos.s - 1.0);
  const double c3 = c1 * (eos.s - 1.0) * (3.0 * eos.s - 1.0);
  for (double mu : {0.05, 0.2, 0.5, 0.8, 1.2, 2.5}) {
    const double ph = c1 * mu + c2 * mu * mu + c3 * mu * mu * mu;
    const double e_h = ph * mu / (2.0 * eos.rho0 * (1.0 + mu));
    EXPECT_NEAR(eos_pressure(eos, mu, e_h), ph, 1e-12 * ph) << "mu = " << mu;
  }
}

TEST(MieGruneisen, ColdPressureRisesWithCompressionAtEveryDensity) {
  // Reference: a solid's cold (e = 0) pressure rises with density; with gamma0 in place of
  // gamma in eq 2-25 it would peak at mu = 0.67 and fall (the factor 1 - gamma0 mu / 2
  // vanishes at mu = 1.02), and a 10 km/s impact of copper collapses. Exact sign checks up to
  // 4x compression.
  const MieGruneisen eos = copper_eos();
  double previous = 0.0;
  for (double mu = 0.05; mu <= 3.0; mu += 0.05) {
    const double p = eos_pressure(eos, mu, 0.0);
    EXPECT_GT(p, previous) << "mu = " << mu;
    EXPECT_GT(eos.tangent_bulk_modulus(mu, 0.0), 0.0) << "mu = " << mu;
    previous = p;
  }
}

TEST(MieGruneisen, LargeExpansionStaysFiniteAndMonotone) {
  // Reference: no clamp on mu (see mie_gruneisen.cpp): a(mu) = C1 mu (1 - gamma0 mu / (2 (1 + mu)))
  // is finite and increasing for -1 < mu < 0, so the tangent is positive. Exact sign checks.
  const MieGruneisen eos = copper_eos();
  double previous = eos_pressure(eos, -0.9, 0.0);
  for (double mu = -0.8; mu < 0.0; mu += 0.1) {
    const double p = eos_pressure(eos, mu, 0.0);
    EXPECT_TRUE(std::isfinite(p));
    EXPECT_GT(p, previous);
    EXPECT_GT(eos.tangent_bulk_modulus(mu, 0.0), 0.0);
    previous = p;
  }
}

TEST(MieGruneisen, TangentBulkModulusIsRhoDpDrhoAtFixedEnergy) {
  // Reference: K_t(0) = rho0 c0^2 exactly (1e-12 rel); elsewhere central differences of
  // (1 + mu) dp/dmu with h = 1e-6 (truncation ~1e-12, rounding ~1e-10 relative): tol 1e-7 rel.
  const MieGruneisen eos = copper_eos();
  const double c1 = eos.rho0 * eos.c0 * eos.c0;
  EXPECT_NEAR(eos.tangent_bulk_modulus(0.0, 0.0), c1, 1e-12 * c1);
  for (double mu : {-0.2, -0.05, 0.05, 0.2, 0.4, 0.9, 1.5}) {
    const double k = eos.tangent_bulk_modulus(mu, 2.0e4);
    EXPECT_NEAR(k, numerical_tangent(eos, mu, 2.0e4), 1e-7 * k) << "mu = " << mu;
  }
}

LinearPolynomialEos polynomial_eos() {
  LinearPolynomialEos eos;
  eos.rho0 = 2.7e-3;
  const double c[7] = {10.0, 7.0e4, 5.0e4, 2.0e4, 1.5, 0.4, 0.3};
  for (int i = 0; i < 7; ++i) eos.c[i] = c[i];
  return eos;
}

TEST(LinearPolynomialEos, CompressionPressureMatchesKeywordFormulaWithEnergyPerVolume) {
  // Reference: LS-DYNA *EOS_LINEAR_POLYNOMIAL p = C0 + C1 mu + C2 mu^2 + C3 mu^3
  // + (C4 + C5 mu + C6 mu^2) E with E = rho0 e; tol 1e-12 relative.
  const LinearPolynomialEos eos = polynomial_eos();
  const double mu = 0.08, e = 3.0e5;
  const double* c = eos.c;
  const double energy_per_volume = eos.rho0 * e;
  const double formula = c[0] + c[1] * mu + c[2] * mu * mu + c[3] * mu * mu * mu +
                         (c[4] + c[5] * mu + c[6] * mu * mu) * energy_per_volume;
  const double p = eos_pressure(eos, mu, e);
  EXPECT_NEAR(p, formula, 1e-12 * formula);
}

TEST(LinearPolynomialEos, TensionDropsC2AndC6) {
  // Reference: for mu < 0, p = C0 + C1 mu + C3 mu^3 + (C4 + C5 mu) E; tol 1e-12 relative.
  const LinearPolynomialEos eos = polynomial_eos();
  const double mu = -0.06, e = 3.0e5;
  const double* c = eos.c;
  const double formula = c[0] + c[1] * mu + c[3] * mu * mu * mu + (c[4] + c[5] * mu) * eos.rho0 * e;
  EXPECT_NEAR(eos_pressure(eos, mu, e), formula, 1e-12 * std::abs(formula));
}

TEST(LinearPolynomialEos, TangentBulkModulusIsRhoDpDrhoAtFixedEnergy) {
  // Reference: central differences of (1 + mu) dp/dmu at fixed e, tol 1e-7 relative.
  const LinearPolynomialEos eos = polynomial_eos();
  for (double mu : {-0.1, -0.01, 0.01, 0.1, 0.3}) {
    const double k = eos.tangent_bulk_modulus(mu, 3.0e5);
    EXPECT_NEAR(k, numerical_tangent(eos, mu, 3.0e5), 1e-7 * k) << "mu = " << mu;
  }
}

TEST(LinearEos, PressureIsBulkModulusTimesMuIndependentOfEnergy) {
  // Reference: p = K mu, b = 0; K_t = (1 + mu) K; exact up to one rounding (1e-15 rel).
  const LinearEos eos{1.6e5};
  EXPECT_NEAR(eos_pressure(eos, 0.02, 1.0e6), 1.6e5 * 0.02, 1e-15 * 3.2e3);
  EXPECT_EQ(eos.form(0.02).b, 0.0);
  EXPECT_NEAR(eos.tangent_bulk_modulus(0.02, 0.0), 1.02 * 1.6e5, 1e-15 * 1.6e5);
}

}  // namespace
}  // namespace afemp::core
