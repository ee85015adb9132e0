// Binning: the cell of every particle, the grid blocks that become active, and the colour
// layers that let the particle-to-grid sweep run in parallel without atomics: particles of
// layer L (cells with index L along the sweep axis) touch nodes L and L + 1 only, so layers
// of equal parity never share a node. Within a layer, particles keep their memory order,
// so every node sums its contributions in the same order for any thread count.
#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::bin_particles() {
  const Particles& p = particles_;
  const std::size_t n = p.size();
  cell_.resize(n);
  layer_.resize(n);
  thread_bad_.assign(static_cast<std::size_t>(core::thread_count()), -1);
  const int axis = sweep_axis_;
#pragma omp parallel
  {
    std::int64_t bad = -1;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& x = p.position[i];
      if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) {
        if (bad < 0) bad = static_cast<std::int64_t>(i);
        cell_[i] = 0;
        layer_[i] = 0;
        continue;
      }
      const auto c = grid_.cell_of(x);
      if (!grid_.inside(c)) {
        if (bad < 0) bad = static_cast<std::int64_t>(i);
        cell_[i] = 0;
        layer_[i] = 0;
        continue;
      }
      cell_[i] = grid_.linear_cell(c);
      layer_[i] = c[static_cast<std::size_t>(axis)];
    }
    thread_bad_[static_cast<std::size_t>(core::thread_index())] = bad;
  }
  raise_if_bad("position");

  grid_.activate(cell_);

  // Counting sort by layer (stable).
  const std::size_t layers = static_cast<std::size_t>(grid_.cells()[static_cast<std::size_t>(axis)]);
  layer_offsets_.assign(layers + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++layer_offsets_[static_cast<std::size_t>(layer_[i]) + 1];
  for (std::size_t l = 0; l < layers; ++l) layer_offsets_[l + 1] += layer_offsets_[l];
  layer_order_.resize(n);
  std::vector<std::int64_t>& next = scratch_offsets_;
  next.assign(layer_offsets_.begin(), layer_offsets_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    layer_order_[static_cast<std::size_t>(next[static_cast<std::size_t>(layer_[i])]++)] =
        static_cast<std::int32_t>(i);
}

}  // namespace afemp::mpm
