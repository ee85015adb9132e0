// Tangent stiffness of the 8-node hexahedra (fem/hexahedron_stiffness.hpp). Row I of Bbar_g for
// node a, component j: the normal strains eps_ii take b_j delta_ij + (m_j - b_j) / 3 (b = grad N_a
// at g, m its element mean), the shear strains their usual b entries; the one-point element's B
// is the same with b = m. The hourglass stiffness reuses the explicit forms' own functions
// (fem/hourglass.hpp, fem/hourglass_assumed_strain.hpp) for k_h and for K_ASQBI's columns.
#include "fem/hexahedron_stiffness.hpp"

#include <stdexcept>

#include "fem/hourglass.hpp"
#include "fem/hourglass_assumed_strain.hpp"

namespace afemp::fem {

namespace {

// Engineering strains (xx, yy, zz, yz, xz, xy) per dof of the gradients b and their means m.
using StrainMatrix = double[6][24];

void fill_bbar(const std::array<core::Vec3, 8>& grad, const std::array<core::Vec3, 8>& mean,
               StrainMatrix& bbar) {
  for (auto& row : bbar)
    for (double& v : row) v = 0.0;
  for (int a = 0; a < 8; ++a) {
    const core::Vec3& b = grad[a];
    const core::Vec3& m = mean[a];
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
}

// k += weight Bbar^T d Bbar.
void add_btdb(const StrainMatrix& bbar, const core::VoigtMatrix& d, double weight, HexMatrix& k) {
  double db[6][24];  // weight D Bbar
  for (int r = 0; r < 6; ++r)
    for (int q = 0; q < 24; ++q) {
      double s = 0.0;
      for (int t = 0; t < 6; ++t) s += d[r][t] * bbar[t][q];
      db[r][q] = weight * s;
    }
  for (int p = 0; p < 24; ++p)
    for (int q = 0; q < 24; ++q) {
      double s = 0.0;
      for (int r = 0; r < 6; ++r) s += bbar[r][p] * db[r][q];
      k[24 * p + q] += s;
    }
}

// q_l,j = sum_a gamma_l,a u_a,j, index 3 l + j.
std::array<double, 12> hourglass_displacements(const HourglassStiffness& s, const HexVectors& u) {
  std::array<double, 12> q{};
  for (int l = 0; l < 4; ++l)
    for (int a = 0; a < 8; ++a)
      for (int j = 0; j < 3; ++j) q[3 * l + j] += s.gamma[l][a] * u[a][j];
  return q;
}

}  // namespace

core::SymTensor strain_bbar(const FullHex& e, int g, const HexVectors& u) {
  return core::sym_part(velocity_gradient_bbar(e, g, u));
}

void hexahedron_stiffness_bbar(const FullHex& e, const std::array<core::VoigtMatrix, 8>& d,
                               HexMatrix& k) {
  k.fill(0.0);
  for (int g = 0; g < 8; ++g) {
    StrainMatrix bbar;
    fill_bbar(e.grad[g], e.mean_grad, bbar);
    add_btdb(bbar, d[g], e.weight[g], k);
  }
}

core::SymTensor strain_one_point(const OnePointHex& e, const HexVectors& u) {
  return core::sym_part(velocity_gradient(e, u));
}

void hexahedron_stiffness_one_point(const OnePointHex& e, const core::VoigtMatrix& d,
                                    HexMatrix& k) {
  std::array<core::Vec3, 8> b;
  for (int a = 0; a < 8; ++a) b[a] = (1.0 / e.volume) * e.b[a];
  StrainMatrix bmat;
  fill_bbar(b, b, bmat);
  k.fill(0.0);
  add_btdb(bmat, d, e.volume, k);
}

HourglassStiffness hourglass_stiffness(const HexVectors& x, const OnePointHex& e,
                                       const core::Material& material,
                                       const core::HourglassSettings& settings) {
  const HourglassModes modes = hourglass_modes(e, x);
  HourglassStiffness s;
  s.gamma = modes.gamma;
  const double coefficient = settings.effective_coefficient();
  switch (settings.form) {
    case core::HourglassForm::viscous:
      throw std::invalid_argument(
          "hourglass_stiffness: the viscous hourglass form resists only rates: it has no "
          "stiffness");
    case core::HourglassForm::stiffness: {
      const double modulus = material.bulk_modulus() + 4.0 / 3.0 * material.shear_modulus();
      const double k_h =
          stiffness_hourglass_factor(coefficient, modulus, modes.b_squared, e.volume);
      for (int p = 0; p < 12; ++p) s.h[13 * p] = k_h;
      break;
    }
    case core::HourglassForm::assumed_strain: {
      // Column 3 l + j: the generalised forces of one step of length 1 from rest with the unit
      // hourglass velocity q_l = e_j.
      const AssumedStrainGeometry geometry = assumed_strain_geometry(x);
      for (int l = 0; l < 4; ++l)
        for (int j = 0; j < 3; ++j) {
          std::array<core::Vec3, 4> q{}, g{};
          q[l][j] = 1.0;
          HourglassComponents stress{};
          assumed_strain_hourglass_forces(geometry, e.volume,
                                          coefficient * material.shear_modulus(),
                                          material.poisson_ratio, 1.0, q, stress, g);
          for (int k = 0; k < 4; ++k)
            for (int i = 0; i < 3; ++i) s.h[12 * (3 * k + i) + 3 * l + j] = g[k][i];
        }
      break;
    }
  }
  return s;
}

std::array<core::Vec3, 4> hourglass_generalised_forces(const HourglassStiffness& s,
                                                       const HexVectors& u) {
  const std::array<double, 12> q = hourglass_displacements(s, u);
  std::array<core::Vec3, 4> g{};
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i)
      for (int p = 0; p < 12; ++p) g[k][i] += s.h[12 * (3 * k + i) + p] * q[p];
  return g;
}

void add_hourglass_forces(const HourglassStiffness& s, const HexVectors& u, HexVectors& f) {
  const std::array<core::Vec3, 4> g = hourglass_generalised_forces(s, u);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 8; ++a) f[a][i] -= s.gamma[k][a] * g[k][i];
}

void add_hourglass_stiffness_matrix(const HourglassStiffness& s, HexMatrix& k) {
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int m = 0; m < 4; ++m)
        for (int l = 0; l < 4; ++l) {
          const double gg = s.gamma[m][a] * s.gamma[l][b];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              k[24 * (3 * a + i) + 3 * b + j] += gg * s.h[12 * (3 * m + i) + 3 * l + j];
        }
}

double hourglass_energy(const HourglassStiffness& s, const HexVectors& u) {
  const std::array<double, 12> q = hourglass_displacements(s, u);
  double energy = 0.0;
  for (int p = 0; p < 12; ++p)
    for (int r = 0; r < 12; ++r) energy += 0.5 * q[p] * s.h[12 * p + r] * q[r];
  return energy;
}

}  // namespace afemp::fem
