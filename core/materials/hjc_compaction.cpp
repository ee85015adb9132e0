// Pressure-compaction law of Holmquist, Johnson & Cook (1993), "A computational constitutive
// model for concrete subjected to large strains, high strain rates, and high pressures", 14th
// Int. Symp. Ballistics, pp. 591-600 (LS-DYNA *MAT_HOLMQUIST_JOHNSON_COOK, *MAT_111), with
// mu = rho / rho0 - 1 and the largest compaction mu_max reached:
//   I   mu <= mu_c (elastic, also tension):  P = K_e mu,  K_e = P_c / mu_c
//   II  mu_c < mu <= mu_plock (crushing):     P = P_c + (P_l - P_c)(mu - mu_c)/(mu_plock - mu_c)
//       unloading from mu_max:                P = P(mu_max) - K_u (mu_max - mu),
//                                             K_u = (1 - F) K_e + F K1,
//                                             F = (mu_max - mu_c)/(mu_plock - mu_c)
//   III mu > mu_plock (fully dense):          P = K1 mubar + K2 mubar^2 + K3 mubar^3,
//                                             mubar = (mu - mu_l)/(1 + mu_l)
//       unloading from mu_max:                P = P(mu_max) - K1 (mubar_max - mubar)
// mu_l is the locking strain, where the fully dense curve has P = 0, and mu_plock the strain at
// which it reaches P_l: crushing ends there, so P is continuous. (Reading the crushing line as
// ending at (mu_l, P_l) would make P drop from P_l to 0 at mu_l.) The unloading modulus jumps
// from K1 to K1 / (1 + mu_l) at mu_plock, as in the paper, which interpolates towards K1 itself.
#include <algorithm>
#include <cmath>
#include <limits>

#include "afemp/equations_of_state.hpp"
#include "core/materials/holmquist_johnson_cook.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

namespace {

double dense_pressure(double k1, double k2, double k3, double mubar) {
  return mubar * (k1 + mubar * (k2 + mubar * k3));
}

}  // namespace

HjcCompaction::HjcCompaction(double crush_pressure, double crush_strain, double lock_pressure,
                             double lock_strain, double k1, double k2, double k3)
    : crush_pressure_(crush_pressure),
      crush_strain_(crush_strain),
      lock_pressure_(lock_pressure),
      lock_strain_(lock_strain),
      k1_(k1),
      k2_(k2),
      k3_(k3) {
  // Bisection for dense_pressure(mubar) = P_l on [0, hi], hi doubled until it brackets.
  plock_strain_ = std::numeric_limits<double>::quiet_NaN();
  if (!(k1 > 0.0 && lock_pressure > 0.0)) return;
  double lo = 0.0, hi = lock_pressure / k1;
  for (int i = 0; i < 64 && dense_pressure(k1, k2, k3, hi) < lock_pressure; ++i) hi *= 2.0;
  if (!(dense_pressure(k1, k2, k3, hi) >= lock_pressure)) return;
  for (int i = 0; i < 200 && hi - lo > 4.0 * std::numeric_limits<double>::epsilon() * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (dense_pressure(k1, k2, k3, mid) < lock_pressure)
      lo = mid;
    else
      hi = mid;
  }
  plock_strain_ = lock_strain + (1.0 + lock_strain) * 0.5 * (lo + hi);
}

double HjcCompaction::loading_pressure(double mu) const {
  if (mu <= crush_strain_) return elastic_modulus() * mu;
  if (mu <= plock_strain_)
    return crush_pressure_ + (lock_pressure_ - crush_pressure_) * (mu - crush_strain_) /
                                 (plock_strain_ - crush_strain_);
  return dense_pressure(k1_, k2_, k3_, (mu - lock_strain_) / (1.0 + lock_strain_));
}

