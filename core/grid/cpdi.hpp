// Convected particle domain interpolation. Each particle's domain is a hexahedron with eight
// corners x_c that move with the material; the weight of node I is the linear hat N_I averaged
// over the domain, and its gradient the domain average of grad N_I. Both are taken with N_I
// replaced over the domain by its interpolant through the corner values (the trilinear map
// phi_c of the hexahedron's natural coordinates):
//
//   S_Ip      = sum_c w_c N_I(x_c),       w_c = (1/V_p) int phi_c dV
//   grad S_Ip = sum_c N_I(x_c) g_c,       g_c = (1/V_p) int grad phi_c dV
//                                             = (1/V_p) int_boundary phi_c n dA
//
// the last form being the divergence theorem the method is built on.
//
// CPDI1 (Sadeghirad, Brannon & Burghardt 2011, "A convected particle domain interpolation
// technique to extend applicability of the material point method for problems involving massive
// deformations", IJNME 2011; docs/references.md): the domain is a parallelepiped x_p + sum_k s_k
// r_k (s_k = -1 or 1) whose edge vectors 2 r_k follow the deformation gradient, r_k = F r_k^0. The
// map is affine, so w_c = 1/8 and g_c = J^-T s_c / 8 with J = [r_1 r_2 r_3]:
// J^-T s = (s_1 r_2 x r_3 + s_2 r_3 x r_1 + s_3 r_1 x r_2) / det J, the faces' area vectors.
//
// CPDI2 (Sadeghirad, Brannon & Guilkey 2013, "Second-order convected particle domain
// interpolation (CPDI2) with enrichment for weak discontinuities at material interfaces",
// IJNME 2013, quadrilaterals in 2-D; here their 3-D counterpart, the trilinear
// hexahedron): each corner is tracked, x_c += dt sum_I N_I(x_c) v_I, so the domain may take any
// hexahedral shape. w_c and g_c are integrals of polynomials of degree at most three per natural
// coordinate (phi_c times det J, and the cofactor of J times grad_xi phi_c), which 2 x 2 x 2
// Gauss points integrate exactly.
//
// Both weights are a partition of unity (sum_I S_Ip = 1, sum_I grad S_Ip = 0), reproduce linear
// fields (sum_I S_Ip x_I = sum_c w_c x_c, the domain's centroid; sum_I x_I (x) grad S_Ip = I),
// and so pass the constant-strain patch test and conserve linear momentum exactly.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "afemp/tensor.hpp"

