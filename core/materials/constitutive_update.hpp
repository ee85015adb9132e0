// Definition of constitutive_update (declared in material.hpp, which includes this file at its
// end: include material.hpp, not this header). Eq 2-41 of Ma 2005 with the energy equation
// de = (s_mid : de_dev - p_mid tr(d eps)) / rho solved in closed form with p = a(mu) + b(mu) e;
// a model with its own pressure law (Holmquist-Johnson-Cook concrete) updates the whole point.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/materials/failure.hpp"

namespace afemp::core {

template <bool Fails>
inline IncrementStart start_increment([[maybe_unused]] const Material& material,
                                      const PointState& point, const SymTensor& d_eps, double dt) {
  IncrementStart in;
  in.dt = dt;
  in.p_old = pressure(point.stress);
  in.s_old = point.stress.deviator();
  in.de_dev = d_eps.deviator();
  in.d_vol = d_eps.trace();  // dV / V over the increment
  // Work per unit mass uses the volume the increment acts on: the solvers update volume as
  // V_new = V_old (1 + tr d eps), so sigma : d eps V_old / m = sigma : d eps / rho_old, which
  // makes the volumetric work exact over a compress-release cycle (second order overall).
  in.inv_rho_work = 1.0 / (point.density * (1.0 + in.d_vol));  // one division per point
  if constexpr (Fails) {
    // Coupled damage (failure.hpp): the stress holds (1 - D_C D) times the effective deviator.
    in.softening = damage_softening(material.failure, point.damage);
    if (in.softening != 1.0) in.s_old = in.s_old * (1.0 / in.softening);
  }
  return in;
}

namespace failure_detail {
inline constexpr SymTensor zero_deviator{};
inline constexpr DeviatoricResult no_flow{};
}  // namespace failure_detail

template <class Eos, bool Fails>
inline PointUpdate finish_increment(const Material& material, const Eos& eos, bool thermal,
                                    PointState& point, const IncrementStart& in,
                                    const SymTensor& s_deviator, const DeviatoricResult& r_model) {
  static_assert(!IsOwnPressureLaw<Eos>, "a model's own pressure law goes with that model only");
  // A failed point (failure.hpp) carries no shear and no tension: whatever the strength model
  // returned, its deviator is zero, it flows no more, and its pressure is cut at zero.
  bool failed = false;
  if constexpr (Fails) failed = has_failed(point);
  const SymTensor& s_new = failed ? failure_detail::zero_deviator : s_deviator;
  const DeviatoricResult& r = failed ? failure_detail::no_flow : r_model;
  point.plastic_strain += r.plastic_strain_increment;
  // The plastic work by the trapezoidal rule, as the deviatoric work below: the stress's work on
  // the plastic strain at both ends of the radial return, dp (q_new + 3/2 s_old : s_new / q_new)
  // / 2. The rest of the deviatoric work is then exactly the change of the elastic energy
  // s : s / 4G, so the elastic energy (internal - plastic - viscous) cannot go negative; the end
  // flow stress alone, q_new dp, overstated the plastic work (and the Taylor-Quinney heat) by
  // half the hardening over each increment (a 2 mm steel block on a wall ended with an elastic
  // energy of -0.46 % of the initial energy).
  double plastic_work = 0.0;
  if (r.plastic_strain_increment > 0.0 && r.flow_stress > 0.0) {
    plastic_work = 0.5 * r.plastic_strain_increment *
                   (r.flow_stress + 1.5 * double_dot(in.s_old, s_new) / r.flow_stress) *
                   in.inv_rho_work;
  }

  // Trapezoidal deviatoric work: elastic (recoverable) and plastic parts together.
  double deviatoric_work = 0.5 * double_dot(in.s_old + s_new, in.de_dev) * in.inv_rho_work;
  if constexpr (Fails) {
    // Coupled damage: the stress is the effective one softened by the damage at the start;
    // the damage this increment adds drops it at the end, at fixed strain (no work).
    plastic_work *= in.softening;
    deviatoric_work *= in.softening;
  }
  const double d_vol = in.d_vol;
  double p_new;
  if constexpr (std::is_same_v<Eos, NoEos>) {
    p_new = in.p_old - material.bulk_modulus() * d_vol;
    // Without a failure model `failed` is the constant false and this folds away, so the
    // energy equation compiles as it did (material.hpp says why that matters).
    p_new = failed && p_new < 0.0 ? 0.0 : p_new;
    point.energy += deviatoric_work - 0.5 * (in.p_old + p_new) * d_vol * in.inv_rho_work;
  } else {
    const double mu = point.density / material.density - 1.0;
    EosLinearForm f = eos.form(mu);
    // A high explosive's products push with its burn fraction (programmed_burn.hpp): p = F p_JWL.
    if constexpr (std::is_same_v<Eos, Jwl>) {
      f.a *= point.burn;
      f.b *= point.burn;
    }
    // e_new = e* - p_new tr/(2 rho) with p_new = a + b e_new: linear in e_new, so the
    // midpoint-rule energy and the EOS pressure are consistent without iteration.
    const double e_star = point.energy + deviatoric_work - 0.5 * in.p_old * d_vol * in.inv_rho_work;
    const double half_strain = 0.5 * d_vol * in.inv_rho_work;
    // The implicit form needs 1 + b tr/(2 rho) > 0. Near the reference density that is any
    // step short of halving the volume, but b = Gamma rho0 (Gamma = Gamma0 rho0 / rho) over a
    // density 150 times below the reference (failed debris of V5) makes it 0.5 Gamma tr(de), and
    // a compression of 0.7 % per step then flips its sign: the point took e = 1e9 and 43 km/s.
    // There the increment's end pressure is estimated from e* instead (explicit; the step is
    // far beyond this point's own stable one, which a cut pressure does not limit).
    const double denominator = 1.0 + f.b * half_strain;
    point.energy = denominator > 0.5 ? (e_star - f.a * half_strain) / denominator
                                     : e_star - (f.a + f.b * e_star) * half_strain;
    p_new = f.a + f.b * point.energy;
    // No tension: the increment's pressure work is then p_old's half (folds away as above).
    const bool cut = failed && p_new < 0.0;
    point.energy = cut ? e_star : point.energy;
    p_new = cut ? 0.0 : p_new;
    // A fluid's cavitation (Material::pressure_cutoff, -inf unless set): the pressure stays at
    // or above it, the increment's work done at it.
    if (p_new < material.pressure_cutoff) {
      point.energy = e_star - material.pressure_cutoff * half_strain;
      p_new = material.pressure_cutoff;
    }
  }

  point.stress = s_new - p_new * SymTensor::identity();
  if (thermal) {
    point.temperature +=
        material.thermal.taylor_quinney * plastic_work / material.thermal.specific_heat;
  }
  if constexpr (Fails) {
    if (!failed) {
      // The triaxiality is the stress's: -p over the softened deviator's von Mises stress
      // (in uniaxial stress the pressure softens with the deviator, the EOS's with the strain).
      point.damage = failure_damage(material.failure, point.damage, point.plastic_strain,
                                    r.plastic_strain_increment, in.dt, p_new, in.softening * s_new,
                                    point.temperature);
      const double softening = damage_softening(material.failure, point.damage);
      if (softening != 1.0) point.stress = softening * s_new - p_new * SymTensor::identity();
    }
  }
  return {plastic_work};
}

template <class Strength, class Eos, bool Fails>
inline PointUpdate constitutive_update(const Material& material, const Strength& strength,
                                       const Eos& eos, bool thermal, PointState& point,
                                       const SymTensor& d_eps, double dt) {
  static_assert(composable<Strength, Eos>, "a model's own pressure law goes with it only");
  static_assert(!std::is_same_v<Strength, UserStrength>,
                "user strength models run on batches (user_strength_chunk.hpp), never per point");
  if constexpr (HasOwnPressureLaw<Strength>) {
    return strength.update_point(material, eos, point, d_eps, dt);
  } else {
    const IncrementStart in = start_increment<Fails>(material, point, d_eps, dt);
    SymTensor s_new = in.s_old;
    if constexpr (Fails) {
      if (has_failed(point))  // no strength: finish_increment zeroes the deviator
        return finish_increment<Eos, true>(material, eos, thermal, point, in, s_new, {});
    }
    const StrengthContext context{material.shear_modulus(), point.plastic_strain, point.temperature,
                                  dt};
    const DeviatoricResult r = strength.update(s_new, in.de_dev, context);
    return finish_increment<Eos, Fails>(material, eos, thermal, point, in, s_new, r);
  }
}

template <class Eos>
inline double tangent_bulk_modulus(const Material& material, const Eos& eos,
                                   const PointState& point) {
  const double mu = point.density / material.density - 1.0;
  if constexpr (std::is_same_v<Eos, NoEos>) {
    return material.bulk_modulus();
  } else if constexpr (IsOwnPressureLaw<Eos>) {
    return eos.tangent_bulk_modulus(mu, point);  // it reads the point's history
  } else {
    return eos.tangent_bulk_modulus(mu, point.energy);
  }
}

template <class Eos>
inline double wave_speed(const Material& material, const Eos& eos, const PointState& point) {
  // Below its reference density a point's pressure may be held at a floor, where dp/drho = 0:
  // - A failed point (a failure model's, or fully damaged HJC concrete: D = 1) carries no
  //   pressure (cut off at zero, or at -T (1 - D) = 0) and no shear: no signal crosses it until
  //   it is compacted again. Counting 4G/3 over its current density instead let a few debris
  //   particles, expanded 20 to 30 times, cut the stable step to a third (V6), and failed copper
  //   debris of a plate perforated at 2 km/s to a twentieth (V5). Without a failure model the
  //   damage stays 0 (HJC aside). Only a point whose pressure is cut is silent: failed debris
  //   that is hot enough to push (p > 0 below the reference density, a gas) carries the
  //   isentropic signal below, without shear; treating it as silent let one such copper
  //   particle in V5 run away to 1e7 m/s.
  // - A point cavitated at its cutoff (Material::pressure_cutoff) carries only its shear signal
  //   (none in a fluid) until it is compressed again. The EOS's tangent over the current density
  //   instead let one cavitated water particle, stretched fiftyfold at an explosion bubble's
  //   wall, cut the stable step to a fifth (examples/underwater_explosion/bubble.toml).
  const bool expanded = point.density < material.density;
  const bool failed = point.damage >= 1.0 && expanded;
  const double shear = 4.0 / 3.0 * material.shear_modulus();
  if constexpr (std::is_same_v<Eos, NoEos> || IsOwnPressureLaw<Eos>) {
    if (failed) return 0.0;
    return std::sqrt((tangent_bulk_modulus(material, eos, point) + shear) / point.density);
  } else {
    const EosLinearForm f = eos.form(point.density / material.density - 1.0);
    const double p = f.a + f.b * point.energy;
    if (failed && !(p > 0.0)) return 0.0;
    if (!failed && expanded && p <= material.pressure_cutoff)
      return std::sqrt(shear / point.density);
    // Along the isentrope de = p / rho^2 drho, so rho dp/drho|_s = K_e + (dp/de) p / rho: for
    // an ideal gas (p = (gamma - 1) rho e) c^2 = gamma p / rho, not p / rho. Only compression
    // (p > 0) adds; a tensile state keeps the fixed-e value, which is then the larger.
    const double k_e = tangent_bulk_modulus(material, eos, point);
    const double heat = p > 0.0 && f.b > 0.0 ? f.b * p / point.density : 0.0;
    if (failed) return std::sqrt((std::max(k_e, 0.0) + heat) / point.density);
    return std::sqrt((k_e + heat + shear) / point.density);
  }
}

}  // namespace afemp::core
