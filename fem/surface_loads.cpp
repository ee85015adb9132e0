// Surface loads on hexahedra ([[loads]], core::LoadSpec): a dead traction t on the boundary
// faces whose four nodes the load's region holds, LS-DYNA's *LOAD_SEGMENT_SET with a traction
// vector and Abaqus's *DSLOAD TRVEC. Each face hands its nodes the consistent forces
// f_a = t ∫ N_a dA over its initial area (the load vector of a distributed surface load,
// Zienkiewicz, Taylor & Zhu 2013), N_a the bilinear shape functions of the face, by 2 x 2
// Gauss points, exact for a flat face: the forces sum to t A and their moment about any point
// is that of t A at the face's centroid. A total force F is the traction F / A over the faces'
// area A. The nodal update applies factor(t) f_a at each step's start time t, as it applies
// gravity. The work is booked by the trapezoidal rule in time, (f^n + f^{n+1}) / 2 . v^{n+1/2}
// dt, as Belytschko, Liu & Moran (2000) book external work for their energy balance: a ramped
// load's work is then not short by (df/dt) dt / 2 per unit of travel (the nodal update books
// f^n's part, book_load_change the rest). Dead loads: the faces' area and direction stay those
// of the initial mesh (small rotations of the loaded faces; a follower pressure is not built).
#include <cmath>

#include "afemp/errors.hpp"
#include "fem/fe_solver.hpp"
#include "fem/surface_faces.hpp"

namespace afemp::fem {

namespace {

// f_a += t ∫ N_a dA over the bilinear face with corners x[q], by 2 x 2 Gauss points; returns
// the face's area.
double add_face_load(const std::array<std::int32_t, 4>& q, const std::vector<Vec3>& x,
                     const Vec3& t, std::array<Vec3, 4>& f) {
  const double g = 1.0 / std::sqrt(3.0);
  // Corners in the face's cyclic order at natural coordinates (-1,-1), (1,-1), (1,1), (-1,1).
  static constexpr double xi_a[4] = {-1.0, 1.0, 1.0, -1.0};
  static constexpr double eta_a[4] = {-1.0, -1.0, 1.0, 1.0};
  double area = 0.0;
  for (int gp = 0; gp < 4; ++gp) {
    const double xi = xi_a[gp] * g, eta = eta_a[gp] * g;
    Vec3 dx_dxi, dx_deta;
    double n[4];
    for (int a = 0; a < 4; ++a) {
      const Vec3& p = x[static_cast<std::size_t>(q[static_cast<std::size_t>(a)])];
      n[a] = 0.25 * (1.0 + xi_a[a] * xi) * (1.0 + eta_a[a] * eta);
      dx_dxi += (0.25 * xi_a[a] * (1.0 + eta_a[a] * eta)) * p;
      dx_deta += (0.25 * eta_a[a] * (1.0 + xi_a[a] * xi)) * p;
    }
    const double da = core::norm(core::cross(dx_dxi, dx_deta));  // weight 1 at each point
    area += da;
    for (int a = 0; a < 4; ++a) f[static_cast<std::size_t>(a)] += (n[a] * da) * t;
  }
  return area;
}

}  // namespace

void FeSolver::setup_load(std::size_t k, const std::vector<char>& selected,
                          const SurfaceFaces& surface) {
  const core::LoadSpec& l = scene_.loads[k];
  // The faces' forces at unit traction first: a total force needs the faces' area.
  std::vector<Vec3> force(nodes_.size());
  std::vector<char> loaded(nodes_.size(), 0);
  double area = 0.0;
  std::size_t faces = 0;
  for (std::size_t f = 0; f < surface.nodes.size(); ++f) {
    bool all = true;
    for (std::int32_t n : surface.nodes[f]) all = all && selected[static_cast<std::size_t>(n)];
    if (!all) continue;
    ++faces;
    std::array<Vec3, 4> face_force{};
    area += add_face_load(surface.nodes[f], nodes_.initial_position, l.value, face_force);
    for (std::size_t a = 0; a < 4; ++a) {
      const auto n = static_cast<std::size_t>(surface.nodes[f][a]);
      force[n] += face_force[a];
      loaded[n] = 1;
    }
  }
  if (faces == 0)
    throw InputError(l.where, "nodes",
                     "the region holds no boundary face of body \"" +
                         scene_.bodies[static_cast<std::size_t>(l.body)].name +
                         "\" (a face is loaded when all four of its nodes are selected)");
  NodalLoad load;
  load.scene_load = k;
  const double scale = l.traction ? 1.0 : 1.0 / area;
  for (std::size_t n = 0; n < force.size(); ++n)
    if (loaded[n]) {
      load.nodes.push_back(static_cast<std::uint32_t>(n));
      load.force.push_back(scale * force[n]);
    }
  load.area = area;
  nodal_loads_.push_back(std::move(load));
  load_force_.assign(nodes_.size(), Vec3{});
}

void FeSolver::apply_loads(double t) {
  for (const NodalLoad& l : nodal_loads_)
    for (std::uint32_t n : l.nodes) load_force_[n] = Vec3{};
  for (const NodalLoad& l : nodal_loads_) {
    const double f = core::curve_factor(scene_.loads[l.scene_load].curve, t);
    for (std::size_t k = 0; k < l.nodes.size(); ++k) load_force_[l.nodes[k]] += f * l.force[k];
  }
}

void FeSolver::book_load_change(double dt) {
  double work = 0.0;
  for (const NodalLoad& l : nodal_loads_) {
    const std::vector<std::array<double, 2>>& curve = scene_.loads[l.scene_load].curve;
    if (curve.empty()) continue;
    const double change =
        0.5 * (core::curve_factor(curve, time_ + dt) - core::curve_factor(curve, time_));
    if (change == 0.0) continue;
    for (std::size_t k = 0; k < l.nodes.size(); ++k) {
      const std::uint32_t n = l.nodes[k];
      if (!(nodes_.mass[n] > 0.0) || nodes_.grid_driven[n]) continue;  // not moved by the FE step
      work += change * core::dot(l.force[k], nodes_.velocity[n]) * dt;
    }
  }
  external_work_ += work;
}

std::vector<Vec3> FeSolver::scene_loads_at(double t) const {
  std::vector<Vec3> force(nodal_loads_.empty() ? 0 : nodes_.size());
  for (const NodalLoad& l : nodal_loads_) {
    const double f = core::curve_factor(scene_.loads[l.scene_load].curve, t);
    for (std::size_t k = 0; k < l.nodes.size(); ++k) force[l.nodes[k]] += f * l.force[k];
  }
  return force;
}

}  // namespace afemp::fem
