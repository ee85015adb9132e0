// Equations of state: the volumetric half of a material. Every EOS here but HjcCompaction is
// linear in the specific internal energy e, p = a(mu) + b(mu) e with mu = rho / rho0 - 1, which
// lets the energy equation be solved in closed form together with the new pressure
// (material.hpp). HjcCompaction is independent of e but depends on the compaction history.
#pragma once

#include <string_view>

#include "afemp/model_parameters.hpp"

namespace afemp::core {
struct PointState;  // the internal point state of a constitutive update
}

namespace afemp::core {

/// An EOS at fixed density as p = a + b e (e the specific internal energy).
struct EosLinearForm {
  double a = 0.0;  ///< pressure at zero internal energy
  double b = 0.0;  ///< dp/de at fixed density
};

/// No equation of state: pressure follows the hypoelastic law dp = -K tr(d eps), done by the
/// composition itself; this type exists so that the variant is never empty.
struct NoEos {};

/// Linear EOS: p = K mu.
struct LinearEos {
  static constexpr std::string_view name = "linear";  ///< in the scene file
  double bulk_modulus = 0.0;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in linear_eos.cpp.
  void parameters(ParameterVisitor& v);
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;  ///< rho dp/drho
};

/// Mie-Grueneisen with a linear Us-Up Hugoniot (Ma 2005, eqs 2-21..2-26):
/// p = pH (1 - gamma mu / 2) + gamma rho e with gamma = gamma0 rho0 / rho (eq 2-22), i.e.
/// p = pH (1 - gamma0 mu / (2 (1 + mu))) + gamma0 rho0 e,
/// pH = C1 mu + C2 mu^2 + C3 mu^3 (mu >= 0), pH = C1 mu (mu < 0),
/// C1 = rho0 c0^2, C2 = C1 (2s - 1), C3 = C1 (s - 1)(3s - 1).
struct MieGruneisen {
  static constexpr std::string_view name = "mie-gruneisen";
  double rho0 = 0.0, c0 = 0.0, s = 0.0, gamma0 = 0.0;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in mie_gruneisen.cpp.
  void parameters(ParameterVisitor& v);
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;
};

/// Linear polynomial (LS-DYNA *EOS_LINEAR_POLYNOMIAL):
/// p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) rho0 e,
/// with C2 and C6 terms dropped in tension (mu < 0).
struct LinearPolynomialEos {
  static constexpr std::string_view name = "linear-polynomial";
  double rho0 = 0.0;
  double c[7] = {0, 0, 0, 0, 0, 0, 0};
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in
  /// linear_polynomial_eos.cpp.
  void parameters(ParameterVisitor& v);
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;
};

/// Jones-Wilkins-Lee EOS of detonation products (Lee, Hornig & Kury 1968; LS-DYNA *EOS_JWL):
/// p = A (1 - omega / (R1 V)) e^(-R1 V) + B (1 - omega / (R2 V)) e^(-R2 V) + omega E / V,
/// V = rho0 / rho the relative volume and E = rho0 e the internal energy per unit reference
/// volume; E0 is its initial value (the detonation energy per unit volume), which the points
/// of the material start with. Linear in e: a(V) the first two terms, b = omega rho0 / V.
struct Jwl {
  static constexpr std::string_view name = "jwl";
  double rho0 = 0.0, A = 0.0, B = 0.0, R1 = 0.0, R2 = 0.0, omega = 0.0, E0 = 0.0;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in jwl.cpp.
  void parameters(ParameterVisitor& v);
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;
  /// p at relative volume V and energy per unit reference volume E.
  double pressure(double V, double E) const;
};

/// Pressure-compaction law of the Holmquist-Johnson-Cook concrete model (hjc_compaction.cpp):
/// elastic up to the crush point (mu_c, P_c), linear crushing of the air voids up to the lock
/// pressure P_l, then the fully dense cubic in mubar = (mu - mu_l) / (1 + mu_l). Unloading
/// follows a modulus set by the largest compaction mu_max reached, so the law needs that
/// history; the HJC update (holmquist_johnson_cook.cpp) is its only user. The tension cutoff
/// -T (1 - D) belongs to the strength model and is applied there.
class HjcCompaction {
 public:
  static constexpr std::string_view name = "hjc-compaction";
  /// The strength model whose own pressure law this is (it goes with that model only).
  static constexpr std::string_view strength_model = "holmquist-johnson-cook";
  HjcCompaction() = default;
  /// Finds mu_plock, the strain at which the fully dense curve reaches lock_pressure (NaN when
  /// it never does; Material::validate reports that).
  HjcCompaction(double crush_pressure, double crush_strain, double lock_pressure,
                double lock_strain, double k1, double k2, double k3);

  double crush_pressure() const { return crush_pressure_; }  ///< P_c
  double crush_strain() const { return crush_strain_; }      ///< mu_c
  double lock_pressure() const { return lock_pressure_; }    ///< P_l
  double lock_strain() const { return lock_strain_; }        ///< mu_l: dense curve's P = 0 point
  double plock_strain() const { return plock_strain_; }      ///< mu_plock: crushing ends, P = P_l
  double k1() const { return k1_; }
  double k2() const { return k2_; }
  double k3() const { return k3_; }
  double elastic_modulus() const { return crush_pressure_ / crush_strain_; }  ///< K_e = P_c / mu_c

  /// Pressure on the virgin loading curve (mu >= mu_max: the point compacts further).
  double loading_pressure(double mu) const;
  /// dP/dmu of the virgin loading curve.
  double loading_slope(double mu) const;
  /// dP/dmu of the unloading (and reloading) line from mu_max.
  double unloading_modulus(double mu_max) const;
  /// Pressure at mu after the largest compaction mu_max >= mu, before the tension cutoff.
  double pressure(double mu, double mu_max) const;
  /// Permanent volumetric strain mu_p left at P = 0 after mu_max: the crushed air voids.
  double plastic_compaction(double mu_max) const;
  /// rho dp/drho for the time step: the stiffer of the loading and unloading slopes at mu_max,
  /// because a point loading now may unload in the next step.
  double tangent_bulk_modulus(double mu, double mu_max) const;
  /// The same at a point's own largest compaction (its history, holmquist_johnson_cook.hpp).
  double tangent_bulk_modulus(double mu, const PointState& point) const;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in hjc_compaction.cpp.
  void parameters(ParameterVisitor& v);

 private:
  double crush_pressure_ = 0.0, crush_strain_ = 0.0, lock_pressure_ = 0.0, lock_strain_ = 0.0;
  double k1_ = 0.0, k2_ = 0.0, k3_ = 0.0;
  double plock_strain_ = 0.0;
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::HjcCompaction;
using core::Jwl;
using core::LinearEos;
using core::LinearPolynomialEos;
using core::MieGruneisen;
using core::NoEos;
}  // namespace afemp
