// The background grid shared by particles (and, later, FE nodes): regular cubic cells with
// trilinear shape functions (Ma 2005, eq 2-5). Nodal data exists only in 4x4x4-node blocks
// that material touches, so memory follows the material, not the domain (the dynamic grid of
// Lian et al. 2013, §2.8); a block directory over the domain costs 4 bytes per 64 nodes.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/grid/bspline.hpp"
#include "core/grid/cpdi.hpp"
#include "core/grid/gimp.hpp"
#include "core/grid/tensor_weights.hpp"
#include "core/scene.hpp"

namespace afemp::core {

// Trilinear weights and gradients of the 8 nodes of the cell that contains a point.
// Node n = a + 2 b + 4 c is node (i + a, j + b, k + c) of the cell (i, j, k).
struct CellWeights {
  std::array<double, 8> w;
  std::array<Vec3, 8> grad;
};

// uGIMP weights of the 3 x 3 x 3 nodes base + (a, b, c), node n = a + 3 b + 9 c (gimp.hpp).
using GimpWeights = TensorWeights<3>;
// B-spline weights of the (Order + 1)^3 nodes a point reaches (bspline.hpp).
template <int Order>
using SplineWeights = TensorWeights<Order + 1>;

class BackgroundGrid {
 public:
  static constexpr int block_edge = 4;  // nodes per block edge
  static constexpr int block_nodes = block_edge * block_edge * block_edge;

  // halo: nodes stored beyond each face (1 for uGIMP, whose particles near a face reach the
  // node outside it; those nodes take the face's condition).
  explicit BackgroundGrid(const GridSettings& settings, int halo = 0);
  int halo() const { return halo_; }

  const GridSettings& settings() const { return settings_; }
  double cell() const { return h_; }
  double inverse_cell() const { return inv_h_; }
  // Cells and nodes per axis.
  const std::array<int, 3>& cells() const { return cells_; }
  std::array<int, 3> nodes() const { return {cells_[0] + 1, cells_[1] + 1, cells_[2] + 1}; }

  // Cell containing x, per axis; may be outside [0, cells) for points outside the domain.
  std::array<int, 3> cell_of(const Vec3& x) const {
    return {static_cast<int>(std::floor((x.x - origin_.x) * inv_h_)),
            static_cast<int>(std::floor((x.y - origin_.y) * inv_h_)),
            static_cast<int>(std::floor((x.z - origin_.z) * inv_h_))};
  }
  bool inside(const std::array<int, 3>& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < cells_[0] && c[1] < cells_[1] &&
           c[2] < cells_[2];
  }
  // Weights of the 8 nodes of cell c at x (x must lie in c); inline: every transfer of
  // every particle calls it.
  CellWeights weights(const Vec3& x, const std::array<int, 3>& c) const {
    // Local coordinates in [0, 1) along each axis; N = (1 - f) or f per axis (eq 2-5).
    const double fx = (x.x - origin_.x) * inv_h_ - c[0];
    const double fy = (x.y - origin_.y) * inv_h_ - c[1];
    const double fz = (x.z - origin_.z) * inv_h_ - c[2];
    const double wx[2] = {1.0 - fx, fx}, wy[2] = {1.0 - fy, fy}, wz[2] = {1.0 - fz, fz};
    const double dx[2] = {-inv_h_, inv_h_};
    CellWeights r;
    for (int n = 0; n < 8; ++n) {
      const int a = n & 1, b = (n >> 1) & 1, cc = n >> 2;
      r.w[static_cast<std::size_t>(n)] = wx[a] * wy[b] * wz[cc];
      r.grad[static_cast<std::size_t>(n)] = {dx[a] * wy[b] * wz[cc], wx[a] * dx[b] * wz[cc],
                                             wx[a] * wy[b] * dx[cc]};
    }
    return r;
  }
  // uGIMP weights at x for a particle of half-width a h (0 < a <= 1/2).
  GimpWeights gimp_weights(const Vec3& x, double a) const {
    GimpWeights r;
    for (int d = 0; d < 3; ++d)
      r.axis[static_cast<std::size_t>(d)] = gimp_axis((x[d] - origin_[d]) * inv_h_, a, h_);
    r.multiply();
    return r;
  }
  // Boundary-modified B-spline weights of order 2 or 3 at x (x inside the domain).
  template <int Order>
  SplineWeights<Order> spline_weights(const Vec3& x) const {
    SplineWeights<Order> r;
    for (int d = 0; d < 3; ++d)
      r.axis[static_cast<std::size_t>(d)] = bspline_axis<Order>(
          (x[d] - origin_[d]) * inv_h_, cells_[static_cast<std::size_t>(d)], h_);
    r.multiply();
    return r;
  }
  // CPDI weights of domain d for a particle in cell c (cpdi.hpp).
  CpdiWeights cpdi_weights(const CpdiDomain& d, const std::array<int, 3>& c) const {
    return core::cpdi_weights(d, c, origin_, inv_h_);
  }
  // Whether domain d of a particle in cell c lies within the CPDI reach (cpdi.hpp).
  bool cpdi_within_reach(const CpdiDomain& d, const std::array<int, 3>& c, int& away) const {
    return core::cpdi_within_reach(d, c, origin_, inv_h_, cells_, away);
  }
  Vec3 node_position(int i, int j, int k) const {
    return {origin_.x + i * h_, origin_.y + j * h_, origin_.z + k * h_};
  }

