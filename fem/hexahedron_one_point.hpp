// One-point (uniform-gradient) 8-node hexahedron of Flanagan & Belytschko, "A uniform strain
// hexahedron and quadrilateral with orthogonal hourglass control", IJNME 17 (1981) 679-706:
// the B vectors b_a = integral of grad N_a over the element = dV/dx_a, the exact trilinear
// volume, the mean velocity gradient and the nodal forces of a uniform stress.
#pragma once

#include <array>

#include "afemp/tensor.hpp"
#include "fem/hexahedron.hpp"

namespace afemp::fem {

struct OnePointHex {
  double volume = 0.0;          // exact volume of the trilinear element
  std::array<core::Vec3, 8> b;  // b_a = integral over the element of grad N_a dV
};

// FB's closed form of b_a = dV/dx_a (a cubic in the coordinates, exact for any trilinear
// element), evaluated relative to the centroid so that elements far from the origin keep their
// precision; the volume follows from linear completeness, V = sum_a b_a,x x_a. A tangled element
// gives volume <= 0, which the caller checks.
OnePointHex one_point_hex(const HexVectors& x);

// Mean velocity gradient L_ij = (1/V) sum_a v_a,i b_a,j (m[i][j] = dv_i/dx_j); exact for any
// linear velocity field on any (distorted) element.
core::Mat3 velocity_gradient(const OnePointHex& e, const HexVectors& v);

// Adds the nodal forces of a uniform Cauchy stress, f_a,i -= sigma_ij b_a,j (f is external minus
// internal, so this is minus the internal force). Their power is -sum_a f_a . v_a = V sigma : D.
void add_stress_forces(const OnePointHex& e, const core::SymTensor& sigma, HexVectors& f);

// Length for the time step, L = V / (largest face area), as LS-DYNA's default for solids (a box
// gives its shortest edge). A warped face's area is taken as the mean over its two diagonal
// splits of the two triangles' areas; each split is at least the norm of the face's vector area
// 0.5 |d1 x d2|, so warping shortens L (a conservative time step), and for a planar convex face
// all three agree.
double characteristic_length(const HexVectors& x, double volume);

}  // namespace afemp::fem
