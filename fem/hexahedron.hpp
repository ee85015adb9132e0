// Shared vocabulary of the 8-node hexahedron kernels (hexahedron_one_point, hourglass,
// hexahedron_full): one vector per node in the kHexNatural order of fem/mesh.hpp, and the six
// faces of the element. The kernels are pure functions of one element's nodal data.
#pragma once

#include <array>

#include "afemp/tensor.hpp"
#include "fem/mesh.hpp"

namespace afemp::fem {

// One vector per node (coordinates, velocities or forces), node a at kHexNatural[a].
using HexVectors = std::array<core::Vec3, 8>;

// The six faces zeta = -1, zeta = +1, eta = -1, xi = +1, eta = +1, xi = -1, each listed
// counter-clockwise seen from outside, so that (p1 - p0) x (p3 - p0) points outward on a
// well-formed element.
inline constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

}  // namespace afemp::fem
