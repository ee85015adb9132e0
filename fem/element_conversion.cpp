// Adaptive conversion of hexahedra into particles (AFEMP: Lian et al. 2013, §2.6, the adaptive
// FE-MPM of Zhang et al.; Ma 2005, §3.3). An element of a body with `conversion` that lies inside
// the background grid and meets a criterion (plastic strain, damage, |V / V0 - 1|, the smallest
// scaled corner Jacobian, its critical step against the grid's h / c, or inversion) leaves the
// mesh and becomes n x n x n particles (n = 1: the centroid; n = 2: the 2 x 2 x 2 Gauss points
// xi = +-1/sqrt(3)), each with mass m_e / n^3, the integration-point state (stress, plastic
// strain, temperature, specific internal energy, damage), volume m / rho and the velocity
// sum_a N_a(xi) v_a interpolated from the element's nodes.
// Exactness: the lumped mass gives each node m_e / 8 of the element, and for both point sets
// sum_p (m_e / n^3) N_a(xi_p) = m_e / 8 (the centroid has N_a = 1/8; the Gauss rule integrates
// the trilinear N_a exactly), so the particles carry exactly the mass and momentum the nodes
// lose when their masses are recomputed from the live elements. A node left with no element
// has handed its whole mass and momentum to the particles this way. The kinetic energy the
// interpolation loses (Jensen: never negative) is booked as `converted` energy.
#include <algorithm>
#include <cmath>

#include "core/materials/material.hpp"
#include "fem/fe_solver.hpp"
#include "fem/mesh_quality.hpp"

