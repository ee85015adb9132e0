// Loads on particles ([[loads]], core::LoadSpec): a total force F shared among the particles
// of a body that start inside a box, in proportion to their mass, f_p = m_p F / M. A particle
// carries no surface of its own, so the load is given as its total, as Uintah's pressure
// loads (the force over the particles of a region) and CB-Geo's particle tractions are; on a
// layer of equal particles at a flat face it is a uniform traction F / A. It enters the grid as
// a body force does, f_I += N_I(x_p) f_p (the external force's nodal share in Sulsky, Chen
// & Schreyer 1994), at each step's start time with the load's curve, and its work over the step is
// f_p . sum_I N_I (v_I + v_I^new) / 2 dt, the work of the nodal forces at the nodes' mean
// velocity (as gravity's is booked, grid_momentum_update.cpp). A particle that splits hands
// the load on to its pieces by mass; one that leaves through an outflow face takes its share
// out of the total. In the reproducible mode the nodal shares go into the grid's fixed-point
// force sums (reproducible_sums.cpp, whose force bound counts them) and the work into an exact
// sum, so that neither depends on the particles' order or rank.
#include <algorithm>
#include <cmath>

#include "afemp/errors.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::mpm {

void MpmSolver::setup_particle_loads() {
  Particles& p = particles_;
  for (std::size_t k = 0; k < scene_.loads.size(); ++k) {
    const core::LoadSpec& l = scene_.loads[k];
    if (scene_.bodies[static_cast<std::size_t>(l.body)].discretisation !=
        core::Discretisation::particles)
      continue;  // hexahedra: fem/surface_loads.cpp
    if (load_acceleration_.empty()) p.keep(&Particles::load, std::int32_t{0});
    load_acceleration_.resize(k + 1);
    double mass = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.body[i] != l.body) continue;
      bool inside = true;
      for (int a = 0; a < 3; ++a)
        inside =
            inside && p.position[i][a] >= l.region.min[a] && p.position[i][a] <= l.region.max[a];
      if (!inside) continue;
      if (p.load[i] != 0)
        throw core::InputError(l.where, "particles",
                               "particle " + std::to_string(p.id[i]) + " of body \"" +
                                   scene_.bodies[static_cast<std::size_t>(l.body)].name +
                                   "\" lies in the boxes of [[loads]] entries " +
                                   std::to_string(p.load[i]) + " and " + std::to_string(k + 1) +
                                   "; a particle shares one load (give one load the sum)");
      p.load[i] = static_cast<std::int32_t>(k + 1);
      mass += p.mass[i];
    }
    if (!(mass > 0.0))
      throw core::InputError(l.where, "particles",
                             "the box holds no particle of body \"" +
                                 scene_.bodies[static_cast<std::size_t>(l.body)].name + "\"");
    load_acceleration_[k] = (1.0 / mass) * l.value;
  }
}

void MpmSolver::add_particle_loads() {
  core::BackgroundGrid& g = grid_;
  const Particles& p = particles_;
  std::vector<Vec3> a(load_acceleration_.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    a[k] = core::curve_factor(scene_.loads[k].curve, time_) * load_acceleration_[k];
  FixedNodes* fixed = reproducible() ? &fixed_ : nullptr;
  bool ok = true;
  // Serial: the loaded particles are few (a face's layer), and the sums keep their order.
  with_stencil([&]<class Stencil, bool>() {
    typename Stencil::Slots slot{};
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.load[i] == 0) continue;
      const Vec3 f = p.mass[i] * a[static_cast<std::size_t>(p.load[i] - 1)];
      const Stencil st(g, p, i, p.position[i]);
      st.slots(g, slot);
      const std::size_t field = field_offset(i);
      for (int n = 0; n < Stencil::nodes; ++n) {
        const std::size_t k = static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field;
        const Vec3 share = st.w(n) * f;
        if (!fixed) {
          g.force[k] += share;
          continue;
        }
        for (std::size_t c = 0; c < 3; ++c)
          fixed->force[3 * k + c] +=
              core::to_fixed(share[static_cast<int>(c)], fixed->force_scale, ok);
      }
    }
  });
  if (!ok) fixed_ok_[0] = 0;
}

double MpmSolver::largest_particle_load(std::size_t i) const {
  const Particles& p = particles_;
  if (load_acceleration_.empty() || p.load[i] == 0) return 0.0;
  const auto k = static_cast<std::size_t>(p.load[i] - 1);
  const Vec3 a = core::curve_factor(scene_.loads[k].curve, time_) * load_acceleration_[k];
  return p.mass[i] * std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
}

void MpmSolver::book_particle_load_work(double dt) {
  const core::BackgroundGrid& g = grid_;
  const Particles& p = particles_;
  double work = 0.0;
  core::ExactSum* exact = reproducible() ? &exact_[exact_external] : nullptr;
  with_stencil([&]<class Stencil, bool>() {
    typename Stencil::Slots slot{};
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.load[i] == 0) continue;
      const auto k = static_cast<std::size_t>(p.load[i] - 1);
      const Vec3 f =
          (p.mass[i] * core::curve_factor(scene_.loads[k].curve, time_)) * load_acceleration_[k];
      const Stencil st(g, p, i, p.position[i]);
      st.slots(g, slot);
      const std::size_t field = field_offset(i);
      Vec3 mean;
      for (int n = 0; n < Stencil::nodes; ++n) {
        const std::size_t s = static_cast<std::size_t>(slot[static_cast<std::size_t>(n)]) + field;
        mean += (0.5 * st.w(n)) * (g.velocity[s] + g.velocity_new[s]);
      }
      work += core::dot(f, mean) * dt;
      if (exact) exact->add(core::dot(f, mean) * dt);
    }
  });
  external_work_ += work;
}

}  // namespace afemp::mpm
