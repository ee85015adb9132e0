// Uniaxial-stress form of the shared material law, for trusses and other bars: the 3-D
// constitutive_update (material.hpp) driven by d_eps = diag(d_axial, d_l, d_l), with the
// lateral strain increment d_l found by secant iteration so that the lateral stress vanishes.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "core/materials/material.hpp"

namespace afemp::core {

struct UniaxialUpdate {
  PointUpdate point;                      // the accepted trial's constitutive update
  double lateral_strain_increment = 0.0;  // d_l, the same in y and z
  int trials = 0;                         // constitutive updates evaluated
  bool converged = false;                 // |sigma_yy| met the tolerance
};

// Most trials of one increment. Elastic points converge at the first (d_l = -nu d_axial is
// exact for the hypoelastic law), linear-hardening points in 2 or 3, Johnson-Cook and EOS
// points in 4 or 5 (the rate term's logarithm bends r(d_l) the most); the cap is reached
// only by an increment that makes the law itself misbehave, and then the trial with the
// smallest lateral stress is kept (converged = false).
inline constexpr int kMaxUniaxialTrials = 30;

// Lateral stress tolerance relative to max(|sigma_xx|, E |d_axial|).
inline constexpr double kUniaxialLateralTolerance = 1e-10;

// Elastic modulus of a bar under uniaxial stress, E_t = 9 K_t G / (3 K_t + G); E itself
// without an EOS. The bar wave speed sqrt(E_t / rho) bounds a truss's time step.
template <class Eos>
inline double uniaxial_modulus(const Material& material, const Eos& eos, const PointState& point) {
  const double k = tangent_bulk_modulus(material, eos, point);
  const double g = material.shear_modulus();
  return 9.0 * k * g / (3.0 * k + g);
}

// Advances `point` by the axial strain increment d_axial (= axial strain rate * dt) under
// uniaxial stress. The point's stress is in the bar's frame, axis along x, lateral stresses
// zero to the tolerance above. point.density is rho^k on entry and rho^{k+1} on return,
// rho^{k+1} = rho^k / (1 + d_axial + 2 d_l) as in the particle volume update (Ma 2005,
// eq 2-40), so every trial sees the density its own lateral strain implies.
//
// The lateral stress r(d_l) increases monotonically with d_l (more lateral stretch, more
// lateral tension) and is linear on each elastic or linear-hardening branch. The first trial
// is the elastic guess d_l = -nu d_axial. If it flows plastically, the second is the
// isochoric d_l = -d_axial / 2 (exact for perfect plasticity without an EOS, and with the
// first it brackets the root under hardening); otherwise a Newton step with the elastic
// slope dr/dd_l = 2 K_t + 2G/3. Then secant steps, exact on a linear branch; once trials on
// both sides of the root are known, a secant step leaving that bracket is replaced by
// bisection. Every trial starts from the same entry state.
template <class Strength, class Eos>
UniaxialUpdate uniaxial_update(const Material& material, const Strength& strength, const Eos& eos,
                               bool thermal, PointState& point, double d_axial, double dt) {
  const PointState start = point;
  const double scale_floor = material.youngs_modulus * std::abs(d_axial);
  const double inf = std::numeric_limits<double>::infinity();

  UniaxialUpdate best;
  double best_residual = inf;
  PointState trial;
  // Runs one trial from the entry state; returns its lateral stress (mean of yy and zz), 0 once
  // within tolerance, and keeps the trial if it converged or has the smallest |r| so far.
  auto lateral_stress = [&](double d_l) {
    trial = start;
    const double d_vol = d_axial + 2.0 * d_l;
    trial.density = start.density / (1.0 + d_vol);
    const PointUpdate u = constitutive_update(material, strength, eos, thermal, trial,
                                              SymTensor{d_axial, d_l, d_l, 0.0, 0.0, 0.0}, dt);
    ++best.trials;
    const double r = 0.5 * (trial.stress.yy + trial.stress.zz);
    const double tolerance =
        kUniaxialLateralTolerance * std::max(std::abs(trial.stress.xx), scale_floor);
    const bool within = std::abs(r) <= tolerance;
    if (within || std::abs(r) < best_residual) {
      best_residual = std::abs(r);
      best.point = u;
      best.lateral_strain_increment = d_l;
      best.converged = within;
      point = trial;
    }
    return within ? 0.0 : r;
  };

  double x_prev = -material.poisson_ratio * d_axial;
  double r_prev = lateral_stress(x_prev);
  if (r_prev == 0.0) return best;
  double x;
  if (trial.plastic_strain > start.plastic_strain && d_axial != 0.0) {
    x = -0.5 * d_axial;
  } else {
    const double elastic_slope =
        2.0 * tangent_bulk_modulus(material, eos, start) + 2.0 / 3.0 * material.shear_modulus();
    x = x_prev - r_prev / elastic_slope;
  }
  double below = r_prev < 0.0 ? x_prev : -inf;  // largest d_l with r < 0
  double above = r_prev > 0.0 ? x_prev : inf;   // smallest d_l with r > 0

  while (best.trials < kMaxUniaxialTrials) {
    const double r = lateral_stress(x);
    if (r == 0.0) break;
    if (r < 0.0) {
      below = std::max(below, x);
    } else {
      above = std::min(above, x);
    }
    double next = r == r_prev ? x : x - r * (x - x_prev) / (r - r_prev);
    if (std::isfinite(below) && std::isfinite(above) && !(next > below && next < above)) {
      next = 0.5 * (below + above);
    }
    if (next == x) break;  // no representable progress left
    x_prev = x;
    r_prev = r;
    x = next;
  }
  return best;
}

// One-point form for tests and slow paths: visits the material's strength and EOS.
inline UniaxialUpdate uniaxial_update(const Material& material, PointState& point, double d_axial,
                                      double dt) {
  const bool thermal = material.has_thermal_term();
  return visit_models(material, [&](const auto& strength, const auto& eos) {
    return uniaxial_update(material, strength, eos, thermal, point, d_axial, dt);
  });
}

// One-point form of uniaxial_modulus.
inline double uniaxial_modulus(const Material& material, const PointState& point) {
  return std::visit([&](const auto& eos) { return uniaxial_modulus(material, eos, point); },
                    material.eos);
}

}  // namespace afemp::core
