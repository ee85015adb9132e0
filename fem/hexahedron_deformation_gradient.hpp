// The deformation gradient of a trilinear 8-node hexahedron, for the hyperelastic strength
// models (afemp/neo_hookean.hpp, afemp/mooney_rivlin.hpp) on elements: F = dx/dX at a natural
// point, from the nodes' current and initial positions, so it is exact for every homogeneous
// deformation and has no rate to integrate; and its F-bar form for the fully integrated
// element, F_bar = (J_bar / det F)^(1/3) F with J_bar the element's volume ratio (de Souza
// Neto, Peric, Dutko & Owen 1996, eq. 3.3): the finite-strain counterpart of the B-bar
// dilatation (fem/hexahedron_full.hpp), so the element stays free of volumetric locking.
#pragma once

#include "afemp/tensor.hpp"
#include "fem/hexahedron.hpp"

namespace afemp::fem {

// F = (dx/dxi)(dX/dxi)^(-1) at natural point (xi, eta, zeta) of the element with current nodes
// x and initial nodes x0 (node a at kHexNatural[a]). Both Jacobians must be positive there.
core::Mat3 hexahedron_deformation_gradient(const HexVectors& x, const HexVectors& x0, double xi,
                                           double eta, double zeta);

// F scaled so that its determinant is j_bar: F (j_bar / det F)^(1/3).
core::Mat3 f_bar(const core::Mat3& f, double j_bar);

}  // namespace afemp::fem