  // --- Activation, once per step -------------------------------------------------------
  // Makes active exactly the blocks that hold a node of one of the given cells, or of the
  // halo around it (cells as linear indices, see linear_cell); nodal storage is resized, not
  // shrunk, so a steady run allocates nothing. Block order is ascending block index: deterministic.
  void activate(std::span<const std::int64_t> cells);
  std::int64_t linear_cell(const std::array<int, 3>& c) const {
    return (static_cast<std::int64_t>(c[2]) * cells_[1] + c[1]) * cells_[0] + c[0];
  }
  std::array<int, 3> cell_from_linear(std::int64_t l) const {
    const std::int64_t nx = cells_[0], ny = cells_[1];
    return {static_cast<int>(l % nx), static_cast<int>((l / nx) % ny),
            static_cast<int>(l / (nx * ny))};
  }

  // Storage slots of the 8 nodes of an active cell, in CellWeights order.
  void node_slots(const std::array<int, 3>& c, std::array<std::int32_t, 8>& slots) const {
    const std::int64_t bx = blocks_[0], by = blocks_[1];
    int blk[3][2], loc[3][2];
    for (int a = 0; a < 3; ++a)
      for (int o = 0; o < 2; ++o) {
        const int n = c[static_cast<std::size_t>(a)] + o + halo_;
        blk[a][o] = n / block_edge;
        loc[a][o] = n % block_edge;
      }
    for (int n = 0; n < 8; ++n) {
      const int a = n & 1, b = (n >> 1) & 1, cc = n >> 2;
      const std::int64_t block = (blk[2][cc] * by + blk[1][b]) * bx + blk[0][a];
      slots[static_cast<std::size_t>(n)] =
          directory_[static_cast<std::size_t>(block)] * block_nodes +
          (loc[2][cc] * block_edge + loc[1][b]) * block_edge + loc[0][a];
    }
  }
  // Storage slots of the Span^3 nodes base + (a, b, c), node n = a + Span (b + Span c); every
  // node must lie in an active block (activate with the halo).
  template <int Span>
  void stencil_slots(const std::array<int, 3>& base,
                     std::array<std::int32_t, Span * Span * Span>& slots) const {
    const std::int64_t bx = blocks_[0], by = blocks_[1];
    int blk[3][Span], loc[3][Span];
    for (int a = 0; a < 3; ++a)
      for (int o = 0; o < Span; ++o) {
        const int n = base[static_cast<std::size_t>(a)] + o + halo_;
        blk[a][o] = n / block_edge;
        loc[a][o] = n % block_edge;
      }
    for (int c = 0; c < Span; ++c)
      for (int b = 0; b < Span; ++b)
        for (int a = 0; a < Span; ++a) {
          const std::int64_t block = (blk[2][c] * by + blk[1][b]) * bx + blk[0][a];
          slots[static_cast<std::size_t>(a + Span * (b + Span * c))] =
              directory_[static_cast<std::size_t>(block)] * block_nodes +
              (loc[2][c] * block_edge + loc[1][b]) * block_edge + loc[0][a];
        }
  }
  // Number of node slots in use (active blocks x 64; slots of untouched nodes carry zero mass).
  std::size_t slot_count() const { return active_blocks_.size() * block_nodes; }
  std::size_t active_block_count() const { return active_blocks_.size(); }
  // Grid node (i, j, k) of a slot.
  std::array<int, 3> node_of_slot(std::size_t slot) const;
  // Active block a (slots a x 64 ..) by its index in the block directory (ascending in a), the
  // block coordinates of an index (block (i, j, k) stores nodes 4i - halo .. 4i + 3 - halo along
  // x, and so on), and the active number of a directory index (-1: inactive).
  std::int64_t active_block(std::size_t a) const { return active_blocks_[a]; }
  std::array<int, 3> block_coord(std::int64_t block) const {
    const std::int64_t bx = blocks_[0], by = blocks_[1];
    return {static_cast<int>(block % bx), static_cast<int>((block / bx) % by),
            static_cast<int>(block / (bx * by))};
  }
  // The block that stores cell c's lowest node: the cell's block, by which a run divided among
  // ranks gives each particle its rank (mpm/domain_decomposition.cpp).
  std::array<int, 3> block_of_cell(const std::array<int, 3>& c) const {
    return {(c[0] + halo_) / block_edge, (c[1] + halo_) / block_edge, (c[2] + halo_) / block_edge};
  }
  std::int32_t active_number(std::int64_t block) const {
    return block >= 0 && static_cast<std::size_t>(block) < directory_.size()
               ? directory_[static_cast<std::size_t>(block)]
               : -1;
  }
  // Calls f(slot, node) for every slot of every active block; blocks split statically among
  // the threads of an enclosing parallel region (call from inside one, or serially).
  template <class F>
  void for_each_slot(F&& f) const {
    const std::size_t blocks = active_blocks_.size();
#pragma omp for schedule(static)
    for (std::size_t b = 0; b < blocks; ++b) {
      const auto base = node_of_slot(b * block_nodes);
      std::size_t slot = b * block_nodes;
      for (int k = 0; k < block_edge; ++k)
        for (int j = 0; j < block_edge; ++j)
          for (int i = 0; i < block_edge; ++i, ++slot)
            f(slot, std::array<int, 3>{base[0] + i, base[1] + j, base[2] + k});
    }
  }

