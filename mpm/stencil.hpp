// A particle's view of the grid for each shape function: the nodes it reaches, their weights,
// gradients and storage slots. The transfer kernels are templates over these, so the linear
// path keeps its 8-node loops, uGIMP and the quadratic B-spline get 27-node ones and the cubic
// B-spline 64-node ones, with no branch per node.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/grid/background_grid.hpp"
#include "core/parallel.hpp"
#include "mpm/particles.hpp"

namespace afemp::mpm {

// Trilinear hat (Ma 2005, eq 2-5): the 8 nodes of the particle's cell.
struct LinearStencil {
  static constexpr int nodes = 8;
  // Colour layers (one cell thick along the sweep axis) that may run at once: layer L
  // reaches nodes L and L + 1, so layers two apart share none.
  static constexpr int colours = 2;
  using Slots = std::array<std::int32_t, 8>;
  core::CellWeights weights;
  std::array<int, 3> cell;
  std::int64_t key;  // equal keys, equal nodes (the cell)

  LinearStencil(const core::BackgroundGrid& g, const Particles&, std::size_t, const Vec3& x)
      : cell(g.cell_of(x)) {
    weights = g.weights(x, cell);
    key = g.linear_cell(cell);
  }
  void slots(const core::BackgroundGrid& g, Slots& out) const { g.node_slots(cell, out); }
  // Grid node (i, j, k) of stencil node n.
  std::array<int, 3> node(int n) const {
    return {cell[0] + (n & 1), cell[1] + ((n >> 1) & 1), cell[2] + (n >> 2)};
  }
  double w(int n) const { return weights.w[static_cast<std::size_t>(n)]; }
  const Vec3& grad(int n) const { return weights.grad[static_cast<std::size_t>(n)]; }
};

// The weights that are products of one weight per axis: Span^3 nodes from base.
template <int Span>
struct TensorStencil {
  static constexpr int nodes = Span * Span * Span;
  // Layer L reaches nodes L - 1 .. L + 2 (uGIMP, quadratic and cubic B-splines): layers four
  // apart share none.
  static constexpr int colours = 4;
  using Slots = std::array<std::int32_t, nodes>;
  core::TensorWeights<Span> weights;
  std::int64_t key = 0;  // equal keys, equal nodes (the base node)

  void set_key() {
    const auto& b = weights.base;
    key = (static_cast<std::int64_t>(b[2] + 1) << 42) |
          (static_cast<std::int64_t>(b[1] + 1) << 21) | static_cast<std::int64_t>(b[0] + 1);
  }
  void slots(const core::BackgroundGrid& g, Slots& out) const {
    g.stencil_slots<Span>(weights.base, out);
  }
  std::array<int, 3> node(int n) const {
    const auto& b = weights.base;
    return {b[0] + n % Span, b[1] + (n / Span) % Span, b[2] + n / (Span * Span)};
  }
  double w(int n) const { return weights.w[static_cast<std::size_t>(n)]; }
  const Vec3& grad(int n) const { return weights.grad[static_cast<std::size_t>(n)]; }
  // x_I - x_p.
  Vec3 offset(int n) const { return weights.offset(n); }
  // APIC (Jiang et al. 2015, eq 10): C_p = sum_I S v_I (x_I - x_p)^T D_p^-1, where
  // D_p = sum_I S (x_I - x_p)(x_I - x_p)^T is diagonal for tensor-product weights.
  Vec3 inverse_moments() const {
    return {weights.axis[0].inverse_moment, weights.axis[1].inverse_moment,
            weights.axis[2].inverse_moment};
  }
};

// uGIMP (core/grid/gimp.hpp): 3 x 3 x 3 nodes around the particle.
struct GimpStencil : TensorStencil<3> {
  GimpStencil(const core::BackgroundGrid& g, const Particles& p, std::size_t i, const Vec3& x) {
    weights = g.gimp_weights(x, p.half_width[i]);
    set_key();
  }
};

// Quadratic (Order 2, 27 nodes) and cubic (Order 3, 64 nodes) B-splines, modified at the
// grid's faces (core/grid/bspline.hpp).
template <int Order>
struct SplineStencil : TensorStencil<Order + 1> {
  SplineStencil(const core::BackgroundGrid& g, const Particles&, std::size_t, const Vec3& x) {
    this->weights = g.template spline_weights<Order>(x);
    this->set_key();
  }
};

// CPDI1 (Tracked false: the parallelepiped of Particles::domain around the particle) and CPDI2
// (Tracked true: the hexahedron of Particles::corners), core/grid/cpdi.hpp: the 4 x 4 x 4 nodes
// from the particle's cell - 1, reached through the eight corners' cells. Layer L reaches nodes
// L - 1 .. L + 2, as the tensor stencils.
template <bool Tracked>
struct CpdiStencil {
  static constexpr int nodes = core::CpdiWeights::nodes;
  static constexpr int colours = 4;
  static constexpr bool tracks_corners = Tracked;
  using Slots = std::array<std::int32_t, nodes>;
  core::CpdiWeights weights;
  std::int64_t key = 0;  // equal keys, equal nodes (the box's first node)

