// The one-point hexahedron kernels of Flanagan & Belytschko, IJNME 17 (1981) 679-706, written
// for W elements side by side ("lanes"): every array is [component][node][lane], so each
// formula is one loop over the lanes that the compiler turns into vector instructions. The
// hexahedron stage runs them on packs of elements; the one-element functions of
// fem/hexahedron_one_point.hpp and fem/hourglass.hpp are the same kernels with W = 1, so each
// formula exists once.
//
// - b vectors b_a = integral of grad N_a dV = dV/dx_a (FB eq. 79, their closed cubic form with
//   the node permutation), relative to the centroid for precision, and the exact trilinear
//   volume V = sum_a b_a,x x_a (linear completeness);
// - the mean velocity gradient L_ij = (1/V) sum_a v_a,i b_a,j;
// - the length for the time step, V / largest face area, each face's area the mean of its two
//   diagonal splits into triangles (at least the true area of a warped face: conservative);
// - FB's hourglass shape vectors gamma_k = h_k - (1/V) sum_b (h_k,b x_b) . b_a (FB eq. 42) and
//   the hourglass velocities q_ik = sum_a v_a,i gamma_k,a;
// - the nodal forces of a uniform stress and of generalised hourglass forces g_ik:
//   f_a,i -= sigma_ij b_a,j + sum_k g_ik gamma_k,a (f is external minus internal).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "fem/hexahedron.hpp"
#include "fem/mesh.hpp"

namespace afemp::fem::lanes {

template <int W>
using NodeArray = double[3][8][W];  // [component][node][lane]

// FB's node permutation: row a lists, for node a, the nodes that take the places of nodes
// 0..7 in the formula written for node 0, so that one expression gives every B vector.
inline constexpr int kPermutation[8][8] = {{0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, 3, 0, 5, 6, 7, 4},
                                           {2, 3, 0, 1, 6, 7, 4, 5}, {3, 0, 1, 2, 7, 4, 5, 6},
                                           {4, 7, 6, 5, 0, 3, 2, 1}, {5, 4, 7, 6, 1, 0, 3, 2},
                                           {6, 5, 4, 7, 2, 1, 0, 3}, {7, 6, 5, 4, 3, 2, 1, 0}};

// Base vectors h_k of the four hourglass modes, the nodal values of eta*zeta, zeta*xi, xi*eta
// and xi*eta*zeta: orthogonal to each other and to the constant and linear nodal patterns.
inline constexpr std::array<std::array<double, 8>, 4> kHourglassBase = [] {
  std::array<std::array<double, 8>, 4> h{};
  for (int a = 0; a < 8; ++a) {
    const double xi = kHexNatural[a][0], eta = kHexNatural[a][1], zeta = kHexNatural[a][2];
    h[0][a] = eta * zeta;
    h[1][a] = zeta * xi;
    h[2][a] = xi * eta;
    h[3][a] = xi * eta * zeta;
  }
  return h;
}();

// b_a,i = dV/dx_a,i (FB eq. 79) for node A and component I of every lane: it involves only the
// two other components j, k (cyclic after I). Indices are compile-time constants so that the
// lane loop vectorises.
template <int W, int A, int I>
inline void b_component(const NodeArray<W>& c, NodeArray<W>& b) {
  constexpr int J = (I + 1) % 3, K = (I + 2) % 3;
  constexpr int n2 = kPermutation[A][1], n3 = kPermutation[A][2], n4 = kPermutation[A][3],
                n5 = kPermutation[A][4], n6 = kPermutation[A][5], n8 = kPermutation[A][7];
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    const double y2 = c[J][n2][l], y3 = c[J][n3][l], y4 = c[J][n4][l], y5 = c[J][n5][l],
                 y6 = c[J][n6][l], y8 = c[J][n8][l];
    const double z2 = c[K][n2][l], z3 = c[K][n3][l], z4 = c[K][n4][l], z5 = c[K][n5][l],
                 z6 = c[K][n6][l], z8 = c[K][n8][l];
    b[I][A][l] = (y2 * ((z6 - z3) - (z4 - z5)) + y3 * (z2 - z4) + y4 * ((z3 - z8) - (z5 - z2)) +
                  y5 * ((z8 - z6) - (z2 - z4)) + y6 * (z5 - z2) + y8 * (z4 - z5)) *
                 (1.0 / 12.0);
  }
}

