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
// the particle count past max_particles stops the run. `axes` limits the axes a particle may
// split along (all three by default): a shaped charge's liner splits along its jet's axis only
// (docs/scene-format.md says why).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::split_particles() {
  Particles& p = particles_;
  const core::SplittingSettings& settings = *scene_.mpm.splitting;
  const std::size_t n = p.size();
  // The axes each particle splits along (bit a: axis a), in particle order; the count is an
  // integer sum, the same for any thread count.
  std::vector<std::uint8_t> axes(n, 0);
  std::size_t added = 0;
#pragma omp parallel for schedule(static) reduction(+ : added) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i) {
    unsigned bits = 0;
    if (!splits_[static_cast<std::size_t>(p.body[i])]) {
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
  if (added == 0) return;
  if (n + added > settings.max_particles)
    throw core::SimulationError(
        steps_, time_, "the particles (" + std::to_string(n) + ")", "particle count",
        "splitting would make " + std::to_string(n + added) + " particles, more than " +
            "[mpm] splitting max_particles = " + std::to_string(settings.max_particles) +
            "; raise it, or use a coarser start or a larger alpha");
  std::int32_t next_id = next_particle_id();
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