  static core::CpdiDomain domain(const Particles& p, std::size_t i, const Vec3& x) {
    if constexpr (Tracked)
      return core::cpdi2_domain(p.corners[i]);
    else
      return core::cpdi1_domain(x, p.domain[i]);
  }
  CpdiStencil(const core::BackgroundGrid& g, const Particles& p, std::size_t i, const Vec3& x) {
    weights = g.cpdi_weights(domain(p, i, x), g.cell_of(x));
    const auto& b = weights.base;
    key = (static_cast<std::int64_t>(b[2] + 1) << 42) |
          (static_cast<std::int64_t>(b[1] + 1) << 21) | static_cast<std::int64_t>(b[0] + 1);
  }
  void slots(const core::BackgroundGrid& g, Slots& out) const {
    g.stencil_slots<core::CpdiWeights::span>(weights.base, out);
  }
  std::array<int, 3> node(int n) const {
    const auto& b = weights.base;
    constexpr int s = core::CpdiWeights::span;
    return {b[0] + n % s, b[1] + (n / s) % s, b[2] + n / (s * s)};
  }
  double w(int n) const { return weights.w[static_cast<std::size_t>(n)]; }
  const Vec3& grad(int n) const { return weights.grad[static_cast<std::size_t>(n)]; }
  // sum_I N_I(x_c) v_I at corner c, from the nodal field v (slot + field).
  Vec3 corner_velocity(int c, const Slots& slot, std::size_t field, const Vec3* v) const {
    const auto k = static_cast<std::size_t>(c);
    Vec3 out{};
    for (int j = 0; j < 8; ++j) {
      const auto n =
          static_cast<std::size_t>(weights.corner_node[k] + core::CpdiWeights::box_offset(j));
      out += weights.corner_w[k][static_cast<std::size_t>(j)] *
             v[static_cast<std::size_t>(slot[n]) + field];
    }
    return out;
  }
};

// m <- m + dt L m (m <- (I + dt L) m): CPDI1's edge vectors and the deformation gradient F.
inline void add_velocity_gradient_step(core::Mat3& m, const core::Mat3& l, double dt) {
  const core::Mat3 m0 = m;
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 3; ++k)
      m.m[a][k] += dt * (l.m[a][0] * m0.m[0][k] + l.m[a][1] * m0.m[1][k] + l.m[a][2] * m0.m[2][k]);
}

// Moves particle i's CPDI domain over dt with the nodal velocity v that moves the particle
// (slots + field): CPDI1's edge vectors by the velocity gradient, r_k <- (I + dt L) r_k with
// L = sum_I v_I (x) grad S_Ip (the incremental form of r_k = F r_k^0); CPDI2's corners by the
// velocity interpolated at each, x_c <- x_c + dt sum_I N_I(x_c) v_I, and the particle to the
// centroid of its new domain. Other stencils carry no domain.
template <class Stencil>
void move_domain(Particles& p, std::size_t i, const Stencil& st,
                 const typename Stencil::Slots& slot, std::size_t field, const Vec3* v, double dt) {
  if constexpr (requires { Stencil::tracks_corners; }) {
    if constexpr (Stencil::tracks_corners) {
      std::array<Vec3, 8>& x = p.corners[i];
      for (int c = 0; c < 8; ++c)
        x[static_cast<std::size_t>(c)] += dt * st.corner_velocity(c, slot, field, v);
      p.position[i] = core::cpdi_centroid(core::cpdi2_domain(x));
    } else {
      core::Mat3 l;
      for (int n = 0; n < Stencil::nodes; ++n)
        core::add_outer(l, v[static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field],
                        st.grad(n));
      add_velocity_gradient_step(p.domain[i], l, dt);
    }
  }
}

// Total-Lagrangian MPM (de Vaucorbeil, Nguyen & Hutchinson 2020; docs/references.md): the Base
// shape's weights at the particle's reference position X_p, so they depend on X_p alone and never
// cross a cell, and their gradients pushed to the current configuration,
// grad_x S_I = F^-T grad_X S_I. Then -V sigma grad_x S_I = -V_0 P grad_X S_I (P = J sigma F^-T,
// the first Piola-Kirchhoff stress) and sum_I v_I (x) grad_x S_I = dF/dt F^-1 = L: the transfer
// kernels run unchanged. The weights are taken from X_p at each use, the same every time, rather
// than stored (27 to 64 weights and gradients would be 0.9 to 2 KB a particle; which is faster
// has not been measured).
template <class Base>
struct ReferenceStencil : Base {
  static constexpr bool reference = true;
  ReferenceStencil(const core::BackgroundGrid& g, const Particles& p, std::size_t i, const Vec3&)
      : Base(g, p, i, p.reference_position[i]) {
    const core::Mat3& f = p.deformation_gradient[i];
    const Vec3 f0{f.m[0][0], f.m[1][0], f.m[2][0]}, f1{f.m[0][1], f.m[1][1], f.m[2][1]},
        f2{f.m[0][2], f.m[1][2], f.m[2][2]};
    // F^-T v = (v_0 f1 x f2 + v_1 f2 x f0 + v_2 f0 x f1) / det F, f_a the columns of F.
    const double inv = 1.0 / core::dot(f0, core::cross(f1, f2));
    const Vec3 c0 = inv * core::cross(f1, f2), c1 = inv * core::cross(f2, f0),
               c2 = inv * core::cross(f0, f1);
    for (Vec3& d : this->weights.grad) d = d.x * c0 + d.y * c1 + d.z * c2;
  }
};

