#include "core/grid/background_grid.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace afemp::core {

BackgroundGrid::BackgroundGrid(const GridSettings& settings)
    : settings_(settings), origin_(settings.min), h_(settings.cell), inv_h_(1.0 / settings.cell) {
  for (int a = 0; a < 3; ++a) {
    const double extent = settings.max[a] - settings.min[a];
    // A domain that is not a whole number of cells is extended by the remainder.
    cells_[a] = std::max(1, static_cast<int>(std::ceil(extent * inv_h_ - 1e-9)));
    blocks_[a] = (cells_[a] + 1 + block_edge - 1) / block_edge;
  }
  directory_.assign(static_cast<std::size_t>(blocks_[0]) * blocks_[1] * blocks_[2], -1);
}

CellWeights BackgroundGrid::weights(const Vec3& x, const std::array<int, 3>& c) const {
  // Local coordinates in [0, 1) along each axis; N = (1 - f) or f per axis (eq 2-5).
  const double fx = (x.x - origin_.x) * inv_h_ - c[0];
  const double fy = (x.y - origin_.y) * inv_h_ - c[1];
  const double fz = (x.z - origin_.z) * inv_h_ - c[2];
  const double wx[2] = {1.0 - fx, fx}, wy[2] = {1.0 - fy, fy}, wz[2] = {1.0 - fz, fz};
  const double dx[2] = {-inv_h_, inv_h_};
  CellWeights r;
  for (int n = 0; n < 8; ++n) {
    const int a = n & 1, b = (n >> 1) & 1, cc = n >> 2;
    r.w[n] = wx[a] * wy[b] * wz[cc];
    r.grad[n] = {dx[a] * wy[b] * wz[cc], wx[a] * dx[b] * wz[cc], wx[a] * wy[b] * dx[cc]};
  }
  return r;
}

void BackgroundGrid::activate(std::span<const std::int64_t> cells) {
  for (std::int64_t b : active_blocks_) directory_[static_cast<std::size_t>(b)] = -1;

  const int nt = thread_count();
  thread_blocks_.resize(static_cast<std::size_t>(nt));
  const std::int64_t bx = blocks_[0], by = blocks_[1];
  const std::int64_t n = static_cast<std::int64_t>(cells.size());
#pragma omp parallel
  {
    auto& mine = thread_blocks_[static_cast<std::size_t>(thread_index())];
    mine.clear();
    std::int64_t last_cell = -1;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t l = cells[static_cast<std::size_t>(p)];
      if (l == last_cell) continue;  // neighbours in memory mostly share a cell
      last_cell = l;
      const auto c = cell_from_linear(l);
      for (int cc = 0; cc < 2; ++cc)
        for (int b = 0; b < 2; ++b)
          for (int a = 0; a < 2; ++a) {
            const std::int64_t blk = ((c[2] + cc) / block_edge * by + (c[1] + b) / block_edge) * bx +
                                     (c[0] + a) / block_edge;
            if (mine.empty() || mine.back() != blk) mine.push_back(blk);
          }
    }
  }
  active_blocks_.clear();
  for (auto& t : thread_blocks_) active_blocks_.insert(active_blocks_.end(), t.begin(), t.end());
  std::sort(active_blocks_.begin(), active_blocks_.end());
  active_blocks_.erase(std::unique(active_blocks_.begin(), active_blocks_.end()),
                       active_blocks_.end());
  for (std::size_t i = 0; i < active_blocks_.size(); ++i)
    directory_[static_cast<std::size_t>(active_blocks_[i])] = static_cast<std::int32_t>(i);
  resize_fields();
}

void BackgroundGrid::resize_fields() {
  const std::size_t n = slot_count();
  mass.resize(n);
  momentum.resize(n);
  force.resize(n);
  velocity.resize(n);
  velocity_new.resize(n);
  if (keep_remap_) velocity_remap.resize(n);
}

void BackgroundGrid::node_slots(const std::array<int, 3>& c,
                                std::array<std::int32_t, 8>& slots) const {
  const std::int64_t bx = blocks_[0], by = blocks_[1];
  int blk[3][2], loc[3][2];
  for (int a = 0; a < 3; ++a)
    for (int o = 0; o < 2; ++o) {
      blk[a][o] = (c[a] + o) / block_edge;
      loc[a][o] = (c[a] + o) % block_edge;
    }
  for (int n = 0; n < 8; ++n) {
    const int a = n & 1, b = (n >> 1) & 1, cc = n >> 2;
    const std::int64_t block = (blk[2][cc] * by + blk[1][b]) * bx + blk[0][a];
    slots[static_cast<std::size_t>(n)] =
        directory_[static_cast<std::size_t>(block)] * block_nodes +
        (loc[2][cc] * block_edge + loc[1][b]) * block_edge + loc[0][a];
  }
}

std::array<int, 3> BackgroundGrid::node_of_slot(std::size_t slot) const {
  const std::int64_t block = active_blocks_[slot / block_nodes];
  const int local = static_cast<int>(slot % block_nodes);
  const std::int64_t bx = blocks_[0], by = blocks_[1];
  const int bi = static_cast<int>(block % bx), bj = static_cast<int>((block / bx) % by),
            bk = static_cast<int>(block / (bx * by));
  return {bi * block_edge + local % block_edge, bj * block_edge + (local / block_edge) % block_edge,
          bk * block_edge + local / (block_edge * block_edge)};
}

std::size_t BackgroundGrid::bytes() const {
  return directory_.capacity() * sizeof(std::int32_t) +
         active_blocks_.capacity() * sizeof(std::int64_t) + mass.capacity() * sizeof(double) +
         (momentum.capacity() + force.capacity() + velocity.capacity() + velocity_new.capacity() +
          velocity_remap.capacity()) *
             sizeof(Vec3);
}

}  // namespace afemp::core
