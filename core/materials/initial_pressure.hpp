// A body that starts at a pressure (water at depth, a pre-stressed fluid): the density at which
// the material's equation of state gives that pressure at the body's initial specific internal
// energy, so that the state is in equilibrium with its own EOS from the first step. The EOS are
// linear in e at fixed density (p = a(mu) + b(mu) e, equations_of_state.hpp), and a(mu) + b e
// rises with compression, so mu is found by bisection on [-0.5, 1] (below zero where the
// internal energy alone gives more than p).
#pragma once

#include <optional>
#include <string>

#include "afemp/material.hpp"

namespace afemp::core {

/// The relative compression mu = rho / rho0 - 1 at which the material's EOS gives pressure p
/// at specific internal energy e; 0 for a material without an EOS (the hypoelastic law then
/// starts from the stress -p I at rho0). Empty when the material cannot start at a pressure:
/// the Holmquist-Johnson-Cook compaction law (its unloading depends on the history), an
/// explosive (its products' state comes from the burn), or an EOS that does not reach p
/// before mu = 1 (twice the reference density).
std::optional<double> compression_at_pressure(const Material& material, double p, double e);

/// Why the material cannot start at pressure p at energy e, with what is allowed (the message
/// of the parser, the scene check and particle generation alike); empty when it can.
std::optional<std::string> initial_pressure_refusal(const Material& material, double p, double e);

}  // namespace afemp::core