// Calls f.template operator()<Stencil>() for a shape function.
template <class F>
void with_shape(core::ShapeFunction shape, F&& f) {
  switch (shape) {
    case core::ShapeFunction::linear:
      f.template operator()<LinearStencil>();
      break;
    case core::ShapeFunction::gimp:
      f.template operator()<GimpStencil>();
      break;
    case core::ShapeFunction::bspline2:
      f.template operator()<SplineStencil<2>>();
      break;
    case core::ShapeFunction::bspline3:
      f.template operator()<SplineStencil<3>>();
      break;
    case core::ShapeFunction::cpdi1:
      f.template operator()<CpdiStencil<false>>();
      break;
    case core::ShapeFunction::cpdi2:
      f.template operator()<CpdiStencil<true>>();
      break;
  }
}

// Calls f(i, stencil, slots) for every particle, threads splitting the particles statically
// (each call writes only particle i: no race).
template <class Stencil, class F>
void for_each_particle_stencil(const core::BackgroundGrid& g, Particles& p, F&& f) {
  const std::size_t n = p.size();
#pragma omp parallel for schedule(static) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    const Stencil st(g, p, i, p.position[i]);
    typename Stencil::Slots slot;
    st.slots(g, slot);
    f(i, st, slot);
  }
}

// Runs body(begin, end) on the particle range of every colour layer (particle_binning.cpp):
// the layers of one colour in parallel (they share no node), then the next colour. Scatter
// loops from particles to nodes use it to sum without atomics.
template <int Colours, class Body>
void sweep_layers(const std::vector<std::int64_t>& offsets, Body&& body) {
  const std::int64_t layers = static_cast<std::int64_t>(offsets.size()) - 1;
  [[maybe_unused]] const bool threads =  // read by the pragma (unused without OpenMP)
      core::worth_threads(static_cast<std::size_t>(offsets.back()));
  for (int colour = 0; colour < Colours; ++colour) {
#pragma omp parallel for schedule(dynamic, 1) if (threads)
    for (std::int64_t l = colour; l < layers; l += Colours)
      body(static_cast<std::size_t>(offsets[static_cast<std::size_t>(l)]),
           static_cast<std::size_t>(offsets[static_cast<std::size_t>(l) + 1]));
  }
}

// C_p = b D_p^-1 with b = sum S v (x_I - x_p)^T and D_p^-1 diagonal (GimpStencil).
inline void store_affine(core::Mat3& c, const core::Mat3& b, const Vec3& inverse_moments) {
  for (int r = 0; r < 3; ++r)
    for (int a = 0; a < 3; ++a) c.m[r][a] = b.m[r][a] * inverse_moments[a];
}

// The grid-to-particle velocity update of one particle, summed node by node: the PIC/FLIP
// blend v_p <- flip (v_p + sum S (v_new - v)) + (1 - flip) sum S v_new, or with the affine
// transfer v_p <- sum S v_new and C_p <- sum S v_new (x_I - x_p)^T D_p^-1 (Jiang et al.
// 2015, eqs 8-10). Used by G2P (USF, MUSL) and by USL's kinematics pass.
template <class Stencil, bool Affine>
struct VelocityUpdate {
  Vec3 v_grid, dv;
  core::Mat3 b;
  void add(const Stencil& st, int k, const Vec3& v_new, const Vec3& v_old) {
    const double wk = st.w(k);
    v_grid += wk * v_new;
    if constexpr (Affine)
      core::add_outer(b, wk * v_new, st.offset(k));
    else
      dv += wk * (v_new - v_old);
  }
  void store(Particles& p, std::size_t i, const Stencil& st, double flip) const {
    if constexpr (Affine) {
      p.velocity[i] = v_grid;
      store_affine(p.affine[i], b, st.inverse_moments());
    } else {
      p.velocity[i] = flip * (p.velocity[i] + dv) + (1.0 - flip) * v_grid;
    }
  }
};

// How far a point at offset d from a grid node reaches along the unit normal n (Lian et al. 2013,
// eq 42), or -inf for a point more than half a cell h from the normal line through the node.
inline double reach_along(const Vec3& d, const Vec3& n, double h) {
  const double along = core::dot(d, n);
  const Vec3 lateral = d - along * n;
  return core::dot(lateral, lateral) <= 0.25 * h * h ? along
                                                     : -std::numeric_limits<double>::infinity();
}

}  // namespace afemp::mpm