// Coordinates relative to each element's centroid, c, then b (same layout) and the volume.
template <int W>
void b_vectors(const NodeArray<W>& x, NodeArray<W>& c, NodeArray<W>& b, double (&volume)[W]) {
  for (int i = 0; i < 3; ++i) {
    double centroid[W] = {};
    for (int a = 0; a < 8; ++a)
      for (int l = 0; l < W; ++l) centroid[l] += x[i][a][l];
    for (int a = 0; a < 8; ++a)
      for (int l = 0; l < W; ++l) c[i][a][l] = x[i][a][l] - 0.125 * centroid[l];
  }
  [&]<int... A>(std::integer_sequence<int, A...>) {
    (b_component<W, A, 0>(c, b), ...);
    (b_component<W, A, 1>(c, b), ...);
    (b_component<W, A, 2>(c, b), ...);
  }
  (std::make_integer_sequence<int, 8>{});
  for (int l = 0; l < W; ++l) volume[l] = 0.0;
  for (int a = 0; a < 8; ++a)
    for (int l = 0; l < W; ++l) volume[l] += b[0][a][l] * c[0][a][l];
}

// L[i][j][lane] = dv_i/dx_j.
template <int W>
void velocity_gradient(const NodeArray<W>& b, const double (&volume)[W], const NodeArray<W>& v,
                       double (&grad)[3][3][W]) {
  double inv_v[W];
  for (int l = 0; l < W; ++l) inv_v[l] = 1.0 / volume[l];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s[W] = {};
      for (int a = 0; a < 8; ++a)
#pragma omp simd
        for (int l = 0; l < W; ++l) s[l] += v[i][a][l] * b[j][a][l];
      for (int l = 0; l < W; ++l) grad[i][j][l] = s[l] * inv_v[l];
    }
}

// Adds twice the area of triangle (P, Q, R) of every lane to sum.
template <int W, int P, int Q, int R>
inline void add_twice_triangle_area(const NodeArray<W>& x, double (&sum)[W]) {
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    const double ux = x[0][Q][l] - x[0][P][l], uy = x[1][Q][l] - x[1][P][l],
                 uz = x[2][Q][l] - x[2][P][l];
    const double wx = x[0][R][l] - x[0][P][l], wy = x[1][R][l] - x[1][P][l],
                 wz = x[2][R][l] - x[2][P][l];
    const double cx = uy * wz - uz * wy, cy = uz * wx - ux * wz, cz = ux * wy - uy * wx;
    sum[l] += std::sqrt(cx * cx + cy * cy + cz * cz);
  }
}

// largest = max(largest, area of face F): the mean of the face's two splits along its
// diagonals, each the sum of two triangles.
template <int W, int F>
inline void face_area(const NodeArray<W>& x, double (&largest)[W]) {
  constexpr int p0 = kHexFaces[F][0], p1 = kHexFaces[F][1], p2 = kHexFaces[F][2],
                p3 = kHexFaces[F][3];
  double sum[W] = {};
  add_twice_triangle_area<W, p0, p1, p2>(x, sum);
  add_twice_triangle_area<W, p0, p2, p3>(x, sum);
  add_twice_triangle_area<W, p1, p2, p3>(x, sum);
  add_twice_triangle_area<W, p1, p3, p0>(x, sum);
  for (int l = 0; l < W; ++l) largest[l] = std::max(largest[l], 0.25 * sum[l]);
}

