// Elements, fields and a small mesh shared by the hexahedron kernel tests (header only; not a
// test file itself): cubes, fixed-seed distorted elements, linear velocity fields and the
// 2x2x2 patch of the patch test with its interior node moved.
#pragma once

#include <array>
#include <cstdint>
#include <random>

#include "afemp/tensor.hpp"
#include "fem/hexahedron.hpp"

namespace afemp::fem::test {

// Uniform in [-1, 1), from the raw 32-bit engine output so that the sequence is the same with
// every standard library (std::uniform_real_distribution is not).
inline double symmetric_random(std::mt19937& rng) {
  return 2.0 * (static_cast<double>(rng()) / 4294967296.0) - 1.0;
}

inline core::Vec3 random_vec(std::mt19937& rng) {
  const double x = symmetric_random(rng), y = symmetric_random(rng), z = symmetric_random(rng);
  return {x, y, z};
}

inline core::Mat3 random_mat(std::mt19937& rng) {
  core::Mat3 a;
  for (auto& row : a.m)
    for (double& aij : row) aij = symmetric_random(rng);
  return a;
}

inline core::SymTensor random_stress(std::mt19937& rng, double scale) {
  core::SymTensor s;
  for (double* c : {&s.xx, &s.yy, &s.zz, &s.yz, &s.xz, &s.xy}) *c = scale * symmetric_random(rng);
  return s;
}

inline core::Vec3 times(const core::Mat3& a, const core::Vec3& x) {
  return {a.m[0][0] * x.x + a.m[0][1] * x.y + a.m[0][2] * x.z,
          a.m[1][0] * x.x + a.m[1][1] * x.y + a.m[1][2] * x.z,
          a.m[2][0] * x.x + a.m[2][1] * x.y + a.m[2][2] * x.z};
}

// The cube [0, h]^3 in kHexNatural order.
inline HexVectors cube(double h) {
  HexVectors x;
  for (int a = 0; a < 8; ++a)
    for (int i = 0; i < 3; ++i) x[a][i] = 0.5 * h * (1.0 + kHexNatural[a][i]);
  return x;
}

// The unit cube with every coordinate of every corner moved by up to 20 % of the edge.
inline HexVectors distorted_hex(std::uint32_t seed) {
  std::mt19937 rng(seed);
  HexVectors x = cube(1.0);
  for (core::Vec3& p : x) p += 0.2 * random_vec(rng);
  return x;
}

// v_a = A x_a + c at every node.
inline HexVectors linear_field(const HexVectors& x, const core::Mat3& a, const core::Vec3& c) {
  HexVectors v;
  for (int n = 0; n < 8; ++n) v[n] = times(a, x[n]) + c;
  return v;
}

// 2x2x2 elements of edge h filling [0, 2h]^3; node (i, j, k) has index i + 3 j + 9 k, and the
// one interior node (13) is moved by up to 20 % of h in each direction.
struct Patch {
  double h = 1.0;
  std::array<core::Vec3, 27> nodes;
  std::array<std::array<int, 8>, 8> elements;

  Patch(double edge, std::uint32_t seed) : h(edge) {
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) nodes[i + 3 * j + 9 * k] = {i * h, j * h, k * h};
    std::mt19937 rng(seed);
    nodes[13] += 0.2 * h * random_vec(rng);
    for (int e = 0; e < 8; ++e)
      for (int a = 0; a < 8; ++a) {
        const int i = e % 2 + (kHexNatural[a][0] > 0), j = (e / 2) % 2 + (kHexNatural[a][1] > 0),
                  k = e / 4 + (kHexNatural[a][2] > 0);
        elements[e][a] = i + 3 * j + 9 * k;
      }
  }

  HexVectors element_nodes(int e) const {
    HexVectors x;
    for (int a = 0; a < 8; ++a) x[a] = nodes[elements[e][a]];
    return x;
  }

  // Integral over the patch boundary of N_n sigma.n for node n (zero for the interior node):
  // on each flat boundary face a node shares h^2/4 with every square it is a corner of.
  core::Vec3 traction_integral(int n, const core::SymTensor& s) const {
    const int index[3] = {n % 3, (n / 3) % 3, n / 9};
    core::Vec3 t;
    for (int d = 0; d < 3; ++d) {
      if (index[d] == 1) continue;
      int squares = 1;
      for (int other = 0; other < 3; ++other)
        if (other != d && index[other] == 1) squares *= 2;
      core::Vec3 normal;
      normal[d] = index[d] == 0 ? -1.0 : 1.0;
      const core::Vec3 traction{s.xx * normal.x + s.xy * normal.y + s.xz * normal.z,
                                s.xy * normal.x + s.yy * normal.y + s.yz * normal.z,
                                s.xz * normal.x + s.yz * normal.y + s.zz * normal.z};
      t += (squares * 0.25 * h * h) * traction;
    }
    return t;
  }
};

}  // namespace afemp::fem::test