namespace afemp::core {

// Corner c = a + 2 b + 4 k sits at natural coordinates s_c = (2a - 1, 2b - 1, 2k - 1), the
// order of the linear hat's nodes in a cell.
constexpr Vec3 cpdi_corner_sign(int c) {
  return {(c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0};
}

// A domain's corners with their weights w_c and gradient weights g_c; volume is V_p (or the
// smallest Gauss point's det J times 8 when that is not positive: an inverted domain).
struct CpdiDomain {
  std::array<Vec3, 8> x;
  std::array<double, 8> w;
  std::array<Vec3, 8> g;
  double volume = 0.0;
  bool inverted = false;
};

// CPDI1: the parallelepiped x_p + sum s_k r_k, r_k the columns of r.
inline CpdiDomain cpdi1_domain(const Vec3& xp, const Mat3& r) {
  const Vec3 r1{r.m[0][0], r.m[1][0], r.m[2][0]};
  const Vec3 r2{r.m[0][1], r.m[1][1], r.m[2][1]};
  const Vec3 r3{r.m[0][2], r.m[1][2], r.m[2][2]};
  const Vec3 a1 = cross(r2, r3), a2 = cross(r3, r1), a3 = cross(r1, r2);
  const double det = dot(r1, a1);
  CpdiDomain d;
  d.volume = 8.0 * det;
  d.inverted = !(det > 0.0);
  const double scale = d.inverted ? 0.0 : 0.125 / det;
  for (int c = 0; c < 8; ++c) {
    const Vec3 s = cpdi_corner_sign(c);
    const auto k = static_cast<std::size_t>(c);
    d.x[k] = xp + s.x * r1 + s.y * r2 + s.z * r3;
    d.w[k] = 0.125;
    d.g[k] = scale * (s.x * a1 + s.y * a2 + s.z * a3);
  }
  return d;
}

// CPDI2: the trilinear hexahedron through the eight corners x.
inline CpdiDomain cpdi2_domain(const std::array<Vec3, 8>& x) {
  CpdiDomain d;
  d.x = x;
  d.w = {};
  d.g = {};
  const double gp = 1.0 / std::sqrt(3.0);
  double smallest = std::numeric_limits<double>::infinity();
  for (int q = 0; q < 8; ++q) {
    const Vec3 xi = gp * cpdi_corner_sign(q);
    // phi_c and grad_xi phi_c at the Gauss point; J = sum_c x_c (x) grad_xi phi_c.
    std::array<double, 8> phi;
    std::array<Vec3, 8> dphi;
    Mat3 j;
    for (int c = 0; c < 8; ++c) {
      const Vec3 s = cpdi_corner_sign(c);
      const double fx = 1.0 + s.x * xi.x, fy = 1.0 + s.y * xi.y, fz = 1.0 + s.z * xi.z;
      const auto k = static_cast<std::size_t>(c);
      phi[k] = 0.125 * fx * fy * fz;
      dphi[k] = {0.125 * s.x * fy * fz, 0.125 * fx * s.y * fz, 0.125 * fx * fy * s.z};
      add_outer(j, x[k], dphi[k]);
    }
    // Columns of J are dx/dxi_a; the cofactor's columns give det J J^-T.
    const Vec3 c0{j.m[0][0], j.m[1][0], j.m[2][0]};
    const Vec3 c1{j.m[0][1], j.m[1][1], j.m[2][1]};
    const Vec3 c2{j.m[0][2], j.m[1][2], j.m[2][2]};
    const Vec3 k0 = cross(c1, c2), k1 = cross(c2, c0), k2 = cross(c0, c1);
    const double det = dot(c0, k0);
    smallest = std::min(smallest, det);
    d.volume += det;  // Gauss weights 1 per point
    for (int c = 0; c < 8; ++c) {
      const auto k = static_cast<std::size_t>(c);
      d.w[k] += phi[k] * det;
      d.g[k] += dphi[k].x * k0 + dphi[k].y * k1 + dphi[k].z * k2;
    }
  }
  d.inverted = !(smallest > 0.0);
  if (d.inverted) {
    d.volume = 8.0 * smallest;
    return d;
  }
  const double inv = 1.0 / d.volume;
  for (std::size_t k = 0; k < 8; ++k) {
    d.w[k] *= inv;
    d.g[k] = inv * d.g[k];
  }
  return d;
}

// The centroid sum_c w_c x_c (the particle's position under CPDI2).
inline Vec3 cpdi_centroid(const CpdiDomain& d) {
  Vec3 c{};
  for (std::size_t k = 0; k < 8; ++k) c += d.w[k] * d.x[k];
  return c;
}

// The 4 x 4 x 4 nodes base + (a, b, c) (node n = a + 4 (b + 4 c)) a domain reaches when every
// corner lies in the particle's cell or one of its neighbours (base = the particle's cell - 1):
// the weights, gradients, and for each corner the box node of its cell's first node with the
// corner's eight linear weights (the corners' velocities, sum_I N_I(x_c) v_I).
struct CpdiWeights {
  static constexpr int span = 4;
  static constexpr int nodes = 64;
  std::array<int, 3> base;
  std::array<double, nodes> w;
  std::array<Vec3, nodes> grad;
  std::array<int, 8> corner_node;
  std::array<std::array<double, 8>, 8> corner_w;
  // Box node of the first node of corner c's cell plus linear node j (j = a + 2 b + 4 k).
  static constexpr int box_offset(int j) {
    return (j & 1) + span * (((j >> 1) & 1) + span * (j >> 2));
  }
};

// The box weights of domain d for a particle in cell `cell`; xi0 = (x - origin) / h maps a
// point to cell units. A corner outside the reach (the particle's cell +- 1, checked by the
// solver before any transfer) is clamped into it, so the arrays are never overrun.
inline CpdiWeights cpdi_weights(const CpdiDomain& d, const std::array<int, 3>& cell,
                                const Vec3& origin, double inv_h) {
  CpdiWeights r;
  for (int a = 0; a < 3; ++a)
    r.base[static_cast<std::size_t>(a)] = cell[static_cast<std::size_t>(a)] - 1;
  r.w.fill(0.0);
  r.grad.fill(Vec3{});
  for (int c = 0; c < 8; ++c) {
    const auto k = static_cast<std::size_t>(c);
    int local[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
      const double xi = (d.x[k][a] - origin[a]) * inv_h;
      int cc = static_cast<int>(std::floor(xi)) - r.base[static_cast<std::size_t>(a)];
      cc = cc < 0 ? 0 : (cc > 2 ? 2 : cc);
      local[a] = cc;
      const double t = xi - (r.base[static_cast<std::size_t>(a)] + cc);
      f[a] = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    }
    const int first = local[0] + CpdiWeights::span * (local[1] + CpdiWeights::span * local[2]);
    r.corner_node[k] = first;
    const double wx[2] = {1.0 - f[0], f[0]}, wy[2] = {1.0 - f[1], f[1]}, wz[2] = {1.0 - f[2], f[2]};
    for (int j = 0; j < 8; ++j) {
      const int a = j & 1, b = (j >> 1) & 1, cz = j >> 2;
      const double n = wx[a] * wy[b] * wz[cz];
      const auto box = static_cast<std::size_t>(first + CpdiWeights::box_offset(j));
      r.corner_w[k][static_cast<std::size_t>(j)] = n;
      r.w[box] += d.w[k] * n;
      r.grad[box] += n * d.g[k];
    }
  }
  return r;
}

// Whether every corner lies in the particle's cell or a neighbour (the box of cpdi_weights)
// and in a cell whose nodes the grid stores (-1 .. cells along each axis, with its one-node
// halo). The largest |corner cell - particle cell| over the axes goes to `reach`.
inline bool cpdi_within_reach(const CpdiDomain& d, const std::array<int, 3>& cell,
                              const Vec3& origin, double inv_h, const std::array<int, 3>& cells,
                              int& reach) {
  bool ok = true;
  reach = 0;
  for (std::size_t k = 0; k < 8; ++k)
    for (int a = 0; a < 3; ++a) {
      const auto aa = static_cast<std::size_t>(a);
      if (!std::isfinite(d.x[k][a])) {
        reach = std::numeric_limits<int>::max();
        return false;
      }
      const int cc = static_cast<int>(std::floor((d.x[k][a] - origin[a]) * inv_h));
      reach = std::max(reach, std::abs(cc - cell[aa]));
      ok = ok && std::abs(cc - cell[aa]) <= 1 && cc >= -1 && cc <= cells[aa];
    }
  return ok;
}

}  // namespace afemp::core
