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

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "fem/mesh.hpp"

namespace afemp::coupling {

namespace {

// Calls f(from, to, width) for each point array of the hexahedra that a particle takes
// (fem::PointField::convert, fem/element_store.hpp) with the particles' array of the same name
// (the history: their history store), width values per point; an array either side does not
// keep is left out.
template <class F>
void for_each_converted_field(const fem::HexElements& el, mpm::Particles& p, F&& f) {
  fem::for_each_point_field(
      el, [&](const fem::PointField& field, const auto& from, std::size_t width) {
        using T = typename std::decay_t<decltype(from)>::value_type;
        if (!field.convert || from.empty()) return;
        if constexpr (std::is_same_v<T, double>) {
          if (&from == &el.history) {
            f(from, p.history, width);
            return;
          }
        }
        bool named = false;
        p.for_each_field([&](const mpm::ParticleField& to_field, auto& to) {
          using U = typename std::decay_t<decltype(to)>::value_type;
          if constexpr (std::is_same_v<T, U>) {
            if (std::strcmp(to_field.name, field.name) != 0) return;
            named = true;
            if (p.has(to_field)) f(from, to, width);
          }
        });
        if (!named)
          throw std::logic_error(std::string("element point field ") + field.name +
                                 " has no particle field of its name and type");
      });
}

}  // namespace

Conversion convert_element(const fem::FeSolver& fe, const core::Scene& scene,
                           const fem::RetiredElement& ev, mpm::Particles& out) {
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

  // Particle j inherits the state of integration point g (or the mass-weighted mean of all
  // points when one particle replaces a fully integrated element); its density gives its
  // volume.
  auto state_of = [&](int g, std::size_t j) {
    if (g >= 0) {
      const std::size_t p = p0 + static_cast<std::size_t>(g);
      for_each_converted_field(el, out, [&](const auto& from, auto& to, std::size_t width) {
        std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(p * width), width,
                    to.begin() + static_cast<std::ptrdiff_t>(j * width));
      });
      return el.density[p];
    }
    double m = 0.0, volume = 0.0;
    for (int h = 0; h < ppe; ++h) {
      const std::size_t p = p0 + static_cast<std::size_t>(h);
      m += el.point_mass[p];
      volume += el.point_mass[p] / el.density[p];
    }
    for_each_converted_field(el, out, [&](const auto& from, auto& to, std::size_t width) {
      using T = typename std::decay_t<decltype(from)>::value_type;
      for (std::size_t k = 0; k < width; ++k) {
        T sum{};
        for (int h = 0; h < ppe; ++h) {
          const std::size_t p = p0 + static_cast<std::size_t>(h);
          sum += el.point_mass[p] * from[p * width + k];
        }
        if constexpr (std::is_same_v<T, double>)
          to[j * width + k] = sum / m;
        else
          to[j * width + k] = (1.0 / m) * sum;
      }
    });
    return m / volume;
  };

  const int n = c.particles == 1 ? 1 : 2;
  const double mass = el.mass[e] / c.particles;
  double kinetic_after = 0.0, internal_after = 0.0;
  const double r = n == 1 ? 0.0 : 1.0 / std::sqrt(3.0);
  for (int g = 0; g < c.particles; ++g) {
    core::Vec3 position, velocity;
    for (std::size_t a = 0; a < 8; ++a) {
      double shape = 1.0 / 8.0;
      for (int d = 0; d < 3; ++d)
        shape *= 1.0 + r * fem::kHexNatural[g][d] * fem::kHexNatural[a][d];
      position += shape * x[a];
      velocity += shape * v[a];
    }
    const std::size_t j = out.size();
    out.push_back(position, velocity, mass, 0.0, 0.0, batch->body, batch->material);
    // Gauss point g is nearest node g, as in fem/hexahedron_full.hpp.
    const double density = state_of(ppe == 1 ? 0 : (n == 2 ? g : -1), j);
    out.volume[j] = mass / density;
    kinetic_after += 0.5 * mass * core::dot(velocity, velocity);
    internal_after += mass * out.energy[j];
  }
  c.lost_energy = kinetic_before + internal_before - kinetic_after - internal_after;
  c.kinetic_before = kinetic_before;
  c.kinetic_after = kinetic_after;
  return c;
}

}  // namespace afemp::coupling
