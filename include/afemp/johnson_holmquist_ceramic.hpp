// The Johnson-Holmquist ceramic model (JH-2; Johnson & Holmquist 1994, "An improved
// computational constitutive model for brittle materials", AIP Conf. Proc. 309, 981-984;
// LS-DYNA *MAT_110): armour ceramics, whose strength grows with pressure and falls with damage,
// and whose pressure law gains a bulking pressure as they fracture.
#pragma once

#include <cstddef>
#include <string_view>

#include "afemp/model_parameters.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

struct Material;     // afemp/material.hpp
struct PointState;   // the internal point state of a constitutive update
struct PointUpdate;  // and what it reports
struct Jh2Pressure;

/// JH-2 strength and damage (johnson_holmquist_ceramic.cpp). With the normalised pressure
/// P* = P / PHEL, T* = T / PHEL, sigma_HEL = 3/2 (HEL - PHEL) and the rate factor
/// r = 1 + C ln(max(epsdot / epsdot_0, 1)), epsdot the equivalent deviatoric strain rate:
///   intact     sigma_i* = A (P* + T*)^N r                      (paper eq 2)
///   fractured  sigma_f* = min(SFMAX, B P*^M r), 0 for P* < 0   (eq 3)
///   strength   sigma_y = sigma_HEL [sigma_i* - D (sigma_i* - sigma_f*)]   (eq 1)
///   damage     D += d eps_p / max(D1 (P* + T*)^D2, 0), D <= 1   (eqs 4, 5; D = 1 where the
///              fracture strain is 0, at the tension limit)
/// The pressure is Jh2Pressure's with the bulking pressure, limited to P >= -T (1 - D).
struct JohnsonHolmquist2 {
  static constexpr std::string_view name = "johnson-holmquist-2";  ///< in the scene file
  double A = 0.0, B = 0.0, C = 0.0, M = 1.0, N = 1.0;
  double reference_strain_rate = 1.0;   ///< epsdot_0, in the scene's time unit
  double tensile_strength = 0.0;        ///< T, the largest hydrostatic tension
  double max_fractured_strength = 0.0;  ///< SFMAX, normalised (0: no limit)
  double hel = 0.0;                     ///< HEL, the Hugoniot elastic limit (normal stress)
  double hel_pressure = 0.0;            ///< PHEL, the pressure at the HEL
  double beta = 1.0;                    ///< the fraction of the released energy that bulks
  double D1 = 0.0, D2 = 0.0;

  /// sigma_HEL = 3/2 (HEL - PHEL), the equivalent stress at the HEL.
  double hel_strength() const { return 1.5 * (hel - hel_pressure); }
  /// sigma* at normalised pressure p_star, damage and equivalent strain rate.
  double normalised_strength(double p_star, double damage, double strain_rate) const;
  /// Plastic strain to fracture at normalised pressure p_star, D1 (P* + T*)^D2 (0 below -T*).
  double fracture_strain(double p_star) const;

  bool thermal() const { return false; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = true;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = true;
  /// Its own history variable: the bulking pressure (core/materials/material.hpp,
  /// model_history_size; named in johnson_holmquist_ceramic.cpp).
  static constexpr std::size_t history_size = 1;
  static const char* history_name(std::size_t k);
  /// Its own pressure law: a material with this model takes eos jh2-pressure and no other.
  using PressureLaw = Jh2Pressure;
  /// The update of one point: pressure with the bulking pressure and the tension limit,
  /// deviator returned radially onto the strength at that pressure, damage, then the bulking
  /// pressure from the elastic energy the damage released (eq 7), acting from the next
  /// increment on; the energy equation of the other models.
  PointUpdate update_point(const Material& material, const Jh2Pressure& eos, PointState& point,
                           const SymTensor& d_eps, double dt) const;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp).
  void parameters(ParameterVisitor& v);
};

/// The JH-2 pressure law (Johnson & Holmquist 1994, eq 6), mu = rho / rho0 - 1:
///   P = K1 mu + K2 mu^2 + K3 mu^3 + dP   (mu >= 0),   P = K1 mu + dP   (mu < 0),
/// dP the bulking pressure a point has built (its history), which grows as the damage releases
/// elastic energy dU: dP_new = -K1 mu + sqrt((K1 mu + dP_old)^2 + 2 beta K1 dU)   (eq 7).
/// Independent of the internal energy.
struct Jh2Pressure {
  static constexpr std::string_view name = "jh2-pressure";  ///< in the scene file
  /// The strength model whose own pressure law this is (it goes with that model only).
  static constexpr std::string_view strength_model = JohnsonHolmquist2::name;
  double K1 = 0.0, K2 = 0.0, K3 = 0.0;

  /// The bulk modulus K1: with the material's G it gives E and nu.
  double elastic_modulus() const { return K1; }
  /// P at compression mu with the bulking pressure bulking, before the tension limit.
  double pressure(double mu, double bulking) const;
  /// The bulking pressure after the elastic energy per unit volume energy_loss was released
  /// at compression mu, from bulking_old (eq 7).
  double bulking_pressure(double mu, double bulking_old, double energy_loss, double beta) const;
  /// rho dp/drho for the time step.
  double tangent_bulk_modulus(double mu) const;
  double tangent_bulk_modulus(double mu, const PointState& point) const;
  void parameters(ParameterVisitor& v);
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::Jh2Pressure;
using core::JohnsonHolmquist2;
}  // namespace afemp
