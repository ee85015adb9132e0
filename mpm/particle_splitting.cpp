// Adaptive multi-axis particle splitting: the MPM paper on explosion and impact in the
// Journal of Harbin Engineering University (2020, issue 8; docs/references.md, item 3),
// eqs 14-17. A particle whose length along an axis reaches 2 alpha l0 (l0 its length there at
// the start, alpha 0.9 by default; eqs 14, 16) splits into two equal halves along that axis,
// along every axis that meets the criterion in the same step: 2, 4 or 8 particles (the seven
// 3-D patterns). Extensive quantities (mass, volume, length along the split axes) are shared
// equally (eqs 15, 17: 0.5, 0.25, 0.125); intensive ones (velocity, stress, strain, plastic
// strain, temperature, specific energy, damage, history: each field's SplitRule in
// mpm/particles.hpp says which it is) are copied, so mass and momentum are
// split exactly and the kinetic and internal energies with them. l0 stays the original
// particle's: a half (length alpha l0 just after the split) splits again only when it has
// doubled in turn, so spacing stays below 2 alpha l0 along every axis. The halves sit at the
// centres of the parent's halves, x +- l_a / 4 along each split axis. A split that would take
// the particle count past max_particles stops the run. The pieces take new ids in the order of
// their parents' ids, over every rank's parents on ranks: the same ids on any rank count. `axes`
// limits the axes a particle may split along (all three by default): a shaped charge's liner splits
// along its jet's axis only (docs/scene-format.md says why). On an axisymmetric grid a ring splits
// along z only, and not within one cell of the axis: there a ring's volume 2 pi r A and its weight
// at the nodes off the axis shrink with r, and the ever lighter pieces that a jet on the axis split
// into ran away (a liner piece at 21 % of copper's density with 2.7 GJ/kg; the stable step fell
// 111-fold at 0.3 mm cells), where the unsplit rings next to them hold (mpm/axisymmetric.hpp).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "core/rank_link.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::split_particles() {
  Particles& p = particles_;
  const core::SplittingSettings& settings = *scene_.mpm.splitting;
  const std::size_t n = p.size();
  // The axes each particle splits along (bit a: axis a), in particle order; the count is an
  // integer sum, the same for any thread count.
  std::vector<std::uint8_t> axes(n, 0);
  const double axis_cell = grid_.cell();
  std::size_t added = 0;