namespace afemp::fem {

bool FeSolver::inside_grid(std::size_t e) const {
  if (!scene_.has_grid) return false;
  const core::GridSettings& g = scene_.mpm.grid;
  for (std::size_t a = 0; a < 8; ++a) {
    const Vec3& x = nodes_.position[static_cast<std::size_t>(hexes_.nodes[e][a])];
    for (int k = 0; k < 3; ++k)
      if (!(x[k] >= g.min[k] && x[k] <= g.max[k])) return false;  // its points are inside
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

void FeSolver::collect_conversions() {
  HexElements& el = hexes_;
  for (std::size_t t = 0; t < thread_conversions_.size(); ++t) {
    for (std::size_t k = 0; k < thread_conversions_[t].size(); ++k) {
      const std::size_t e = thread_conversions_[t][k];
      const ElementBatch* batch = &batch_of(el, e);
      const int n = scene_.bodies[static_cast<std::size_t>(batch->body)].conversion->points;
      ConversionEvent ev;
      ev.time = time_;
      ev.element = e;
      ev.id = static_cast<std::int64_t>(e - batch->begin);
      ev.body = batch->body;
      ev.reason = thread_conversion_reason_[t][k];
      ev.particles = n * n * n;
      ev.mass = el.mass[e];
      conversion_events_.push_back(ev);
      for (std::size_t a = 0; a < 8; ++a) converted_node_[static_cast<std::size_t>(el.nodes[e][a])] = 1;
      el.alive[e] = 0;
      el.bulk_q[e] = 0.0;
      erosion_this_step_ = true;  // node masses are recomputed at the end of the step
    }
    thread_conversions_[t].clear();
    thread_conversion_reason_[t].clear();
  }
}

std::vector<ConvertedPoint> FeSolver::take_converted_points() {
  std::vector<ConvertedPoint> out;
  run_stage(FeStageKind::conversion, [&] { out = make_converted_points(); });
  return out;
}

std::vector<ConvertedPoint> FeSolver::make_converted_points() {
  // Built when taken, from the nodes' final v^{n+1/2}: in a coupled step the grid sets the
  // bonded nodes' velocity after the element update that flagged the conversion.
  std::vector<ConvertedPoint> out;
  const HexElements& el = hexes_;
  for (std::size_t k = converted_taken_; k < conversion_events_.size(); ++k) {
    ConversionEvent& ev = conversion_events_[k];
    const std::size_t e = ev.element;
    const ElementBatch* batch = &batch_of(el, e);
    const int ppe = batch->points_per_element;
    const std::size_t p0 = batch->point_begin + (e - batch->begin) * static_cast<std::size_t>(ppe);
    HexVectors x, v;
    double kinetic_before = 0.0, internal_before = 0.0;
    for (std::size_t a = 0; a < 8; ++a) {
      const auto i = static_cast<std::size_t>(el.nodes[e][a]);
      x[a] = nodes_.position[i];
      v[a] = nodes_.velocity[i];
      kinetic_before += 0.5 * (el.mass[e] / 8.0) * core::dot(v[a], v[a]);
    }
    for (int g = 0; g < ppe; ++g)
      internal_before += el.point_mass[p0 + static_cast<std::size_t>(g)] * el.energy[p0 + static_cast<std::size_t>(g)];

    // The state a particle inherits from integration point g (or the mass-weighted mean of
    // all points when one particle replaces a fully integrated element).
    auto state_of = [&](int g, ConvertedPoint& q) {
      if (g >= 0) {
        const std::size_t p = p0 + static_cast<std::size_t>(g);
        q.stress = el.stress[p];
        q.plastic_strain = el.plastic_strain[p];
        q.temperature = el.temperature[p];
        q.energy = el.energy[p];
        q.damage = el.damage[p];
        q.max_compaction = el.max_compaction[p];
        q.history.assign(el.history.begin() + static_cast<std::ptrdiff_t>(p * el.history_count),
                         el.history.begin() + static_cast<std::ptrdiff_t>((p + 1) * el.history_count));
        return el.density[p];
      }
      double m = 0.0, volume = 0.0;
      q.history.assign(el.history_count, 0.0);
      for (int h = 0; h < ppe; ++h) {
        const std::size_t p = p0 + static_cast<std::size_t>(h);
        const double w = el.point_mass[p];
        for (std::size_t v = 0; v < el.history_count; ++v)
          q.history[v] += w * el.history[p * el.history_count + v];
        m += w;
        q.stress += w * el.stress[p];
        q.plastic_strain += w * el.plastic_strain[p];
        q.temperature += w * el.temperature[p];
        q.energy += w * el.energy[p];
        q.damage += w * el.damage[p];
        q.max_compaction += w * el.max_compaction[p];
        volume += w / el.density[p];
      }
      q.stress = (1.0 / m) * q.stress;
      q.plastic_strain /= m;
      q.temperature /= m;
      q.energy /= m;
      q.damage /= m;
      q.max_compaction /= m;
      for (double& v : q.history) v /= m;
      return m / volume;
    };

    const int n = ev.particles == 1 ? 1 : 2;
    const double mass = el.mass[e] / ev.particles;
    double kinetic_after = 0.0, internal_after = 0.0;
    const double r = n == 1 ? 0.0 : 1.0 / std::sqrt(3.0);
    for (int g = 0; g < ev.particles; ++g) {
      ConvertedPoint q;
      for (std::size_t a = 0; a < 8; ++a) {
        double shape = 1.0 / 8.0;
        for (int d = 0; d < 3; ++d) shape *= 1.0 + r * kHexNatural[g][d] * kHexNatural[a][d];
        q.position += shape * x[a];
        q.velocity += shape * v[a];
      }
      // Gauss point g is nearest node g, as in fem/hexahedron_full.hpp.
      const double density = state_of(ppe == 1 ? 0 : (n == 2 ? g : -1), q);
      q.mass = mass;
      q.volume = mass / density;
      q.body = batch->body;
      q.material = batch->material;
      kinetic_after += 0.5 * mass * core::dot(q.velocity, q.velocity);
      internal_after += mass * q.energy;
      out.push_back(q);
    }
    converted_energy_ += kinetic_before + internal_before - kinetic_after - internal_after;
    ev.kinetic_before = kinetic_before;
    ev.kinetic_after = kinetic_after;
  }
  converted_taken_ = conversion_events_.size();
  return out;
}

std::vector<ConversionEvent> FeSolver::take_conversion_events() {
  std::vector<ConversionEvent> out(conversion_events_.begin(),
                                   conversion_events_.begin() + static_cast<std::ptrdiff_t>(converted_taken_));
  conversion_events_.erase(conversion_events_.begin(),
                           conversion_events_.begin() + static_cast<std::ptrdiff_t>(converted_taken_));
  converted_taken_ = 0;
  return out;
}

}  // namespace afemp::fem
