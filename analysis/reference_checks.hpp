// The checks a scene states in [reference]: the run's result beside the value the scene gives
// (Taylor measures against Ma 2005 eq 2-42, a body's mean velocity, the largest energy-balance
// error), filled into the summary after the time loop's last step (afemp::Simulation::finish,
// and run() below). The time loop itself (core/time_loop.hpp) knows no particular problem.
#pragma once

#include "afemp/run.hpp"
#include "core/model.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"

namespace afemp::analysis {

// Sets summary.taylor and summary.taylor_error (the first flat-ended cylinder body, when the
// scene states a Taylor reference) and appends summary.checks in the scene's order, from the
// model's final state and summary.final and summary.max_energy_error.
void check_references(const core::Model& model, const core::Scene& scene, RunSummary& summary);

// Runs `model` to scene.run.end_time (or max_steps, or [run] terminate) in a core::TimeLoop and
// checks the scene's references. Throws core::SimulationError from the model after flushing
// what was written.
RunSummary run(core::Model& model, const core::Scene& scene, const core::RunOptions& options);

}  // namespace afemp::analysis
