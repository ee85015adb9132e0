// The energy account every solver reports and the balance the time loop checks: kinetic,
// internal (elastic + plastic + EOS work, bulk-viscous heating and assumed-strain stabilisation
// included), hourglass, what
// erosion removed, and the work of external loads.
#pragma once

#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::core {

/// Mass, momentum and energies of one body (one entry per scene body in Energies::bodies).
struct BodySums {
  double mass = 0.0;
  Vec3 momentum{};
  double kinetic = 0.0;
  double internal = 0.0;  ///< sum m e of the body's points (elements, particles)
};

/// The energy account of a model at one instant; the time loop checks its balance.
struct Energies {
  double kinetic = 0.0;
  double internal = 0.0;   ///< sum m e (elastic + plastic + EOS work + bulk-viscous heating)
  double plastic = 0.0;    ///< accumulated plastic work (part of internal)
  double viscous = 0.0;    ///< accumulated bulk-viscous work (part of internal)
  double hourglass = 0.0;  ///< accumulated hourglass work (stored or dissipated)
  /// Strain energy of the assumed-strain hourglass stabilisation (the linear strain field of a
  /// one-point hexahedron under Hooke's law, fem/hourglass_assumed_strain.hpp): physical elastic
  /// energy, so part of internal, and reported on its own as well.
  double stabilisation = 0.0;
  double eroded = 0.0;  ///< internal + kinetic energy taken away by eroded elements
  /// Energy lost when hexahedra became particles (AFEMP, coupling/element_conversion.cpp): the
  /// kinetic energy of the nodes' mass shares less that of the particles, whose velocities are
  /// interpolated from the nodes (never negative), plus any internal energy the particles' equal
  /// mass shares change (fully integrated elements only).
  double converted = 0.0;
  double external_work = 0.0;  ///< accumulated work of body forces and moving boundaries
  /// Energy the grid contact dissipated (normal stops and friction; mpm/grid_contact.cpp),
  /// estimated from the work of its impulses on the interface. An estimate, not part of
  /// total(): in the head-on test it is 1.2 to 2.7 times the energy the bodies actually lose,
  /// so a contact run's balance error includes what the contact dissipated.
  double contact = 0.0;
  /// Penalty contacts between meshes (fem/mesh_contact.cpp): minus the work their forces did
  /// on the nodes, i.e. the energy held in the contact springs plus what friction dissipated
  /// (LS-DYNA's sliding interface energy). Exact, part of total().
  double sliding = 0.0;
  double friction = 0.0;  ///< the part of sliding friction dissipated
  /// What the kinematic rigid walls took from the motion of mesh nodes (fem/rigid_wall.cpp):
  /// minus the work of their impulses, plus the external work of a moving wall. Part of total().
  double wall = 0.0;
  /// What particles carried out of the grid through outflow faces (mpm/outflow.cpp): their
  /// kinetic + internal energy (part of total()), mass and momentum, summed at the step they
  /// left. The bodies' sums no longer hold them.
  double outflow = 0.0;
  double outflow_mass = 0.0;
  /// The kinetic energy a relaxation phase's damping took out of the motion (less what it gave
  /// back setting the held bodies moving; core/time_loop.cpp, run_relaxation), what an
  /// implicit phase's scheme dissipated, and what a static phase after another took out (the
  /// motion it stops and what its path to the equilibrium lost; fem/static_phase.hpp,
  /// ImplicitPhaseOutcome). Part of total().
  double damped = 0.0;
  Vec3 outflow_momentum{};
  std::vector<BodySums> bodies{};
  /// Everything that must equal the initial total plus the external work.
  double total() const {
    return kinetic + internal + hourglass + eroded + converted + outflow + sliding + wall + damped;
  }
};

/// Relative energy-balance error: (E - E0 - W_ext) / max(E0 + |W_ext|, max kinetic so far),
/// E = Energies::total(). The denominator is the energy the run has handled.
double energy_balance_error(const Energies& now, const Energies& initial, double max_kinetic);

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::BodySums;
using core::Energies;
}  // namespace afemp
