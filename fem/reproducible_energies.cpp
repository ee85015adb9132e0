// The reproducible mode of the FE step ([run] reproducible = true; docs/parallel.md, "The
// reproducible mode"). The nodes are already the same bits on any rank and thread count (every
// rank moves every node, gathering the element forces in one order: element_division.cpp);
// what was not is the sums over elements and nodes that threads and ranks split: the element
// energies and works, gravity's and the walls' work, the walls' force. Here each of their terms
// goes into an exact sum (core/exact_sum.hpp, after Neal 2015) that does not depend on the
// terms' order, per thread, per rank and over the ranks.
#include <algorithm>

#include "core/rank_link.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

core::ExactSum FeSolver::exact_threads(std::size_t k) const {
  core::ExactSum sum;
  for (std::size_t i = k; i < exact_mirror_.size(); i += core::cache_line_doubles)
    sum += exact_mirror_[i];
  return sum;
}

void FeSolver::clear_exact_threads(std::size_t k) const {
  for (std::size_t i = k; i < exact_mirror_.size(); i += core::cache_line_doubles)
    exact_mirror_[i].clear();
}

void FeSolver::start_exact_sums() {
  const double from[] = {plastic_work_, viscous_work_, hourglass_work_, stabilisation_work_,
                         eroded_energy_};
  for (std::size_t k = 0; k < exact_.size(); ++k) {
    exact_[k].clear();
    exact_[k].add(from[k]);
  }
  exact_body_stabilisation_.assign(body_stabilisation_.size(), core::ExactSum{});
  for (std::size_t b = 0; b < body_stabilisation_.size(); ++b)
    exact_body_stabilisation_[b].add(body_stabilisation_[b]);
}

FeSolver::RankSums FeSolver::exact_rank_sums(bool over_ranks) const {
  std::vector<core::ExactSum> sums(exact_.begin(), exact_.end());
  sums.insert(sums.end(), exact_body_stabilisation_.begin(), exact_body_stabilisation_.end());
  const std::vector<double> v = core::exact_values(over_ranks ? ranks_ : nullptr, sums);
  RankSums r;
  r.plastic = v[exact_plastic];
  r.viscous = v[exact_viscous];
  r.hourglass = v[exact_hourglass];
  r.stabilisation = v[exact_stabilisation];
  r.eroded = v[exact_eroded];
  r.body_stabilisation.assign(v.begin() + static_cast<std::ptrdiff_t>(exact_.size()), v.end());
  return r;
}

core::Energies FeSolver::reproducible_energies() const {
  // energies() with the elements' part exact: each live element's internal energy (this rank's
  // share of the elements), the running sums, then the ranks'. The nodes' part (kinetic
  // energy, momenta, the walls' and contacts' energies, the external work) is summed in node
  // order on every rank alike, as without the mode.
  const std::size_t nb = scene_.bodies.size();
  std::vector<core::ExactSum> sums(1 + exact_.size() + nb);  // internal, the running, bodies
  core::ExactSum* body = sums.data() + 1 + exact_.size();
  for_each_live_element([&](const ElementStore& el, const ElementBatch& b, std::size_t p0) {
    for (int g = 0; g < b.points_per_element; ++g) {
      const std::size_t p = p0 + static_cast<std::size_t>(g);
      const double internal = el.point_mass[p] * el.energy[p];
      sums[0].add(internal);
      body[static_cast<std::size_t>(b.body)].add(internal);
    }
  });
  std::copy(exact_.begin(), exact_.end(), sums.begin() + 1);
  for (std::size_t b = 0; b < nb && b < exact_body_stabilisation_.size(); ++b)
    body[b] += exact_body_stabilisation_[b];
  sums[0] += exact_[exact_stabilisation];
  const std::vector<double> v = core::exact_values(ranks_, sums);
  core::Energies out = nodal_energies();
  out.internal = v[0];
  out.plastic = v[1 + exact_plastic];
  out.viscous = v[1 + exact_viscous];
  out.hourglass = v[1 + exact_hourglass];
  out.stabilisation = v[1 + exact_stabilisation];
  out.eroded = v[1 + exact_eroded];
  for (std::size_t b = 0; b < nb; ++b) out.bodies[b].internal = v[1 + exact_.size() + b];
  return out;
}

}  // namespace afemp::fem
