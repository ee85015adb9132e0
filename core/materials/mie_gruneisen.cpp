// Mie-Grueneisen EOS with a linear Us-Up Hugoniot in the cubic form of Ma 2005, eqs 2-21..2-26:
// p = pH (1 - gamma mu / 2) + gamma rho e (eq 2-25) with gamma = gamma0 rho0 / rho (eq 2-22),
// so gamma mu = gamma0 mu / (1 + mu) and gamma rho = gamma0 rho0;
// pH = C1 mu + C2 mu^2 + C3 mu^3 (mu >= 0), pH = C1 mu (mu < 0),
// C1 = rho0 c0^2, C2 = C1 (2s - 1), C3 = C1 (s - 1)(3s - 1).
// Eq 2-25 comes from the Rankine-Hugoniot energy (eq 2-23) on the reference curve, whose
// correction term is gamma / 2 pH (V0 - V) / V: with gamma the current coefficient, a state on
// the Hugoniot (e = pH mu / (2 rho0 (1 + mu))) has p = pH exactly, and the factor
// 1 - gamma0 mu / (2 (1 + mu)) stays above 1 - gamma0 / 2 > 0 however far the material is
// compressed. (Taking gamma0 in the factor, as this file did before, makes it vanish at
// mu = 2 / gamma0 and the cold pressure of copper fall with compression beyond mu = 0.67: a
// km/s impact then collapses.) This is LS-DYNA's *EOS_GRUNEISEN numerator
// rho0 c0^2 mu (1 + (1 - gamma0 / 2) mu) over (1 + mu), with the cubic Hugoniot.
#include "afemp/equations_of_state.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

// mu is NOT clamped in expansion: the cubic Hugoniot has no pole (unlike the rational form
// rho0 c0^2 mu (1 + mu) / (1 - (s - 1) mu)^2, which needs a compression cutoff), and in
// tension a = C1 mu (1 - gamma0 mu / (2 (1 + mu))) stays finite for every mu > -1 with
// da/dmu = C1 (1 - gamma0 mu (2 + mu) / (2 (1 + mu)^2)) >= C1 > 0.
// Limiting the tensile pressure is a spall/failure criterion's job, not the EOS's.

namespace {

// pH and dpH/dmu.
struct Hugoniot {
  double p, dp;
};

Hugoniot hugoniot(const MieGruneisen& m, double mu) {
  const double c1 = m.rho0 * m.c0 * m.c0;
  if (mu < 0.0) return {c1 * mu, c1};
  const double c2 = c1 * (2.0 * m.s - 1.0);
  const double c3 = c1 * (m.s - 1.0) * (3.0 * m.s - 1.0);
  return {mu * (c1 + mu * (c2 + mu * c3)), c1 + mu * (2.0 * c2 + 3.0 * c3 * mu)};
}

}  // namespace

EosLinearForm MieGruneisen::form(double mu) const {
  const double factor = 1.0 - 0.5 * gamma0 * mu / (1.0 + mu);
  // gamma rho = gamma0 rho0 (eq 2-22) makes the energy coefficient constant.
  return {hugoniot(*this, mu).p * factor, gamma0 * rho0};
}

double MieGruneisen::tangent_bulk_modulus(double mu, double /*e*/) const {
  // b = gamma0 rho0 is independent of mu, so only a(mu) contributes to dp/dmu at fixed e.
  const Hugoniot h = hugoniot(*this, mu);
  const double factor = 1.0 - 0.5 * gamma0 * mu / (1.0 + mu);
  const double dfactor = -0.5 * gamma0 / ((1.0 + mu) * (1.0 + mu));
  const double k = (1.0 + mu) * (h.dp * factor + h.p * dfactor);  // rho dp/drho
  return k > 0.0 ? k : 0.0;
}

void MieGruneisen::parameters(ParameterVisitor& v) {
  // The reference density is the material's.
  if (v.reading()) rho0 = v.material().density;
  v.require(rho0 > 0.0, "rho0", out_of_range(rho0, "value > 0 (the material's density)"));
  v.required("c0", c0, Range::positive());
  v.required("s", s, Range::non_negative());
  v.required("gamma0", gamma0, Range::non_negative());
}

}  // namespace afemp::core
