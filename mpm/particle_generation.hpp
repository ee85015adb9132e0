// Material points from a scene's bodies: a regular lattice aligned with the background grid
// (n points per cell per direction) clipped to each body's shape, or a user list of points.
// Every point gets its body's material, initial velocity, temperature and mass = rho * volume.
#pragma once

#include "core/scene.hpp"
#include "mpm/particles.hpp"

namespace afemp::mpm {

// Particles of every body of the scene, bodies in order; within a lattice body z-major, then
// y, then x; within a point-list body in file order. Throws core::InputError at the body's
// location when a body crosses a grid face that is not symmetric, when a point-list file is
// unreadable or malformed, or when a body ends up with no particle.
Particles generate_particles(const core::Scene& scene);

}  // namespace afemp::mpm
