#include "core/grid/background_grid.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.hpp"

namespace afemp::core {

BackgroundGrid::BackgroundGrid(const GridSettings& settings, int halo)
    : settings_(settings),
      halo_(halo),
      origin_(settings.min),
      h_(settings.cell),
      inv_h_(1.0 / settings.cell) {
  for (int a = 0; a < 3; ++a) {
    const double extent = settings.max[a] - settings.min[a];
    // A domain that is not a whole number of cells is extended by the remainder.
    cells_[a] = std::max(1, static_cast<int>(std::ceil(extent * inv_h_ - 1e-9)));
    blocks_[a] = (cells_[a] + 1 + 2 * halo_ + block_edge - 1) / block_edge;
  }
  directory_.assign(static_cast<std::size_t>(blocks_[0]) * blocks_[1] * blocks_[2], -1);
}

void BackgroundGrid::activate(std::span<const std::int64_t> cells) {
  for (std::int64_t b : active_blocks_) directory_[static_cast<std::size_t>(b)] = inactive;

  const int nt = thread_count();
  thread_blocks_.resize(static_cast<std::size_t>(nt));
  for (auto& t : thread_blocks_) t.blocks.clear();
  const std::int64_t bx = blocks_[0], by = blocks_[1];
  const std::int64_t n = static_cast<std::int64_t>(cells.size());
#pragma omp parallel if (worth_threads(cells.size()))
  {
    auto& mine = thread_blocks_[static_cast<std::size_t>(thread_index())].blocks;
    std::int64_t last_cell = -1;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t l = cells[static_cast<std::size_t>(p)];
      if (l == last_cell) continue;  // neighbours in memory mostly share a cell
      last_cell = l;
      const auto c = cell_from_linear(l);
      // The cell's nodes and halo, stored nodes c .. c + 1 + 2 halo per axis, lie in one or
      // two blocks per axis.
      int lo[3], nb[3];
      for (int a = 0; a < 3; ++a) {
        lo[a] = c[static_cast<std::size_t>(a)] / block_edge;
        nb[a] = (c[static_cast<std::size_t>(a)] + 1 + 2 * halo_) / block_edge - lo[a] + 1;
      }
      for (int cc = 0; cc < nb[2]; ++cc)
        for (int b = 0; b < nb[1]; ++b)
          for (int a = 0; a < nb[0]; ++a) {
            const std::int64_t blk =
                (static_cast<std::int64_t>(lo[2] + cc) * by + lo[1] + b) * bx + lo[0] + a;
            // Mark the block in the directory so each thread lists it once; two threads
            // may both list it (the marks race benignly through relaxed atomics), which
            // the sort and unique below absorb.
            std::atomic_ref<std::int32_t> mark(directory_[static_cast<std::size_t>(blk)]);
            if (mark.load(std::memory_order_relaxed) == inactive) {
              mark.store(marked, std::memory_order_relaxed);
              mine.push_back(blk);
            }
          }
    }
  }
  active_blocks_.clear();
  for (auto& t : thread_blocks_)
    active_blocks_.insert(active_blocks_.end(), t.blocks.begin(), t.blocks.end());
  std::sort(active_blocks_.begin(), active_blocks_.end());
  active_blocks_.erase(std::unique(active_blocks_.begin(), active_blocks_.end()),
                       active_blocks_.end());
  for (std::size_t i = 0; i < active_blocks_.size(); ++i)
    directory_[static_cast<std::size_t>(active_blocks_[i])] = static_cast<std::int32_t>(i);
  resize_fields();
}

void BackgroundGrid::resize_fields() {
  const std::size_t n = field_slot_count();
  mass.resize(n);
  momentum.resize(n);
  force.resize(n);
  velocity.resize(n);
  velocity_new.resize(n);
  if (keep_remap_) velocity_remap.resize(n);
  if (keep_contact_) {
    mass_gradient.resize(n);
    reach.resize(n);
  }
}

std::array<int, 3> BackgroundGrid::node_of_slot(std::size_t slot) const {
  const std::array<int, 3> b = block_coord(active_blocks_[slot / block_nodes]);
  const int local = static_cast<int>(slot % block_nodes);
  return {b[0] * block_edge + local % block_edge - halo_,
          b[1] * block_edge + (local / block_edge) % block_edge - halo_,
          b[2] * block_edge + local / (block_edge * block_edge) - halo_};
}

std::size_t BackgroundGrid::bytes() const {
  return directory_.capacity() * sizeof(std::int32_t) +
         active_blocks_.capacity() * sizeof(std::int64_t) + mass.capacity() * sizeof(double) +
         (momentum.capacity() + force.capacity() + velocity.capacity() + velocity_new.capacity() +
          velocity_remap.capacity() + mass_gradient.capacity()) *
             sizeof(Vec3) +
         reach.capacity() * sizeof(double);
}

}  // namespace afemp::core
