// How far an explosive drives a ring before it reaches the axis: a one-dimensional cylindrical
// Lagrangian hydrocode (von Neumann & Richtmyer 1950, J. Appl. Phys. 21, the artificial
// viscosity; Wilkins 1964, "Calculation of elastic-plastic flow", Methods in Computational
// Physics 3, the staggered Lagrangian scheme) for one slice of an axisymmetric charge normal to
// its axis. It shares no code with the solvers: it is an independent check of the drive that
// the shaped charge's PER estimate (analysis/shaped_charge_per.hpp) assumes, each liner
// element at its terminal Gurney velocity when it meets the axis (docs/explosives.md, "What the
// explosive gives on the way to the axis").
//
// Rings of material between radii, each a Mie-Grueneisen solid (pressure only: at the
// collapse's tens of GPa the liner's strength is left out, as PER leaves it out) or JWL
// products lit by programmed burn (each zone lit at its lighting time, its pressure scaled by
// a burn fraction that rises over six zones' widths of the detonation's travel; Wilkins 1964).
// Units: those of the numbers given (mm, ms, g, MPa: velocities in m/s, energies in J/kg).
#pragma once

#include <functional>
#include <vector>

#include "analysis/shaped_charge_per.hpp"

namespace afemp::analysis {

struct Ring1d {
  enum class Kind { mie_gruneisen, jwl };
  Kind kind = Kind::mie_gruneisen;
  double inner = 0.0;  // radius
  double outer = 0.0;
  double density = 0.0;
  // Mie-Grueneisen about the Hugoniot Us = c0 + s up, Gamma rho = gamma0 rho0.
  double c0 = 0.0;
  double s = 0.0;
  double gamma0 = 0.0;
  // JWL: p = A (1 - omega / (R1 V)) e^(-R1 V) + B (1 - omega / (R2 V)) e^(-R2 V) + omega rho e,
  // V = rho0 / rho, the products starting at e = E0 / rho0 (E0 per unit initial volume).
  double A = 0.0;
  double B = 0.0;
  double R1 = 0.0;
  double R2 = 0.0;
  double omega = 0.0;
  double E0 = 0.0;
  double detonation_velocity = 0.0;
};

struct Drive1dSettings {
  double zones_per_length = 10.0;  // zones per unit of radius, in every ring
  double courant = 0.1;            // the step over the smallest zone's crossing time
  double end_time = 0.0;
  // The drive ends when the driven ring's inner surface comes within this of the axis, or its
  // outer surface reaches `stop_outer_radius` (0: never), or at end_time.
  double stop_inner_radius = 0.0;
  double stop_outer_radius = 0.0;
  // Each explosive zone's lighting time from its mid-radius.
  std::function<double(double)> lighting_time;
};

struct Drive1dSample {
  double time = 0.0;
  double mean_velocity = 0.0;  // the driven ring's mass-weighted radial velocity
  double inner_radius = 0.0;   // its inner surface
  double outer_radius = 0.0;   // its outer surface
};

struct Drive1dResult {
  std::vector<Drive1dSample> history;  // every step
  // Kinetic plus internal energy over the explosive's chemical energy (E0 times its volume),
  // at the end: 1 when the scheme keeps energy.
  double energy_ratio = 0.0;
};

// Rings in order of radius, touching; `driven` the index of the ring whose motion is
// recorded. Per radian and per unit length of the axis.
Drive1dResult cylindrical_drive_1d(const std::vector<Ring1d>& rings, int driven,
                                   const Drive1dSettings& settings);

// One slice of a conical charge (analysis/shaped_charge_per.hpp) at height z: its liner ring
// (`liner`'s material), the explosive ring around it out to the charge's radius and the case
// ring, lit by the spherical detonation from the charge's lighting point (each zone at its
// distance from it over D). The radii are the slice's; the rings' materials are taken as given.
// The liner is driven until its inner surface comes within 1 % of the wall of the axis.
struct SliceDrive {
  LinerElement element;           // the PER estimate's element at this z
  double largest_velocity = 0.0;  // the liner ring's largest mean inward velocity
  double largest_at = 0.0;        // and when
  double axis_velocity = 0.0;     // its mean inward velocity when its inner surface meets the axis
  double axis_time = 0.0;
  bool reached_axis = false;
  PerCollapse jet{};  // PER's steady collapse with the largest velocity instead of Gurney's
};
SliceDrive liner_slice_drive(const ConicalCharge& charge, const Ring1d& explosive,
                             const Ring1d& liner, const Ring1d& casing, double z,
                             double zones_per_length);

}  // namespace afemp::analysis
