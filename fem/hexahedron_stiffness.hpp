// Small-strain tangent stiffness of the fully integrated hexahedron with B-bar dilatation
// (Hughes, IJNME 15 (1980) 1413-1418; Hughes 2000, sec. 4.5.2): K = sum_g w_g Bbar_g^T D_g
// Bbar_g over the 2x2x2 Gauss points of fem/hexahedron_full.hpp, whose gradients it uses, so
// that it is the derivative of the nodal forces add_stress_forces_bbar gives.
#pragma once

#include <array>

#include "afemp/tensor.hpp"
#include "core/materials/small_strain_tangent.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/sparse_assembly.hpp"

namespace afemp::fem {

// The B-bar small strain at point g of the nodal displacements u: the symmetric part of
// velocity_gradient_bbar applied to u.
core::SymTensor strain_bbar(const FullHex& e, int g, const HexVectors& u);

// k = sum_g w_g Bbar_g^T d[g] Bbar_g (d in Voigt order with engineering shear strains,
// core::VoigtMatrix), dof 3 a + i for component i of node a.
void hexahedron_stiffness_bbar(const FullHex& e, const std::array<core::VoigtMatrix, 8>& d,
                               HexMatrix& k);

}  // namespace afemp::fem
