// Adaptive conversion of hexahedra into particles (AFEMP): what replaces an element the FE
// solver retired (fem/element_retirement.cpp). See element_conversion.cpp.
#pragma once

#include <vector>

#include "afemp/tensor.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::coupling {

// A particle made from a retired hexahedron: at an integration point of the element, with its
// share of the mass and the point's state.
struct ConvertedPoint {
  core::Vec3 position, velocity;  // x^{n+1}; v^{n+1/2} interpolated from the nodes
  double mass = 0.0, volume = 0.0;
  core::SymTensor stress;
  double plastic_strain = 0.0, temperature = 0.0, energy = 0.0;  // energy: per unit mass
  double damage = 0.0;
  // The accumulated strain, where the element integrates it (principal-strain failure reads
  // it: the particle carries on from its element's, not from zero); zero otherwise.
  core::SymTensor strain;
  std::vector<double> history;  // the strength model's history variables
  int body = 0, material = 0;
};

// The particles of one element and its record.
struct Conversion {
  std::vector<ConvertedPoint> points;
  int particles = 0;
  // Kinetic energy of the element's node-mass shares, and of its particles.
  double kinetic_before = 0.0, kinetic_after = 0.0;
  // Kinetic plus internal energy the interpolation lost (booked as Energies::converted).
  double lost_energy = 0.0;
};

// Makes the particles of retired element `retired` from its integration points and its nodes'
// current state (call it after the step that retired it: the grid sets bonded nodes' velocity
// after the element update).
Conversion convert_element(const fem::FeSolver& fe, const core::Scene& scene,
                           const fem::RetiredElement& retired);

}  // namespace afemp::coupling
