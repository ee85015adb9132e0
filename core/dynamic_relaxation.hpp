// Dynamic relaxation as LS-DYNA runs it (*CONTROL_DYNAMIC_RELAXATION, explicit form; its
// fields and defaults as Ansys' LS-DYNA user's guide, "Dynamic Relaxation", and its EDDRELAX
// command give them): the model steps at its stable step with every velocity multiplied by
// DRFCTR after each step (damping proportional to the mass), until its kinetic energy has
// fallen to DRTOL of its peak; then it is put at rest, in the static state of the loads that act
// (gravity, constant loads), for models the implicit tangent cannot reach (particles, contact,
// materials without a tangent, coupling: fem/static_solve.hpp is meshes only).
//
// The convergence check. LS-DYNA checks every NRCYCK steps the ratio of the current
// distortional kinetic energy (rigid-body motion removed) to its peak over the relaxation, and
// has converged when it falls below DRTOL. afemp differs in two ways:
//   - the whole kinetic energy (Model::energies().kinetic) rather than its distortional part: a
//     general model (particles, rigid bodies, coupling) has no split of it into rigid and
//     distortional motion. Rigid-body motion decays under the same factor as the rest, so a
//     supported body reaches the same state; a body its supports do not hold, under a load that
//     accelerates it (which has no static state), keeps its kinetic energy (the damping's
//     terminal velocity) and does not converge, where the distortional ratio would call the
//     drifting body relaxed. A peak raised by rigid motion (a body dropped onto its support)
//     lowers the ratio below the distortional one: such a scene wants a smaller DRTOL;
//   - the kinetic energy compared is the largest over the steps since the last check, not the
//     value at the check (so it never converges earlier than LS-DYNA's check would on the same
//     history): the kinetic energy of an oscillation passes through zero twice a period, at
//     its largest displacement, and a check that fell there would take the state furthest from
//     equilibrium for a converged one.
// What is left of the displacement is about sqrt(DRTOL) of the static one for a load applied
// at once (its peak kinetic energy is the static state's strain energy): 3.2 % at the default,
// 0.32 % at 1e-5 (tests/core/test_dynamic_relaxation.cpp). The kinetic energy is read after
// every step, before and after the scaling (the peak is over every step, and the difference is
// what the damping took, RelaxationResult::damped); that costs two passes over the nodes or
// particles and elements, small beside the step. The model's clock runs on; a scene's
// relaxation phase (core/time_loop.cpp) then sets it to the phase's end and books the damped
// energy in the balance.
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "core/model.hpp"

namespace afemp::core {

// LS-DYNA's names in the comments; IRELAL (Papadrakakis' automatic control) and IDRFLG (the
// initialisation options) have no counterpart.
struct RelaxationSettings {
  // DRTOL: converged when the kinetic energy (see the file's comment) is below this fraction
  // of its peak.
  double tolerance = 1e-3;
  // DRFCTR: every velocity is multiplied by it after every step (in (0, 1]).
  double factor = 0.995;
  // NRCYCK: steps between convergence checks.
  long check_every = 250;
  // TSSFDR: the step is this times the model's stable step. LS-DYNA's TSSFDR replaces the
  // scene's factor TSSF (0 keeps it); afemp's models apply their own (element_time_step_factor,
  // time_step_factor), so here it multiplies them: 1, the default, keeps the scene's, and a
  // deck's TSSFDR is TSSFDR / TSSF here.
  double time_step_factor = 1.0;
  // DRTERM: the longest simulated time the relaxation may take (the last step is cut to end
  // there). LS-DYNA then goes on to the transient unconverged; relax() throws.
  double end = std::numeric_limits<double>::infinity();
};

// What relax() reports at each check, for a history row: steps and simulated time since the
// relaxation began, the kinetic energy now, the largest since the last check and over the
// whole relaxation, and their ratio recent / peak (0 while nothing has moved).
struct RelaxationCheck {
  long steps = 0;
  double time = 0.0;
  double kinetic = 0.0;
  double recent = 0.0;
  double peak = 0.0;
  double ratio = 0.0;
  double damped = 0.0;  // the kinetic energy the damping has taken out so far
};

struct RelaxationResult {
  long steps = 0;     // steps the relaxation took
  double time = 0.0;  // simulated time it took
  double peak_kinetic = 0.0;
  double ratio = 0.0;  // at the check that converged
  // The kinetic energy the damping took out of the motion (the scalings' and the final rest's,
  // each the kinetic energy before it less that after), for the caller's energy balance.
  double damped = 0.0;
  bool converged = false;
  // The force the damping put on each body (Energies::bodies' order) over the last step,
  // -(1 - factor) p / dt with p the body's momentum before the scaling. A body at rest in
  // equilibrium has none; a steady force the relaxation has not balanced (a support still
  // giving way, a contact still pushing) leaves the body drifting at the damping's terminal
  // velocity, where the damping holds that force: a kinetic energy far below DRTOL of the peak
  // can hide it, so the caller reports it beside the convergence.
  std::vector<Vec3> damping_force;
};

// Relaxes `model` from its current state: steps it at time_step_factor x its stable step,
// multiplying its velocities by `factor` after each, and checks every check_every steps (and
// at `end`); calls `observer` (when set) at each check and `after_step` (when set) after each
// step's scaling (a caller that holds some bodies at rest). At convergence puts the model at rest
// (Model::scale_velocities(0)) and returns converged. Throws std::invalid_argument for settings
// out of range (naming the setting), core::SimulationError when `end` comes unconverged (naming
// the step, the time and the ratio reached against the tolerance), and what the model's step
// throws; a caller stops a relaxation (a signal) by throwing from the observer.
RelaxationResult relax(Model& model, const RelaxationSettings& settings,
                       const std::function<void(const RelaxationCheck&)>& observer = {},
                       const std::function<void()>& after_step = {});

}  // namespace afemp::core
