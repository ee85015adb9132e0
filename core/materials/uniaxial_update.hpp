// Uniaxial-stress form of the shared material law, for trusses and other bars: the 3-D
// constitutive_update (material.hpp) driven by d_eps = diag(d_axial, d_l, d_l), with the
// lateral strain increment d_l found by secant iteration so that the lateral stress vanishes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/materials/material.hpp"
#include "core/materials/user_strength_chunk.hpp"

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

// The search for one point's lateral strain increment d_l under uniaxial stress, as a state
// machine: next() is the d_l of the next trial, take() records the trial's result and picks
// the following d_l, until done(). uniaxial_update runs it point by point; a user strength
// model runs the trials of a chunk of points as one batch (uniaxial_update_user).
//
// The lateral stress r(d_l) increases monotonically with d_l (more lateral stretch, more
// lateral tension) and is linear on each elastic or linear-hardening branch. The first trial
// is the elastic guess d_l = -nu d_axial. If it flows plastically, the second is the
// isochoric d_l = -d_axial / 2 (exact for perfect plasticity without an EOS, and with the
// first it brackets the root under hardening); otherwise a Newton step with the elastic
// slope dr/dd_l = 2 K_t + 2G/3. Then secant steps, exact on a linear branch; once trials on
// both sides of the root are known, a secant step leaving that bracket is replaced by
// bisection. Every trial starts from the same entry state.
class UniaxialSearch {
 public:
  UniaxialSearch() = default;
  UniaxialSearch(const Material& material, const PointState& start, double d_axial)
      : start_(start),
        d_axial_(d_axial),
        scale_floor_(material.youngs_modulus * std::abs(d_axial)),
        x_(-material.poisson_ratio * d_axial) {}

  bool done() const { return done_; }
  const UniaxialUpdate& result() const { return best_; }
  // The next trial's entry state (the start, with the density its lateral strain implies:
  // rho^{k+1} = rho^k / (1 + d_axial + 2 d_l), Ma 2005 eq 2-40) and strain increment.
  PointState trial_state() const {
    PointState trial = start_;
    const double d_vol = d_axial_ + 2.0 * x_;
    trial.density = start_.density / (1.0 + d_vol);
    return trial;
  }
  SymTensor trial_increment() const { return {d_axial_, x_, x_, 0.0, 0.0, 0.0}; }

  // Records the trial at next(), `trial` its state after the constitutive update u. Returns
  // true when it is the best so far (then also copied into `point`).
  template <class Eos>
  bool take(const Material& material, const Eos& eos, const PointState& trial, const PointUpdate& u,
            PointState& point) {
    ++best_.trials;
    double r = 0.5 * (trial.stress.yy + trial.stress.zz);
    const double tolerance =
        kUniaxialLateralTolerance * std::max(std::abs(trial.stress.xx), scale_floor_);
    const bool within = std::abs(r) <= tolerance;
    const bool kept = within || std::abs(r) < best_residual_;
    if (kept) {
      best_residual_ = std::abs(r);
      best_.point = u;
      best_.lateral_strain_increment = x_;
      best_.converged = within;
      point = trial;
    }
    if (within) r = 0.0;
    const double x = x_;
    if (best_.trials == 1) {
      x_prev_ = x;
      r_prev_ = r;
      if (r == 0.0) {
        done_ = true;
        return kept;
      }
      if (trial.plastic_strain > start_.plastic_strain && d_axial_ != 0.0) {
        x_ = -0.5 * d_axial_;
      } else {
        const double elastic_slope = 2.0 * tangent_bulk_modulus(material, eos, start_) +
                                     2.0 / 3.0 * material.shear_modulus();
        x_ = x - r / elastic_slope;
      }
      if (r < 0.0) below_ = x;
      if (r > 0.0) above_ = x;
    } else {
      if (r == 0.0) {
        done_ = true;
        return kept;
      }
      if (r < 0.0) {
        below_ = std::max(below_, x);
      } else {
        above_ = std::min(above_, x);
      }
      double next = r == r_prev_ ? x : x - r * (x - x_prev_) / (r - r_prev_);
      if (std::isfinite(below_) && std::isfinite(above_) && !(next > below_ && next < above_)) {
        next = 0.5 * (below_ + above_);
      }
      if (next == x) {  // no representable progress left
        done_ = true;
        return kept;
      }
      x_prev_ = x;
      r_prev_ = r;
      x_ = next;
    }
    if (best_.trials >= kMaxUniaxialTrials) done_ = true;
    return kept;
  }

