// The checks a scene states in [reference]: the run's result beside the value the scene gives
// (Taylor measures against Ma 2005 eq 2-42, a body's mean velocity, the largest energy-balance
// error), filled into the summary at the end of a run (core::TimeLoop::finish).
#pragma once

#include "afemp/run.hpp"
#include "core/scene.hpp"

namespace afemp::core {

class Model;

// Sets summary.taylor and summary.taylor_error (the first flat-ended cylinder body, when the
// scene states a Taylor reference) and appends summary.checks in the scene's order, from the
// model's final state and summary.final and summary.max_energy_error.
void check_references(const Model& model, const Scene& scene, RunSummary& summary);

}  // namespace afemp::core
