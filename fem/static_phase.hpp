// A scene's static or implicit phase (core/phases.hpp) on the FE solver: the mesh bodies it
// solves taken out of the solver as a fem::StaticProblem (their nodes where they are, their
// hexahedra and trusses with their points' stresses and plastic strains, the gravity of their
// lumped masses, the constraints' fixed components and the displacements their imposed
// velocities give over the phase), solved by fem::solve_static or fem::solve_newmark, and the
// result handed to the explicit solver as its state at the phase's end: positions x = x_start
// + u, the points' stresses, plastic strains and internal energies, the hourglass forms' forces,
// the element forces (and an implicit phase's velocities), and the loads' work as external
// work, so that the energy balance spans the phases.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "afemp/scene.hpp"
#include "fem/fe_solver.hpp"
#include "fem/static_solve.hpp"

namespace afemp::fem {

// Where the static problem's entries sit in the solver: per problem node, hexahedron, line and
// wall, the solver's node, hexahedron, truss and [[walls]] entry; per node, its position at the
// phase's start (the problem's reference).
struct StaticPhaseMap {
  std::vector<std::int32_t> nodes, hexahedra, trusses, walls;
  std::vector<core::Vec3> start;
};

// What a static or implicit phase reports.
struct ImplicitPhaseOutcome {
  // Implicit: the work done on the solved bodies that neither their stresses (elastic and
  // plastic work) nor their motion (the explicit solver's lumped kinetic energy) hold: HHT's
  // numerical damping, the nodes that stopped on walls, and the consistent mass's kinetic
  // energy against the lumped one's at the end. Static after another phase: the kinetic energy
  // taken out and what the loads' work does not leave in the stresses (0 for a first phase).
  double dissipated = 0.0;
  std::vector<NewtonIteration> iterations;  // load_step is the time step
  std::vector<NewmarkState> states;         // times from the phase's start
};

// Solves the phase from the solver's state now (the bodies where they are, their points'
// stresses and plastic strains: the virgin meshes for a first phase, an explicit phase's end
// for a later one) and hands its state to the solver, whose clock then reads phase.end_time.
// After an explicit phase the solved bodies are put at rest (their kinetic energy is the
// outcome's dissipated); a first phase keeps their initial velocities. Each Newton iteration is
// printed to `log` when set. Throws core::InputError (at the phase's entry) for what the solve
// cannot take, and core::SimulationError when the equilibrium cannot be found (a body its
// constraints leave free, named with its free modes; Newton that does not converge, with the
// load step, the iteration and the residual), after which `failed` holds the Newton iterations
// of the solve, the failing step's included.
ImplicitPhaseOutcome run_static_phase(FeSolver& solver, const core::Scene& scene,
                                      const core::PhaseSpec& phase, std::ostream* log,
                                      std::vector<NewtonIteration>& failed);

// An implicit phase (kind "implicit": Newmark's trapezoidal rule, or HHT-alpha with the
// phase's alpha) on the same problem, from the solver's state at the phase's start (as the
// static phase's, with the velocities the solved bodies have then: their initial velocities in a
// first phase), in equal steps no longer than the phase's time_step; the constraints'
// components move by their velocities' travel. The state at the end is handed to the solver as
// the static phase's is, with the velocities; the external work is what the loads and the
// constraints did over the phase.
// Throws as run_static_phase (a time step that does not converge leaves the state after the last
// converged one as the solver's, and its iterations in `failed`).
ImplicitPhaseOutcome run_implicit_phase(FeSolver& solver, const core::Scene& scene,
                                        const core::PhaseSpec& phase, std::ostream* log,
                                        std::vector<NewtonIteration>& failed);

}  // namespace afemp::fem
