// The Holmquist-Johnson-Cook concrete model's point-wise update and its own history: the
// largest compaction mu_max reached, which the compaction law's unloading reads (Holmquist,
// Johnson & Cook 1993; holmquist_johnson_cook.cpp, hjc_compaction.cpp).
#pragma once

#include <cstddef>

#include "core/materials/material.hpp"

namespace afemp::core {

// PointState::history slot of the largest volumetric strain mu = rho / rho0 - 1 reached.
inline constexpr std::size_t kMaxCompaction = 0;

// Holmquist-Johnson-Cook update of one point: pressure from the compaction law with the tension
// cutoff -T (1 - D), deviator returned radially onto the yield surface at that pressure, damage
// from the plastic and crushing strain increments, and the same energy equation as
// constitutive_update (the pressure does not depend on e).
PointUpdate holmquist_johnson_cook_update(const Material& material,
                                          const HolmquistJohnsonCook& strength,
                                          const HjcCompaction& eos, PointState& point,
                                          const SymTensor& d_eps, double dt);

// rho dp/drho of the compaction law at the point's density and largest compaction.
inline double hjc_tangent_bulk_modulus(const HjcCompaction& eos, double mu,
                                       const PointState& point) {
  return eos.tangent_bulk_modulus(mu, point.history[kMaxCompaction]);
}

}  // namespace afemp::core
