// The [[phases]] of a scene (afemp/scene.hpp, PhaseSpec): which sequences afemp runs, the mesh
// bodies a static phase solves, and the plan `afemp check` prints for each phase.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "afemp/scene.hpp"

namespace afemp::core {

// When phase k starts: the end of the phase before, or 0.
double phase_start(const Scene& scene, std::size_t k);

// The static, implicit or relaxation phase that starts at time t (the run has reached it and
// not yet run it: each ends after it starts), or nullptr.
const PhaseSpec* phase_due(const Scene& scene, double t);

// An implicit phase's time steps over `span`: the fewest equal steps no longer than its
// time_step.
int implicit_steps(const PhaseSpec& phase, double span);

// When the next static or implicit phase after time t starts (the explicit steps stop there),
// or +infinity.
double next_phase_start(const Scene& scene, double t);

// How long the explicit phases last together: [run] end_time without phases.
double explicit_span(const Scene& scene);

// Whether the history has a `damped` column: a relaxation or implicit phase, or a static phase
// after an explicit one (which puts the bodies it solves at rest).
bool books_damped_energy(const Scene& scene);

// When phase k ends: its end_time, or for the last phase left at 0, [run] end_time.
double phase_end(const Scene& scene, std::size_t k);

// The phase's tolerance: its own, or its kind's default (static and implicit 1e-8, relaxation
// 1e-3).
double phase_tolerance(const PhaseSpec& phase);

// The bodies a relaxation phase holds at rest and sets moving at its end: those with an
// initial velocity.
std::vector<int> moving_bodies(const Scene& scene);

// The bodies a static or implicit phase solves: its own list, or every deformable mesh body not
// bonded to particles.
std::vector<int> static_phase_bodies(const Scene& scene, const PhaseSpec& phase);

// Checks the phases against the sequences afemp runs and the bodies they name; calls fail
// (which must throw) with the entry's location, its dotted key ("phases[0].bodies") and what is
// allowed. The parser and check_scene share it.
using PhaseFailure =
    std::function<void(const SourceLocation&, const std::string&, const std::string&)>;
void check_phases(const Scene& scene, const PhaseFailure& fail);

// One paragraph per phase for `afemp check`: its kind, its clock, what it solves and holds,
// its loads, and what it leaves out (a static phase: contacts, erosion, particles). Empty for
// a scene without phases.
std::string describe_phases(const Scene& scene);

}  // namespace afemp::core
