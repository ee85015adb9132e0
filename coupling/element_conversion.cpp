// Adaptive conversion of hexahedra into particles (AFEMP: Lian et al. 2013, §2.6, the adaptive
// FE-MPM of Zhang et al.; Ma 2005, §3.3). An element the FE solver retired (its body's
// `conversion` criteria met inside the grid: fem/element_retirement.cpp) becomes n x n x n
// particles (n = 1: the centroid; n = 2: the 2 x 2 x 2 Gauss points xi = +-1/sqrt(3)), each
// with mass m_e / n^3, the integration-point state (stress, plastic strain, temperature,
// specific internal energy, damage, accumulated strain, history), volume m / rho and the velocity
// sum_a N_a(xi) v_a interpolated from the element's nodes.
// Exactness: the lumped mass gives each node m_e / 8 of the element, and for both point sets
// sum_p (m_e / n^3) N_a(xi_p) = m_e / 8 (the centroid has N_a = 1/8; the Gauss rule integrates
// the trilinear N_a exactly), so the particles carry exactly the mass and momentum the nodes
// lose when their masses are recomputed from the live elements. A node left with no element
// has handed its whole mass and momentum to the particles this way. The kinetic energy the
// interpolation loses (Jensen: never negative) is booked as `converted` energy.
#include "coupling/element_conversion.hpp"

#include <cmath>

#include "fem/mesh.hpp"

namespace afemp::coupling {

Conversion convert_element(const fem::FeSolver& fe, const core::Scene& scene,
                           const fem::RetiredElement& ev) {
  const fem::HexElements& el = fe.hexahedra();
  const fem::FeNodes& nodes = fe.nodes();
  Conversion c;
  const int points = scene.bodies[static_cast<std::size_t>(ev.body)].conversion->points;
  c.particles = points * points * points;
  const std::size_t e = ev.element;
  const fem::ElementBatch* batch = &fem::batch_of(el, e);
  const int ppe = batch->points_per_element;
  const std::size_t p0 = batch->point_begin + (e - batch->begin) * static_cast<std::size_t>(ppe);
  fem::HexVectors x, v;
  double kinetic_before = 0.0, internal_before = 0.0;
  for (std::size_t a = 0; a < 8; ++a) {
    const auto i = static_cast<std::size_t>(el.nodes[e][a]);
    x[a] = nodes.position[i];
    v[a] = nodes.velocity[i];
    kinetic_before += 0.5 * (el.mass[e] / 8.0) * core::dot(v[a], v[a]);
  }
  for (int g = 0; g < ppe; ++g)
    internal_before += el.point_mass[p0 + static_cast<std::size_t>(g)] *
                       el.energy[p0 + static_cast<std::size_t>(g)];

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
      if (!el.strain.empty()) q.strain = el.strain[p];
      q.history.assign(
          el.history.begin() + static_cast<std::ptrdiff_t>(p * el.history_count),
          el.history.begin() + static_cast<std::ptrdiff_t>((p + 1) * el.history_count));
      return el.density[p];
    }
    double m = 0.0, volume = 0.0;
    q.history.assign(el.history_count, 0.0);
    for (int h = 0; h < ppe; ++h) {
      const std::size_t p = p0 + static_cast<std::size_t>(h);
      const double w = el.point_mass[p];
      for (std::size_t k = 0; k < el.history_count; ++k)
        q.history[k] += w * el.history[p * el.history_count + k];
      m += w;
      q.stress += w * el.stress[p];
      q.plastic_strain += w * el.plastic_strain[p];
      q.temperature += w * el.temperature[p];
      q.energy += w * el.energy[p];
      q.damage += w * el.damage[p];
      if (!el.strain.empty()) q.strain += w * el.strain[p];
      volume += w / el.density[p];
    }
    q.stress = (1.0 / m) * q.stress;
    q.plastic_strain /= m;
    q.temperature /= m;
    q.energy /= m;
    q.damage /= m;
    q.strain = (1.0 / m) * q.strain;
    for (double& value : q.history) value /= m;
    return m / volume;
  };

  const int n = c.particles == 1 ? 1 : 2;
  const double mass = el.mass[e] / c.particles;
  double kinetic_after = 0.0, internal_after = 0.0;
  const double r = n == 1 ? 0.0 : 1.0 / std::sqrt(3.0);
  for (int g = 0; g < c.particles; ++g) {
    ConvertedPoint q;
    for (std::size_t a = 0; a < 8; ++a) {
      double shape = 1.0 / 8.0;
      for (int d = 0; d < 3; ++d)
        shape *= 1.0 + r * fem::kHexNatural[g][d] * fem::kHexNatural[a][d];
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
    c.points.push_back(q);
  }
  c.lost_energy = kinetic_before + internal_before - kinetic_after - internal_after;
  c.kinetic_before = kinetic_before;
  c.kinetic_after = kinetic_after;
  return c;
}

}  // namespace afemp::coupling
