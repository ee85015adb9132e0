// Artificial bulk viscosity, once for particles and hexahedra: the von Neumann-Richtmyer
// quadratic term with Landshoff's linear one in the form of LS-DYNA's solids (LS-DYNA Theory
// Manual, "Bulk viscosity"), q = rho l (C_q l e'^2 - C_l c e') in compression (e' = tr D < 0)
// and 0 in expansion, added to the pressure in the internal force. l is the element's
// characteristic length (fem/hexahedron_update.cpp) or, for particles, the grid cell h: in MPM
// the shock spreads over grid cells whatever the particle spacing (as in Uintah's MPM).
// The q that acted over a step heats the point by -q tr(d eps) / rho per unit mass (its work on
// the step's volume change), so the energy balance holds, and the stable step takes the signal
// speed Q + sqrt(Q^2 + c^2) with Q = C_l c + C_q l |e'| (LS-DYNA's): dt = l / signal.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/scene.hpp"

namespace afemp::core {

struct ViscousState {
  double q = 0.0;       // bulk-viscous pressure for the next step's force
  double signal = 0.0;  // signal speed for the stable step (c when q is off)
};

// rho: density, l: length, trace_rate: tr D, c: the material's wave speed.
inline ViscousState bulk_viscosity(const BulkViscositySettings& s, double rho, double l,
                                   double trace_rate, double c) {
  ViscousState out;
  out.q = trace_rate < 0.0
              ? rho * l * (s.quadratic * l * trace_rate * trace_rate - s.linear * c * trace_rate)
              : 0.0;
  const double qv = s.linear * c + s.quadratic * l * std::abs(std::min(trace_rate, 0.0));
  out.signal = qv + std::sqrt(qv * qv + c * c);
  return out;
}

// Specific heat of the q that acted over a step with strain increment trace d_vol.
inline double bulk_viscous_heat(double q_old, double d_vol, double rho) {
  return -q_old * d_vol / rho;
}

}  // namespace afemp::core
