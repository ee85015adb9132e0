// Retirement of hexahedra: an element of a body with `conversion` that lies inside the
// retirement domain (the background grid, set by coupling/) and meets a criterion (plastic
// strain, damage, |V / V0 - 1|, the smallest scaled corner Jacobian, its critical step against
// the domain's h / c, or inversion) leaves the mesh without eroding: its state stays in the
// arrays for the caller, which makes particles of it (AFEMP: coupling/element_conversion.cpp,
// Lian et al. 2013, §2.6), and its nodes' masses follow the live elements.
#include <algorithm>
#include <cmath>

#include "core/grid/grid_face_margin.hpp"
#include "fem/fe_solver.hpp"
#include "fem/mesh_quality.hpp"

namespace afemp::fem {

void FeSolver::set_retirement_domain(const RetirementDomain& domain) {
  retirement_ = domain;
  // Only the hexahedra of a converting body retire: without one, the domain stays unset and
  // the step (and on ranks the retirements' exchange) skips them.
  bool converts = false;
  for (const core::BodySpec& body : scene_.bodies) converts = converts || body.conversion;
  retirement_.set = domain.set && converts;
}

bool FeSolver::inside_retirement_domain(std::size_t e) const {
  if (!retirement_.set) return false;
  // A node on the domain's face (a mesh on the grid's wall face) counts as inside within a
  // round-off margin (core/grid/grid_face_margin.hpp).
  const double margin = core::kGridFaceMargin * retirement_.cell;
  for (std::size_t a = 0; a < 8; ++a) {
    const Vec3& x = nodes_.position[static_cast<std::size_t>(hexes_.nodes[e][a])];
    for (int k = 0; k < 3; ++k)
      if (!(x[k] >= retirement_.min[k] - margin && x[k] <= retirement_.max[k] + margin))
        return false;  // its points are inside
  }
  return true;
}

const char* FeSolver::conversion_reason(const core::ConversionSettings& c, const ElementBatch& b,
                                        std::size_t e, double volume, double grid_step) const {
  const HexElements& el = hexes_;
  const std::size_t p0 =
      b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element);
  double eps_p = 0.0, damage = 0.0;
  for (int g = 0; g < b.points_per_element; ++g) {
    eps_p = std::max(eps_p, el.plastic_strain[p0 + static_cast<std::size_t>(g)]);
    damage = std::max(damage, el.damage[p0 + static_cast<std::size_t>(g)]);
  }
  if (c.plastic_strain > 0.0 && eps_p >= c.plastic_strain) return "plastic strain";
  if (c.damage > 0.0 && damage >= c.damage) return "damage";
  if (c.volumetric_strain > 0.0 && std::abs(volume / el.volume0[e] - 1.0) >= c.volumetric_strain)
    return "volumetric strain";
  if (c.time_step_fraction > 0.0 && el.critical_dt[e] < c.time_step_fraction * grid_step)
    return "time step";
  if (c.jacobian_ratio > 0.0) {
    std::array<Vec3, 8> x;
    for (std::size_t a = 0; a < 8; ++a)
      x[a] = nodes_.position[static_cast<std::size_t>(el.nodes[e][a])];
    if (hexahedron_quality(x).min_scaled_jacobian < c.jacobian_ratio) return "Jacobian ratio";
  }
  return nullptr;
}

void FeSolver::collect_retirements() {
  HexElements& el = hexes_;
  for (std::size_t t = 0; t < thread_conversions_.size(); ++t) {
    for (std::size_t k = 0; k < thread_conversions_[t].size(); ++k) {
      const std::size_t e = thread_conversions_[t][k];
      const ElementBatch* batch = &batch_of(el, e);
      RetiredElement ev;
      ev.time = time_;
      ev.element = e;
      ev.id = static_cast<std::int64_t>(e - batch->begin);
      ev.body = batch->body;
      ev.reason = thread_conversion_reason_[t][k];
      retired_.push_back(ev);
      for (std::size_t a = 0; a < 8; ++a)
        converted_node_[static_cast<std::size_t>(el.nodes[e][a])] = 1;
      el.alive[e] = 0;
      el.bulk_q[e] = 0.0;
      erosion_this_step_ = true;  // node masses are recomputed at the end of the step
    }
    thread_conversions_[t].clear();
    thread_conversion_reason_[t].clear();
  }
}

std::vector<RetiredElement> FeSolver::take_retired_elements() {
  std::vector<RetiredElement> out;
  out.swap(retired_);
  return out;
}

}  // namespace afemp::fem
