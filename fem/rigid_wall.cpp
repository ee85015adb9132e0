// Rigid planar walls for FE nodes (the kinematic wall of LS-DYNA's *RIGIDWALL_PLANAR): a node
// whose predicted position x + dt v would lie behind the wall gets the normal velocity that
// puts it on the wall at the end of the step; Coulomb friction limits the tangential impulse
// to mu times the normal one (stick below it, slide with the reduced velocity above it). A
// moving wall does work m dv . v_wall on the nodes, which goes to the external work; the
// kinetic energy a wall takes from arriving nodes is the wall energy (below). Imposed velocity
// components (constraints) are never changed by a wall. The
// wall's force on the nodes is the impulse it gave them over the step dt^n.
// Energy: what a wall takes from the motion is booked as the wall energy (Energies::wall,
// LS-DYNA's rigid-wall energy): minus the work of its impulses J on the nodes, taken as the
// element forces' work is in the central difference (J / dt^n over the motion
// dt^{n-1/2} v^{n-1/2} + dt^{n+1/2} v^{n+1/2}, halved: what the sliding energy of the mesh
// contacts does; on the first step, from the initial velocity, J . (v^0 + v^{1/2}) / 2), plus
// what a moving wall put in as external work. A node arriving at u loses
// m u^2 / 2 to it; a node resting on the wall under a load, none.
#include <cmath>
#include <cstdint>

#include "core/contact_impulse.hpp"
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

void FeSolver::apply_walls(double dt) {
  for (std::size_t wi = 0; wi < walls_.size(); ++wi) {
    const WallState& w = walls_[wi];
    const core::WallSpec& s = w.spec;
    const Vec3 wall_point = s.point + (time_ + dt) * s.velocity;
    const std::size_t n = w.nodes.size();
    std::fill(thread_sums_.begin(), thread_sums_.end(), 0.0);
    for (core::ExactSum& e : exact_mirror_) e.clear();
    const double dt_force = force_step(dt);
    const double before_dt = motion_before_step(dt);
    auto sweep = [&](std::size_t begin, std::size_t end, int t) {
      double work = 0.0, done = 0.0;
      Vec3 impulse;
      for (std::size_t k = begin; k < end; ++k) {
        const auto i = static_cast<std::size_t>(w.nodes[k]);
        const double m = nodes_.mass[i];
        if (!(m > 0.0)) continue;
        // Constraints win over walls: the wall moves only the free components, so a node on a
        // symmetry plane normal to the wall is still held by it. free_normal is the wall
        // normal with the imposed components removed; along it the gap closes.
        const std::uint8_t imposed = nodes_.imposed[i];
        Vec3 free_normal = s.normal;
        for (int a = 0; a < 3; ++a)
          if (imposed & (1u << a)) free_normal[a] = 0.0;
        const double reach = core::dot(free_normal, s.normal);
        if (reach < 1e-12) continue;  // the normal lies in imposed components
        Vec3& v = nodes_.velocity[i];
        const double gap = core::dot(nodes_.position[i] + dt * v - wall_point, s.normal);
        if (gap >= 0.0) continue;
        const Vec3 before = v;
        const double dvn = -gap / dt;  // > 0: the normal velocity change back onto the wall
        v += (dvn / reach) * free_normal;
        if (s.friction > 0.0) {
          const Vec3 rel = v - s.velocity;
          Vec3 tangential = core::tangential_part(rel, s.normal);
          for (int a = 0; a < 3; ++a)
            if (imposed & (1u << a)) tangential[a] = 0.0;
          const double vt = core::norm(tangential);
          const double limit = s.friction * dvn;
          v -= (vt <= limit ? 1.0 : limit / vt) * tangential;
          // Removing imposed components may have tilted the friction change off the wall plane.
          const double off = core::dot(nodes_.position[i] + dt * v - wall_point, s.normal);
          v -= (off / (dt * reach)) * free_normal;
        }
        const Vec3 j = m * (v - before);
        work += core::dot(j, s.velocity);
        done += core::dot(j, before_dt * w.start[k] + dt * v);
        impulse += j;
        if (!exact_mirror_.empty()) {  // the reproducible mode: each term exactly, in the
          // mirror of entries 1-3 (impulse), 5 (work) and 6 (done), which the sums below overwrite
          double* mine = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
          for (std::size_t a = 0; a < 3; ++a) book(mine, 1 + a, j[static_cast<int>(a)]);
          book(mine, 5, core::dot(j, s.velocity));
          book(mine, 6, core::dot(j, before_dt * w.start[k] + dt * v));
        }
      }
      double* sums = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
      sums[0] = work;
      sums[1] = impulse.x;
      sums[2] = impulse.y;
      sums[3] = impulse.z;
      sums[4] = done;
    };
    core::parallel_chunks(n, sweep);
    Vec3 impulse;
    double work = 0.0, done = 0.0;
    for (std::size_t t = 0; t < thread_errors_.size(); ++t) {
      const double* sums = &thread_sums_[t * core::cache_line_doubles];
      work += sums[0];
      impulse += Vec3{sums[1], sums[2], sums[3]};
      done += sums[4];
    }
    if (reproducible()) {  // every rank sweeps every wall node: the same exact sums on each
      work = exact_threads(5).value();
      done = exact_threads(6).value();
      impulse = Vec3{exact_threads(1).value(), exact_threads(2).value(), exact_threads(3).value()};
    }
    external_work_ += work;
    wall_energy_ += work - done / (before_dt + dt);
    // Gravity's work in the nodal update was taken on the velocities before the wall's change.
    external_work_ += core::dot(scene_.run.gravity, impulse) * dt;
    // The wall's force on the nodes: the impulse it gave them over the force step.
    wall_force_[wi] = (1.0 / dt_force) * impulse;
  }
}

}  // namespace afemp::fem
