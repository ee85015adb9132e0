// Absorbing faces: the viscous boundary of Lysmer & Kuhlemeyer (1969) on the grid, for a body
// that continues beyond the face (a semi-infinite target): the face applies the tractions
// t_n = -rho c_L v_n and t_t = -rho c_S v_t, which a plane wave meeting the face at normal
// incidence takes without reflection. At a face node of tributary area A the damping is
// C = A rho c; with the material filling the node's half (or quarter) cell inside the grid,
// rho A = 2 m / h for face, edge and corner nodes alike, so C = 2 m c / h from the node's
// own mass. Applied implicitly after the momentum update, v_new <- m v_new / (m + dt C), per
// component (c_L along the face normal, c_S along it), which is stable at any step; the work
// of the damping impulse leaves through the boundary and is booked as external work.
// c_L = sqrt((K + 4G/3) / rho0) and c_S = sqrt(G / rho0) of the one material the face touches.
#include <cmath>
#include <set>
#include <string>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::setup_absorbing_faces() {
  const core::GridSettings& g = scene_.mpm.grid;
  for (std::size_t f = 0; f < 6; ++f) {
    absorbing_[f] = {};
    if (g.faces[f] != core::FaceCondition::absorbing) continue;
    const int a = static_cast<int>(f / 2);
    const bool high = f % 2 == 1;
    const double plane = high ? g.max[a] : g.min[a];
    std::set<int> touching;
    for (std::size_t i = 0; i < particles_.size(); ++i)
      if (std::abs(particles_.position[i][a] - plane) < g.cell)
        touching.insert(particles_.material[i]);
    const std::string key =
        std::string("grid.boundary.") + core::to_string(static_cast<core::Face>(f));
    if (touching.size() != 1)
      throw core::InputError(
          core::SourceLocation{scene_.path, 0}, key,
          "an absorbing face takes the wave speeds of the material that meets it, and " +
              std::string(touching.empty() ? "no particle lies within a cell of it"
                                           : "particles of several materials lie within a cell "
                                             "of it") +
              "; put it where one body continues beyond the grid, or use \"free\", \"fixed\", "
              "\"symmetric\", \"wall\" or \"outflow\"");
    const core::Material& m = scene_.materials[static_cast<std::size_t>(*touching.begin())];
    absorbing_[f].on = true;
    absorbing_[f].c_longitudinal =
        std::sqrt((m.bulk_modulus() + 4.0 / 3.0 * m.shear_modulus()) / m.density);
    absorbing_[f].c_shear = std::sqrt(m.shear_modulus() / m.density);
    any_absorbing_ = true;
  }
}

void MpmSolver::absorb(double dt) {
  core::BackgroundGrid& g = grid_;
  const std::size_t stride = g.slot_count();
  const int fields = g.field_count();
  const std::array<int, 3> nodes = g.nodes();
  const double two_over_h = 2.0 * g.inverse_cell();
  const int nt = core::thread_count();
  thread_sums_.assign(static_cast<std::size_t>(nt) * core::cache_line_doubles, 0.0);
#pragma omp parallel num_threads(nt) if (core::worth_threads(stride))
  {
    double work = 0.0;
    g.for_each_slot([&](std::size_t slot, const std::array<int, 3>& node) {
      // Damping per component: c_L along the normal of each absorbing face the node lies on,
      // c_S along the others (the largest where faces meet).
      Vec3 c;
      bool on_face = false;
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
          const Absorbing& face = absorbing_[static_cast<std::size_t>(2 * a + side)];
          if (!face.on) continue;
          const int k = node[static_cast<std::size_t>(a)];
          if (side == 0 ? k > 0 : k < nodes[static_cast<std::size_t>(a)] - 1) continue;
          on_face = true;
          for (int b = 0; b < 3; ++b)
            c[b] = std::max(c[b], b == a ? face.c_longitudinal : face.c_shear);
        }
      if (!on_face) return;
      for (int f = 0; f < fields; ++f) {
        const std::size_t s = slot + static_cast<std::size_t>(f) * stride;
        const double m = g.mass[s];
        if (m <= 0.0) continue;
        const Vec3 before = g.velocity_new[s];
        for (int b = 0; b < 3; ++b)
          g.velocity_new[s][b] = before[b] / (1.0 + dt * two_over_h * c[b]);
        // The damping impulse's work over the step, J . (v + v_new) / 2 with the start and the
        // damped velocity, as the body forces' work is counted (grid_momentum_update.cpp).
        work +=
            0.5 * core::dot(m * (g.velocity_new[s] - before), g.velocity[s] + g.velocity_new[s]);
      }
    });
    thread_sums_[static_cast<std::size_t>(core::thread_index()) * core::cache_line_doubles] = work;
  }
  for (int t = 0; t < nt; ++t)
    external_work_ += thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
}

}  // namespace afemp::mpm
