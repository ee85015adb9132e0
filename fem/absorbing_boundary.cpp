// Absorbing boundaries of meshes: the viscous boundary of Lysmer & Kuhlemeyer (1969),
// LS-DYNA's *BOUNDARY_NON_REFLECTING. The boundary faces of hexahedra whose four nodes a
// [[absorbing]] selector holds apply the tractions t_n = -rho c_L v_n and t_t = -rho c_S v_t
// (c_L = sqrt((K + 4G/3) / rho), c_S = sqrt(G / rho) of the face's element), which a plane wave
// meeting the face at normal incidence takes without reflection. Each face gives a quarter of
// its area A to each of its nodes, so a node carries the dashpots C_n = sum A rho c_L along its
// outward normal (the area-weighted mean of its faces') and C_t = sum A rho c_S across it. The
// nodal update applies them implicitly to the updated velocity, v_n <- v_n / (1 + dt C_n / m)
// and likewise across, stable at any step (as the grid's absorbing faces do,
// mpm/absorbing_faces.hpp); imposed components stay imposed. The dashpots' work leaves through
// the boundary and is booked as external work. The faces, their areas and normals are those of
// the initial mesh: meant for the far boundary of a target, which moves little. They are
// gathered from every element set with faces (element_set.hpp), each with its element's
// material and centroid.
#include <cmath>

#include "afemp/errors.hpp"
#include "fem/fe_solver.hpp"
#include "fem/surface_faces.hpp"

namespace afemp::fem {

void FeSolver::setup_absorbing(const core::AbsorbingSpec& spec, const std::vector<char>& selected,
                               const SurfaceFaces& faces) {
  std::vector<Vec3> area(nodes_.size());
  std::vector<double> normal_damping(nodes_.size(), 0.0), shear_damping(nodes_.size(), 0.0);
  std::size_t taken = 0;
  for (std::size_t f = 0; f < faces.nodes.size(); ++f) {
    bool all = true;
    for (std::int32_t n : faces.nodes[f]) all = all && selected[static_cast<std::size_t>(n)];
    if (!all) continue;
    ++taken;
    const ElementSet& set = *sets_[static_cast<std::size_t>(faces.set[f])];
    const auto e = static_cast<std::size_t>(faces.element[f]);
    const Vec3 a =
        face_area_vector(faces.nodes[f], set.element_centroid(e, nodes_.position), nodes_.position);
    const core::Material& m =
        scene_.materials[static_cast<std::size_t>(batch_of(set.store(), e).material)];
    const double c_l = std::sqrt((m.bulk_modulus() + 4.0 / 3.0 * m.shear_modulus()) / m.density);
    const double c_s = std::sqrt(m.shear_modulus() / m.density);
    const double quarter = 0.25 * core::norm(a);
    for (std::int32_t n : faces.nodes[f]) {
      const auto k = static_cast<std::size_t>(n);
      area[k] += 0.25 * a;
      normal_damping[k] += quarter * m.density * c_l;
      shear_damping[k] += quarter * m.density * c_s;
    }
  }
  if (taken == 0)
    throw InputError(spec.where, "absorbing",
                     "the selector holds no boundary face of a body of hexahedra (a face is "
                     "absorbing when all four of its nodes are selected)");
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (!(normal_damping[k] > 0.0)) continue;
    AbsorbingNode a;
    a.node = static_cast<std::uint32_t>(k);
    a.normal = (1.0 / core::norm(area[k])) * area[k];
    a.normal_damping = normal_damping[k];
    a.shear_damping = shear_damping[k];
    absorbing_nodes_.push_back(a);  // a node of two [[absorbing]] tables is damped by each
  }
  absorbing_start_.resize(absorbing_nodes_.size());
}

void FeSolver::absorb(double dt) {
  double work = 0.0;
  for (std::size_t k = 0; k < absorbing_nodes_.size(); ++k) {
    const AbsorbingNode& a = absorbing_nodes_[k];
    const double m = nodes_.mass[a.node];
    if (!(m > 0.0) || nodes_.grid_driven[a.node]) continue;
    Vec3& v = nodes_.velocity[a.node];
    const Vec3 before = v;
    const double vn = core::dot(v, a.normal);
    const Vec3 vt = v - vn * a.normal;
    v = (vn / (1.0 + dt * a.normal_damping / m)) * a.normal +
        (1.0 / (1.0 + dt * a.shear_damping / m)) * vt;
    if (const std::uint8_t imposed = nodes_.imposed[a.node])
      for (int c = 0; c < 3; ++c)
        if (imposed & (1u << c)) v[c] = before[c];
    // The dashpots' impulse at the step's mean velocity, as the nodal update books loads.
    work += 0.5 * core::dot(m * (v - before), absorbing_start_[k] + v);
  }
  external_work_ += work;
}

}  // namespace afemp::fem
