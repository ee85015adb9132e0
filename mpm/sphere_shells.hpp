// Particles of a sphere that follow its surface (`layout = "shells"`). A lattice sphere is a
// staircase: its lowest layer is a flat disc of radius about sqrt(R s), wider than a low-speed
// Hertz contact, so the sphere lands as a flat punch (at 20 cells per radius and 10 m/s, -42 %
// of Hertz's contact time and +49 % of its peak force on a rigid wall). Here concentric shells
// of equal thickness t = R / round(R / s) are each cut by an equal-angle cubed-sphere grid
// (Ronchi, Iacono & Paolucci 1996, "The cubed sphere", J. Comput. Phys. 124)
// of N x N cells per cube face, N the even number nearest (pi / 2) r_mid / s, so that every cell
// is about s wide; one particle per cell, at the cell's centroid, with the cell's exact volume.
// The shells need not match: particles need no conforming mesh. N even makes the coordinate
// planes through the centre cell boundaries, so a quarter or half model is exact.
#pragma once

#include <vector>

#include "afemp/scene.hpp"

namespace afemp::mpm {

struct ShellParticle {
  Vec3 position;
  double volume = 0.0;
};

// The particles of `sphere` at spacing s (volumes sum to 4/3 pi R^3 to round-off).
std::vector<ShellParticle> sphere_shell_particles(const SphereShape& sphere, double s);

}  // namespace afemp::mpm
