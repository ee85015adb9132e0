// Artificial bulk viscosity of the particles: the von Neumann-Richtmyer quadratic term with
// Landshoff's linear one, in the form of LS-DYNA's solids (and afemp's hexahedra,
// fem/hexahedron_update.cpp), q = rho l (C_q l e'^2 - C_l c e') in compression (e' = tr D < 0)
// and 0 in expansion, added to the pressure in the internal force. In MPM the shock spreads
// over grid cells, whatever the particle spacing, so l is the cell h (as in Uintah's MPM).
// The q that acted over a step heats the particle by -q tr(d eps) / rho per unit mass (its
// work on the step's volume change), so the energy balance holds, and the stable step takes
// the signal speed Q + sqrt(Q^2 + c^2) with Q = C_l c + C_q l |e'| (LS-DYNA's).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/scene.hpp"

namespace afemp::mpm {

struct ViscousState {
  double q = 0.0;       // bulk-viscous pressure for the next step's force
  double signal = 0.0;  // signal speed for the stable step (c when q is off)
};

// rho: density, l: length, trace_rate: tr D, c: the material's wave speed.
inline ViscousState bulk_viscosity(const core::BulkViscositySettings& s, double rho, double l,
                                   double trace_rate, double c) {
  const double compression = std::max(-trace_rate, 0.0);
  ViscousState out;
  out.q = rho * l * compression * (s.quadratic * l * compression + s.linear * c);
  const double qv = s.linear * c + s.quadratic * l * compression;
  out.signal = qv + std::sqrt(qv * qv + c * c);
  return out;
}

// Specific heat of the q that acted over a step with strain increment trace d_vol.
inline double bulk_viscous_heat(double q_old, double d_vol, double rho) {
  return -q_old * d_vol / rho;
}

}  // namespace afemp::mpm
