// A body that starts at a pressure (water at depth, a pre-stressed fluid): the density at which
// the material's equation of state gives that pressure at the body's initial specific internal
// energy, so that the state is in equilibrium with its own EOS from the first step. The EOS are
// linear in e at fixed density (p = a(mu) + b(mu) e, equations_of_state.hpp), and a(mu) + b e
// rises with compression, so mu is found by bisection on [-0.5, 1] (below zero where the
// internal energy alone gives more than p). And a body at rest under gravity: its geostatic
// stress, vertical -rho g depth and horizontal K0 times that (Terzaghi's earth pressure at rest).
#pragma once

#include <optional>
#include <string>

#include "afemp/material.hpp"
#include "afemp/tensor.hpp"

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

/// The geostatic stress at x in a body of density rho under gravity g (|g| > 0) whose free
/// surface lies at height `surface` along up = -g / |g|: at depth d = max(surface - x . up, 0),
/// sigma = sigma_v (up up + K0 (I - up up)), sigma_v = -rho |g| d (compression negative). The
/// weight of the material above a point is then carried by the vertical stress, and a laterally
/// confined column is in equilibrium at any K0; K0 = nu / (1 - nu) is the elastic one (the
/// state gravity loading builds), 1 - sin(phi) Jaky's (1944) for a normally consolidated soil.
SymTensor geostatic_stress(double surface, double k0, const Vec3& gravity, double density,
                           const Vec3& x);

/// The elastic energy per unit mass the linear elastic law stores in a stress,
/// (s : s / 4G + sigma_m^2 / 2K) / rho0: what a body that starts stressed holds, so that its
/// internal energy less the plastic work stays the elastic energy as it unloads.
double elastic_energy(const Material& material, const SymTensor& stress);

/// Why a body of the material cannot start at a geostatic stress under gravity g (with an
/// initial pressure too when `pressure`), with what is allowed; empty when it can.
std::optional<std::string> geostatic_stress_refusal(const Material& material, const Vec3& gravity,
                                                    bool pressure);

}  // namespace afemp::core