 private:
  static constexpr double inf = std::numeric_limits<double>::infinity();
  PointState start_;
  double d_axial_ = 0.0, scale_floor_ = 0.0;
  UniaxialUpdate best_;
  double best_residual_ = inf;
  double x_ = 0.0, x_prev_ = 0.0, r_prev_ = 0.0;
  double below_ = -inf;  // largest d_l with r < 0
  double above_ = inf;   // smallest d_l with r > 0
  bool done_ = false;
};

// Advances `point` by the axial strain increment d_axial (= axial strain rate * dt) under
// uniaxial stress. The point's stress is in the bar's frame, axis along x, lateral stresses
// zero to the tolerance above. point.density is rho^k on entry and rho^{k+1} on return.
template <class Strength, class Eos>
UniaxialUpdate uniaxial_update(const Material& material, const Strength& strength, const Eos& eos,
                               bool thermal, PointState& point, double d_axial, double dt) {
  UniaxialSearch search(material, point, d_axial);
  while (!search.done()) {
    PointState trial = search.trial_state();
    const PointUpdate u =
        constitutive_update(material, strength, eos, thermal, trial, search.trial_increment(), dt);
    search.take(material, eos, trial, u, point);
  }
  return search.result();
}

// uniaxial_update for points 0..n-1 (n <= kUserChunk) of a user strength model: each round of
// trials of the points still searching is one call of the user's function. history[j] is
// point j's history, the entry values on the way in and the accepted trial's on the way out;
// `kept` is scratch of n * chunk.history_count() doubles.
template <class Eos>
void uniaxial_update_user(const Material& material, UserStrengthChunk& chunk, const Eos& eos,
                          bool thermal, PointState* points, const double* d_axial,
                          double* const* history, std::size_t n, double dt, UniaxialUpdate* results,
                          std::vector<double>& kept) {
  const std::size_t hc = chunk.history_count();
  std::array<UniaxialSearch, kUserChunk> search;
  std::array<std::size_t, kUserChunk> point_of_slot;
  std::array<PointState, kUserChunk> trial;
  std::array<IncrementStart, kUserChunk> start;
  kept.resize(n * hc);
  for (std::size_t j = 0; j < n; ++j) search[j] = UniaxialSearch(material, points[j], d_axial[j]);
  for (;;) {
    std::size_t count = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (search[j].done()) continue;
      trial[count] = search[j].trial_state();
      start[count] = start_increment(material, trial[count], search[j].trial_increment(), dt);
      chunk.load(count, trial[count], start[count], history[j]);
      point_of_slot[count++] = j;
    }
    if (count == 0) break;
    chunk.run(count, dt);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t j = point_of_slot[k];
      const PointUpdate u = finish_increment(material, eos, thermal, trial[k], start[k],
                                             chunk.deviator(k), chunk.result(k));
      if (search[j].take(material, eos, trial[k], u, points[j]))
        chunk.store_history(k, kept.data() + j * hc);
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    results[j] = search[j].result();
    std::copy_n(kept.data() + j * hc, hc, history[j]);
  }
}

// One-point form for tests and slow paths: visits the material's strength and EOS. A user
// strength model with history variables needs the point's `history` (in and out).
inline UniaxialUpdate uniaxial_update(const Material& material, PointState& point, double d_axial,
                                      double dt, double* history = nullptr) {
  const bool thermal = material.has_thermal_term();
  return visit_models(material, [&](const auto& strength, const auto& eos) {
    if constexpr (is_user_strength<std::decay_t<decltype(strength)>>) {
      UserStrengthChunk chunk(material, strength);
      if (chunk.history_count() > 0 && history == nullptr)
        throw std::invalid_argument("material '" + material.name +
                                    "': its strength model has history variables; pass them");
      std::vector<double> kept;
      UniaxialUpdate u;
      uniaxial_update_user(material, chunk, eos, thermal, &point, &d_axial, &history, 1, dt, &u,
                           kept);
      return u;
    } else {
      return uniaxial_update(material, strength, eos, thermal, point, d_axial, dt);
    }
  });
}

// One-point form of uniaxial_modulus.
inline double uniaxial_modulus(const Material& material, const PointState& point) {
  return std::visit([&](const auto& eos) { return uniaxial_modulus(material, eos, point); },
                    material.eos);
}

}  // namespace afemp::core