double HjcCompaction::loading_slope(double mu) const {
  if (mu <= crush_strain_) return elastic_modulus();
  if (mu <= plock_strain_)
    return (lock_pressure_ - crush_pressure_) / (plock_strain_ - crush_strain_);
  const double mubar = (mu - lock_strain_) / (1.0 + lock_strain_);
  return (k1_ + mubar * (2.0 * k2_ + 3.0 * k3_ * mubar)) / (1.0 + lock_strain_);
}

double HjcCompaction::unloading_modulus(double mu_max) const {
  if (mu_max <= crush_strain_) return elastic_modulus();
  if (mu_max <= plock_strain_) {
    const double f = (mu_max - crush_strain_) / (plock_strain_ - crush_strain_);
    return (1.0 - f) * elastic_modulus() + f * k1_;
  }
  return k1_ / (1.0 + lock_strain_);  // slope K1 in mubar
}

double HjcCompaction::pressure(double mu, double mu_max) const {
  if (mu >= mu_max) return loading_pressure(mu);
  return loading_pressure(mu_max) - unloading_modulus(mu_max) * (mu_max - mu);
}

double HjcCompaction::plastic_compaction(double mu_max) const {
  // Crushing ends at mu_plock: the fully dense material has no voids left to close.
  const double mu = std::min(mu_max, plock_strain_);
  if (mu <= crush_strain_) return 0.0;
  return mu - loading_pressure(mu) / unloading_modulus(mu);
}

double HjcCompaction::tangent_bulk_modulus(double mu, double mu_max) const {
  const double slope = std::max(loading_slope(mu_max), unloading_modulus(mu_max));
  return std::max((1.0 + mu) * slope, 0.0);
}

double HjcCompaction::tangent_bulk_modulus(double mu, const PointState& point) const {
  return tangent_bulk_modulus(mu, point.history[kMaxCompaction]);
}

void HjcCompaction::parameters(ParameterVisitor& v) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  v.required("PC", crush_pressure_, Range::positive());
  v.required("muc", crush_strain_, {0.0, 1.0, true, true});
  v.required("PL", lock_pressure_, Range::above(crush_pressure_));
  v.required("mul", lock_strain_, {crush_strain_, 1.0, true, true});
  // Unloading stiffens as the voids close: K1 >= K_e = PC / muc.
  v.required("K1", k1_, Range::at_least(crush_pressure_ / crush_strain_));
  v.required("K2", k2_, Range::any());
  v.required("K3", k3_, Range::non_negative());
  if (v.reading())
    *this =
        HjcCompaction(crush_pressure_, crush_strain_, lock_pressure_, lock_strain_, k1_, k2_, k3_);
  // The dense curve must rise for every mubar >= 0: its slope K1 + 2 K2 x + 3 K3 x^2 is
  // smallest at x = max(0, -K2 / (3 K3)) (K3 > 0) or grows without bound only if K2 >= 0.
  if (k3_ > 0.0) {
    const double x = std::max(0.0, -k2_ / (3.0 * k3_));
    v.require(k1_ + x * (2.0 * k2_ + 3.0 * k3_ * x) > 0.0, "K2",
              out_of_range(k2_,
                           "such that K1 + 2 K2 x + 3 K3 x^2 > 0 for x >= 0 (pressure "
                           "rises with compaction)"));
  } else {
    v.require(k2_ >= 0.0, "K2", out_of_range(k2_, "value >= 0 when K3 = 0"));
  }
  v.require(plock_strain_ > crush_strain_ && plock_strain_ < inf, "PL",
            "mu_plock = " + format_value(plock_strain_) +
                ", where the dense curve reaches PL, must be > muc (lower PL or mul)");
  const double crush_slope = loading_slope(0.5 * (crush_strain_ + plock_strain_));
  v.require(crush_slope <= elastic_modulus(), "PL",
            "(PL - PC) / (mu_plock - muc) = " + format_value(crush_slope) +
                " must be <= PC / muc (crushing is softer than the elastic response)");
}

}  // namespace afemp::core
