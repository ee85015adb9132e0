// Element erosion: an element that meets one of its body's criteria (equivalent plastic
// strain, the material's failure strain, volume ratio, critical time step, or inversion) is
// removed; its internal energy and the kinetic energy of its share of the node masses leave with
// it, booked as eroded energy and written in its erosion.csv record, so the records add up to
// the eroded energy. The plastic work and bulk-viscous heat it had taken (part of that internal
// energy) leave the plastic and viscous totals, which so stay the live material's. Node masses are
// then recomputed from the live elements (one source of truth), and nodes left with no element drop
// out of the update, with a record of their own that reports their mass and kinetic energy (already
// counted in their elements' records). Retired elements (element_retirement.cpp) share the mass
// recomputation.
#include <algorithm>
#include <span>

#include "fem/fe_solver.hpp"

namespace afemp::fem {

const ElementBatch& batch_of(const ElementStore& elements, std::size_t e) {
  for (const ElementBatch& b : elements.batches)
    if (e >= b.begin && e < b.end) return b;
  return elements.batches.back();  // not reached: the batches cover every element
}

void FeSolver::collect_erosions(ElementSet& set) {
  ElementStore& el = set.store();
  const std::span<const std::int32_t> nodes = set.connectivity();
  const auto corners = static_cast<std::size_t>(set.corners());
  for (std::size_t t = 0; t < thread_erosions_.size(); ++t) {
    for (std::size_t k = 0; k < thread_erosions_[t].size(); ++k) {
      const std::size_t e = thread_erosions_[t][k];
      const ElementBatch* batch = &batch_of(el, e);
      const std::size_t p0 =
          batch->point_begin +
          (e - batch->begin) * static_cast<std::size_t>(batch->points_per_element);
      double energy = 0.0;
      for (int g = 0; g < batch->points_per_element; ++g) {
        const std::size_t p = p0 + static_cast<std::size_t>(g);
        energy += el.point_mass[p] * el.energy[p];
        // Its dissipated work leaves the live totals with it (it is in its internal energy,
        // now eroded).
        if (!el.plastic_heat.empty()) {
          plastic_work_ -= el.point_mass[p] * el.plastic_heat[p];
          viscous_work_ -= el.point_mass[p] * el.viscous_heat[p];
          if (reproducible()) {
            exact_[exact_plastic].add(-(el.point_mass[p] * el.plastic_heat[p]));
            exact_[exact_viscous].add(-(el.point_mass[p] * el.viscous_heat[p]));
          }
        }
      }
      // The element's mass leaves its nodes (a lumped share each) at their velocity v^{n+1/2}.
      for (std::size_t a = 0; a < corners; ++a) {
        const Vec3& v = nodes_.velocity[static_cast<std::size_t>(nodes[corners * e + a])];
        energy += 0.5 * (el.mass[e] / static_cast<double>(corners)) * core::dot(v, v);
      }
      el.alive[e] = 0;
      eroded_energy_ += energy;
      if (reproducible()) exact_[exact_eroded].add(energy);
      events_.push_back({time_, set.kind(), static_cast<std::int64_t>(e - batch->begin),
                         batch->body, thread_failure_[t][k], energy, el.mass[e], e});
      erosion_this_step_ = true;
    }
    set.eroded(thread_erosions_[t]);
    thread_erosions_[t].clear();
    thread_failure_[t].clear();
  }
}

void FeSolver::finish_erosion() {
  erosion_this_step_ = false;
  const std::vector<double> before = nodes_.mass;
  recompute_node_masses();
  for (auto& ev : events_)
    if (ev.time < time_) ev.time = time_;  // stamped with the end of the step they happened in
  for (auto& ev : retired_)
    if (ev.time < time_) ev.time = time_;
  // A dropped node's row reports the mass and kinetic energy it leaves the update with; both
  // are already in its elements' rows (and in the eroded energy), so the rows of kind "node"
  // are not added to them.
  // A node whose last element converted handed its mass to the particles: no erosion row.
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (before[i] > 0.0 && nodes_.mass[i] == 0.0 && !converted_node_[i]) {
      const Vec3& v = nodes_.velocity[i];
      events_.push_back({time_, "node", static_cast<std::int64_t>(i), nodes_.body[i],
                         "no element left", 0.5 * before[i] * core::dot(v, v), before[i], i});
    }
  std::fill(converted_node_.begin(), converted_node_.end(), 0);
  // Eroding contact: the surfaces now include the faces the lost elements exposed.
  for (MeshContact& c : contacts_) rebuild_surfaces(c, scene_, sets_, nodes_);
}

}  // namespace afemp::fem