  // --- Nodal fields ---------------------------------------------------------------------
  // One velocity field by default; with grid contact, one per contact body plus the shared
  // one (mpm/grid_contact.cpp). Field f of slot s is entry f * slot_count() + s of each array.
  std::vector<double> mass;
  std::vector<Vec3> momentum;        // after P2G; divided into velocity by the grid update
  std::vector<Vec3> force;           // internal + external; turned into acceleration
  std::vector<Vec3> velocity;        // v^k (old) after the grid update
  std::vector<Vec3> velocity_new;    // v^{k+1}
  std::vector<Vec3> velocity_remap;  // MUSL: velocity remapped from updated particles
  // Grid contact only: each field's mass gradient sum m grad S (Lian et al. 2013, eq 37) and,
  // along its contact normal, how far its particles reach past the node (eq 42).
  std::vector<Vec3> mass_gradient;
  std::vector<double> reach;
  int field_count() const {
    return fields_;
  }
  // Entries per nodal array: fields x slots.
  std::size_t field_slot_count() const {
    return slot_count() * static_cast<std::size_t>(fields_);
  }

  // Bytes held by nodal storage and directory.
  std::size_t bytes() const;

 private:
  GridSettings settings_;
  int halo_ = 0;
  Vec3 origin_;
  double h_ = 0.0, inv_h_ = 0.0;
  std::array<int, 3> cells_{};
  std::array<int, 3> blocks_{};          // blocks per axis
  std::vector<std::int32_t> directory_;  // block -> active block number, or inactive
  static constexpr std::int32_t inactive = -1, marked = -2;
  std::vector<std::int64_t> active_blocks_;
  // Per-thread scratch, one cache line each so that appends do not false-share.
  struct alignas(64) ThreadBlocks {
    std::vector<std::int64_t> blocks;
  };
  std::vector<ThreadBlocks> thread_blocks_;
  bool keep_remap_ = false;
  int fields_ = 1;
  bool keep_contact_ = false;
  void resize_fields();

 public:
  // The remap field is only stored when a scheme asks for it (MUSL).
  void enable_remap_field(bool on) {
    keep_remap_ = on;
  }
  // Velocity fields per node, and whether the contact arrays are kept (before activate).
  void set_fields(int fields, bool contact) {
    fields_ = fields;
    keep_contact_ = contact;
  }
};

}  // namespace afemp::core
