// Adaptive conversion of hexahedra into particles (AFEMP): what replaces an element the FE
// solver retired (fem/element_retirement.cpp). See element_conversion.cpp.
#pragma once

#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/particles.hpp"

namespace afemp::coupling {

// The record of one converted element: how many particles it made and the energies.
struct Conversion {
  int particles = 0;
  // Kinetic energy of the element's node-mass shares, and of its particles.
  double kinetic_before = 0.0, kinetic_after = 0.0;
  // Kinetic plus internal energy the interpolation lost (booked as Energies::converted).
  double lost_energy = 0.0;
};

// Appends to `out` the particles of retired element `retired`, made from its integration points
// and its nodes' current state (call it after the step that retired it: the grid sets bonded
// nodes' velocity after the element update). `out` has the hexahedra's history count and keeps
// the strain where they do.
Conversion convert_element(const fem::FeSolver& fe, const core::Scene& scene,
                           const fem::RetiredElement& retired, mpm::Particles& out);

}  // namespace afemp::coupling
