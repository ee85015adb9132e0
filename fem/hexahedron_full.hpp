// Fully integrated 8-node hexahedron (2x2x2 Gauss) with the selective-reduced B-bar treatment of
// the dilatation of Hughes, "Generalization of selective integration procedures to anisotropic
// and nonlinear media", IJNME 15 (1980) 1413-1418: at every Gauss point the volumetric part of
// the velocity gradient is replaced by its element mean, which removes volumetric locking.
#pragma once

#include <array>

#include "afemp/tensor.hpp"
#include "fem/hexahedron.hpp"

namespace afemp::fem {

// Gauss point g sits at kHexNatural[g] / sqrt(3), the point nearest node g.
struct FullHex {
  std::array<double, 8> weight;                   // det J at point g times its Gauss weight (1)
  std::array<std::array<core::Vec3, 8>, 8> grad;  // grad[g][a] = grad N_a at point g
  std::array<core::Vec3, 8> mean_grad;            // (1/V) integral of grad N_a dV
  double volume = 0.0;                            // sum of the weights: exact trilinear volume
};

// Throws nothing: where det J <= 0 (a tangled element) the gradients are meaningless, so the
// caller checks min_jacobian(e) > 0 first.
FullHex full_hex(const HexVectors& x);

// Smallest det J over the eight Gauss points (equal to the smallest weight).
double min_jacobian(const FullHex& e);

// L_bar = L_g - (tr L_g / 3) I + (tr L_mean / 3) I at point g, L_ij = dv_i/dx_j
// (m[i][j]); L_mean is the element mean of L.
core::Mat3 velocity_gradient_bbar(const FullHex& e, int g, const HexVectors& v);

// Adds the nodal forces (external minus internal) of the Gauss-point stresses, consistent with
// velocity_gradient_bbar: sum_g w_g sigma_g : sym(L_bar_g) = -sum_a f_a . v_a for every v. The
// deviatoric stress acts through each point's gradient, the weighted mean pressure through the
// element mean gradient.
void add_stress_forces_bbar(const FullHex& e, const std::array<core::SymTensor, 8>& sigma,
                            HexVectors& f);

}  // namespace afemp::fem
