// Programmed burn of high explosives (afemp/material.hpp ProgrammedBurn; LS-DYNA
// *MAT_HIGH_EXPLOSIVE_BURN, Keyword Manual vol. II; the beta burn of M. L. Wilkins, "The use of
// one- and two-dimensional hydrodynamic machine calculations in high explosive research",
// UCRL-51213, 1969): the time each point lights, and its burn fraction at a time.
#pragma once

#include <span>

#include "afemp/material.hpp"
#include "afemp/scene.hpp"

namespace afemp::core {

// The detonation's point nearest to x: the point itself, x's foot on the plane, or the
// segment's point nearest to x.
Vec3 nearest_point(const DetonationSpec& d, const Vec3& x);

// min over the detonations without `shadow` of (time + distance from x / D); +inf without
// such detonations. Shadowed detonations take a path around inert bodies instead
// (core/detonation_paths.hpp).
double lighting_time(const Vec3& x, std::span<const DetonationSpec> detonations, double D);

// The burn fraction at time t of a point that lit at t_light, had `previous`, measures `length`
// (the element's volume over its largest face; for particles the grid cell) and is at relative
// volume V = rho0 / rho: min(1, max(previous, F1, F2)) with F1 = 2 (t - t_light) D / (3 length)
// after lighting and F2 = (1 - V) / (1 - V_CJ), each when the burn has it on.
double burn_fraction(const ProgrammedBurn& burn, double rho0, double previous, double t,
                     double t_light, double length, double V);

}  // namespace afemp::core