// V / (largest face area) over the faces kHexFaces.
template <int W>
void characteristic_length(const NodeArray<W>& x, const double (&volume)[W], double (&length)[W]) {
  double largest[W] = {};
  [&]<int... F>(std::integer_sequence<int, F...>) {
    (face_area<W, F>(x, largest), ...);
  }
  (std::make_integer_sequence<int, 6>{});
  for (int l = 0; l < W; ++l) length[l] = volume[l] / largest[l];
}

// gamma[k][a][lane] from the centroid-relative coordinates c and the b vectors.
template <int W, int K>
inline void hourglass_shape(const NodeArray<W>& c, const NodeArray<W>& b, const double (&inv_v)[W],
                            double (&gamma)[4][8][W]) {
  constexpr std::array<double, 8> h = kHourglassBase[K];
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    double hx[3];  // (1/V) sum_n h_k,n c_n
    for (int i = 0; i < 3; ++i) {
      hx[i] = 0.0;
      for (int n = 0; n < 8; ++n) hx[i] += h[n] * c[i][n][l];
      hx[i] *= inv_v[l];
    }
    for (int a = 0; a < 8; ++a)
      gamma[K][a][l] = h[a] - (hx[0] * b[0][a][l] + hx[1] * b[1][a][l] + hx[2] * b[2][a][l]);
  }
}

template <int W>
void hourglass_shapes(const NodeArray<W>& c, const NodeArray<W>& b, const double (&volume)[W],
                      double (&gamma)[4][8][W]) {
  double inv_v[W];
  for (int l = 0; l < W; ++l) inv_v[l] = 1.0 / volume[l];
  hourglass_shape<W, 0>(c, b, inv_v, gamma);
  hourglass_shape<W, 1>(c, b, inv_v, gamma);
  hourglass_shape<W, 2>(c, b, inv_v, gamma);
  hourglass_shape<W, 3>(c, b, inv_v, gamma);
}

// q[k][i][lane] = sum_a v_a,i gamma_k,a.
template <int W>
void hourglass_velocities(const double (&gamma)[4][8][W], const NodeArray<W>& v,
                          double (&q)[4][3][W]) {
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) {
      double s[W] = {};
      for (int a = 0; a < 8; ++a)
#pragma omp simd
        for (int l = 0; l < W; ++l) s[l] += gamma[k][a][l] * v[i][a][l];
      for (int l = 0; l < W; ++l) q[k][i][l] = s[l];
    }
}

// f[i][a][lane] = -(sigma_ij b_a,j) for the stress (xx, yy, zz, yz, xz, xy)[component][lane].
template <int W>
void stress_forces(const NodeArray<W>& b, const double (&sigma)[6][W], NodeArray<W>& f) {
  for (int a = 0; a < 8; ++a)
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const double bx = b[0][a][l], by = b[1][a][l], bz = b[2][a][l];
      const double sxx = sigma[0][l], syy = sigma[1][l], szz = sigma[2][l], syz = sigma[3][l],
                   sxz = sigma[4][l], sxy = sigma[5][l];
      f[0][a][l] = -(sxx * bx + sxy * by + sxz * bz);
      f[1][a][l] = -(sxy * bx + syy * by + syz * bz);
      f[2][a][l] = -(sxz * bx + syz * by + szz * bz);
    }
}

// f_a,i -= sum_k g[k][i] gamma_k,a.
template <int W>
void subtract_hourglass_forces(const double (&gamma)[4][8][W], const double (&g)[4][3][W],
                               NodeArray<W>& f) {
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 8; ++a)
#pragma omp simd
      for (int l = 0; l < W; ++l)
        f[i][a][l] -= gamma[0][a][l] * g[0][i][l] + gamma[1][a][l] * g[1][i][l] +
                      gamma[2][a][l] * g[2][i][l] + gamma[3][a][l] * g[3][i][l];
}

// Lane l of a pack from, or to, one vector per node.
template <int W>
void load(const HexVectors& from, NodeArray<W>& to, int l) {
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) to[i][a][l] = from[a][i];
}
template <int W>
void store(const NodeArray<W>& from, int l, HexVectors& to) {
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) to[a][i] = from[i][a][l];
}

}  // namespace afemp::fem::lanes