#pragma omp parallel for schedule(static) reduction(+ : added) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    unsigned bits = 0;
    if (!splits_[static_cast<std::size_t>(p.body[i])] ||
        (axisymmetric_ && p.position[i].x < axis_cell)) {
      axes[i] = 0;
      continue;
    }
    for (int a = 0; a < 3; ++a)
      if (settings.axes[static_cast<std::size_t>(a)] &&
          p.length[i][a] >= 2.0 * settings.alpha * p.length0[i][a])
        bits |= 1u << a;
    axes[i] = static_cast<std::uint8_t>(bits);
    added += (std::size_t{1} << std::popcount(bits)) - 1;
  }
  if (added == 0 && ranks_ == nullptr) return;  // on ranks, the others may split
  // The new pieces' ids follow their parents' ids in order, over every rank's parents: the
  // same ids on any rank count (ids in memory order would follow the ranks' partition).
  std::vector<std::int32_t> parents;  // id, then the pieces it adds, of each that splits
  for (std::size_t i = 0; i < n; ++i)
    if (axes[i] != 0) parents.insert(parents.end(), {p.id[i], (1 << std::popcount(axes[i])) - 1});
  std::size_t whole = n;
  if (ranks_) {
    const std::vector<std::vector<std::byte>> every =
        ranks_->gather(core::bytes_of(std::span<const std::int32_t>(parents)));
    parents.clear();
    for (const std::vector<std::byte>& b : every) {
      const std::size_t k = parents.size();
      parents.resize(k + b.size() / sizeof(std::int32_t));
      std::memcpy(parents.data() + k, b.data(), b.size());
    }
    whole = whole_count_;
  }
  std::size_t whole_added = 0;
  for (std::size_t k = 1; k < parents.size(); k += 2)
    whole_added += static_cast<std::size_t>(parents[k]);
  if (whole_added == 0) return;
  if (whole + whole_added > settings.max_particles)
    throw core::SimulationError(
        steps_, time_, "the particles (" + std::to_string(whole) + ")", "particle count",
        "splitting would make " + std::to_string(whole + whole_added) + " particles, more than " +
            "[mpm] splitting max_particles = " + std::to_string(settings.max_particles) +
            "; raise it, or use a coarser start or a larger alpha");
  std::int32_t new_id = next_particle_id();
  if (ranks_) new_id = static_cast<std::int32_t>(ranks_->max_over_ranks(new_id));
  std::vector<std::pair<std::int32_t, std::int32_t>> order;  // parent id, pieces added
  for (std::size_t k = 0; k + 1 < parents.size(); k += 2)
    order.emplace_back(parents[k], parents[k + 1]);
  std::sort(order.begin(), order.end());
  std::unordered_map<std::int32_t, std::int32_t> first_id;  // of a parent's new pieces
  for (const auto& [id, pieces] : order) {
    first_id[id] = new_id;
    new_id += pieces;
  }
  if (ranks_) whole_count_ += whole_added;
  if (added == 0) return;
  p.resize(n + added);  // new entries are filled below from their parent
  const std::size_t hc = p.history_count;
  std::size_t next = n;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned bits = axes[i];
    if (bits == 0) continue;
    const int pieces = 1 << std::popcount(bits);
    const double share = 1.0 / pieces;
    // The parent's halves along the split axes; the parent keeps the first piece and its id.
    Vec3 half = p.length[i];
    for (int a = 0; a < 3; ++a)
      if (bits & (1u << a)) half[a] *= 0.5;
    const Vec3 centre = p.position[i];
    std::int32_t next_id = first_id.at(p.id[i]);
    for (int k = 0; k < pieces; ++k) {
      // Piece k: along the j-th split axis, the lower (bit j of k clear) or upper half.
      Vec3 offset;
      int j = 0;
      for (int a = 0; a < 3; ++a) {
        if (!(bits & (1u << a))) continue;
        offset[a] = ((k >> j) & 1 ? 0.25 : -0.25) * p.length[i][a];
        ++j;
      }
      const std::size_t c = k == 0 ? i : next++;
      if (c != i) {
        p.for_each_field([&](const ParticleField& field, auto& a) {
          using T = typename std::decay_t<decltype(a)>::value_type;
          if (!p.has(field)) return;
          if (field.split == SplitRule::copy) a[c] = a[i];
          if constexpr (std::is_same_v<T, double>)
            if (field.split == SplitRule::share) a[c] = share * a[i];
        });
        p.id[c] = next_id++;
        std::copy_n(p.history.data() + i * hc, hc, p.history.data() + c * hc);
      }
      p.position[c] = centre + offset;
      p.length[c] = half;
    }
    // The parent last: its mass and volume were the pieces' source.
    p.for_each_field([&](const ParticleField& field, auto& a) {
      using T = typename std::decay_t<decltype(a)>::value_type;
      if constexpr (std::is_same_v<T, double>)
        if (field.split == SplitRule::share) a[i] = share * a[i];
    });
    if (!p.half_width.empty()) {
      const double w = gimp_half_width(p.volume[i]);
      p.half_width[i] = w;
      for (std::size_t c = next - static_cast<std::size_t>(pieces - 1); c < next; ++c)
        p.half_width[c] = w;
    }
    ++split_count_;
  }
  if (!fused_kinematics()) velocity_gradient_.resize(p.size());
  reorder_particles();  // the material batches, and locality for the new particles
}

}  // namespace afemp::mpm
