// Weights that are products of one weight per axis (uGIMP, the B-splines): each axis's nodes
// base..base+Span-1, and the Span^3 nodes of the particle's stencil they make.
#pragma once

#include <array>
#include <cstddef>

#include "afemp/tensor.hpp"

namespace afemp::core {

// Weights of the nodes base..base+Span-1 along one axis.
template <int Span>
struct AxisWeights {
  int base = 0;
  std::array<double, Span> w{};       // S
  std::array<double, Span> grad{};    // dS/dx_p
  std::array<double, Span> offset{};  // x_I - x_p
  double inverse_moment = 0.0;        // 1 / sum_I S (x_I - x_p)^2, the APIC D_p^-1 of this axis
};

// The Span^3 nodes base + (a, b, c), node n = a + Span (b + Span c): S = Sx Sy Sz and its
// gradient.
template <int Span>
struct TensorWeights {
  static constexpr int nodes = Span * Span * Span;
  std::array<int, 3> base;
  std::array<double, nodes> w;
  std::array<Vec3, nodes> grad;
  std::array<AxisWeights<Span>, 3> axis;
  // x_I - x_p of node n.
  Vec3 offset(int n) const {
    return {axis[0].offset[static_cast<std::size_t>(n % Span)],
            axis[1].offset[static_cast<std::size_t>((n / Span) % Span)],
            axis[2].offset[static_cast<std::size_t>(n / (Span * Span))]};
  }
  // Fills base, w and grad from axis.
  void multiply() {
    const AxisWeights<Span>&ax = axis[0], &ay = axis[1], &az = axis[2];
    for (int d = 0; d < 3; ++d)
      base[static_cast<std::size_t>(d)] = axis[static_cast<std::size_t>(d)].base;
    for (std::size_t c = 0; c < Span; ++c)
      for (std::size_t b = 0; b < Span; ++b) {
        const double wyz = ay.w[b] * az.w[c];
        const double gy = ay.grad[b] * az.w[c], gz = ay.w[b] * az.grad[c];
        for (std::size_t i = 0; i < Span; ++i) {
          const std::size_t n = i + Span * (b + Span * c);
          w[n] = ax.w[i] * wyz;
          grad[n] = {ax.grad[i] * wyz, ax.w[i] * gy, ax.w[i] * gz};
        }
      }
  }
};

}  // namespace afemp::core
