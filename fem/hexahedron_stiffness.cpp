// B-bar tangent stiffness of the 8-node hexahedron (fem/hexahedron_stiffness.hpp). Row I of
// Bbar_g for node a, component j: the normal strains eps_ii take b_j delta_ij + (m_j - b_j) / 3
// (b = grad N_a at g, m its element mean), the shear strains their usual b entries.
#include "fem/hexahedron_stiffness.hpp"

namespace afemp::fem {

core::SymTensor strain_bbar(const FullHex& e, int g, const HexVectors& u) {
  return core::sym_part(velocity_gradient_bbar(e, g, u));
}

void hexahedron_stiffness_bbar(const FullHex& e, const std::array<core::VoigtMatrix, 8>& d,
                               HexMatrix& k) {
  k.fill(0.0);
  for (int g = 0; g < 8; ++g) {
    double bbar[6][24] = {};  // engineering strains (xx, yy, zz, yz, xz, xy) per dof
    for (int a = 0; a < 8; ++a) {
      const core::Vec3& b = e.grad[g][a];
      const core::Vec3& m = e.mean_grad[a];
      for (int j = 0; j < 3; ++j) {
        const double dilatation = (m[j] - b[j]) / 3.0;
        for (int i = 0; i < 3; ++i) bbar[i][3 * a + j] = dilatation;
        bbar[j][3 * a + j] += b[j];
      }
      bbar[3][3 * a + 1] = b.z;  // gamma_yz = du_y/dz + du_z/dy
      bbar[3][3 * a + 2] = b.y;
      bbar[4][3 * a + 0] = b.z;  // gamma_xz
      bbar[4][3 * a + 2] = b.x;
      bbar[5][3 * a + 0] = b.y;  // gamma_xy
      bbar[5][3 * a + 1] = b.x;
    }
    double db[6][24];  // w_g D_g Bbar_g
    for (int r = 0; r < 6; ++r)
      for (int q = 0; q < 24; ++q) {
        double s = 0.0;
        for (int t = 0; t < 6; ++t) s += d[g][r][t] * bbar[t][q];
        db[r][q] = e.weight[g] * s;
      }
    for (int p = 0; p < 24; ++p)
      for (int q = 0; q < 24; ++q) {
        double s = 0.0;
        for (int r = 0; r < 6; ++r) s += bbar[r][p] * db[r][q];
        k[24 * p + q] += s;
      }
  }
}

}  // namespace afemp::fem
