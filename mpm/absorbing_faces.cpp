// The wave speeds of the absorbing faces (absorbing_faces.hpp: Lysmer & Kuhlemeyer 1969):
// c_L = sqrt((K + 4G/3) / rho0) (K the EOS's tangent modulus at rho0 where the material has an
// EOS) and c_S = sqrt(G / rho0) of the one material whose particles
// lie within a cell of the face at the start; with a far field, its impedance rho0 c_L.
#include <cmath>
#include <set>
#include <string>

#include "afemp/errors.hpp"
#include "core/materials/material.hpp"
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
    // The EOS's tangent modulus at the reference state where the material has one (a fluid
    // has no Young's modulus to take K from); core::wave_speed adds 4G/3.
    core::PointState reference;
    reference.density = m.density;
    absorbing_[f].c_longitudinal = core::wave_speed(m, reference);
    absorbing_[f].c_shear = std::sqrt(m.shear_modulus() / m.density);
    if (const std::optional<core::FarField>& far = g.far_field) {
      absorbing_[f].far = true;
      absorbing_[f].impedance = m.density * absorbing_[f].c_longitudinal;
      absorbing_[f].centre = far->centre;
      // The fluid at the face must start at the ambient pressure, or it would be pulled in or
      // pushed out from the first step.
      for (std::size_t i = 0; i < particles_.size(); ++i) {
        if (!(std::abs(particles_.position[i][a] - plane) < g.cell)) continue;
        const double p0 = core::pressure(particles_.stress[i]);
        if (std::abs(p0 - far->pressure) > 1e-6 * std::max(far->pressure, 1.0))
          throw core::InputError(
              scene_.bodies[static_cast<std::size_t>(particles_.body[i])].where,
              "bodies." + scene_.bodies[static_cast<std::size_t>(particles_.body[i])].name +
                  ".pressure",
              "the body meets the far field at " + key + " and starts at pressure " +
                  std::to_string(p0) + "; give it pressure = " +
                  std::to_string(far->pressure) + ", the far field's");
      }
    }
  }
}

// A far-field face stands for the fluid beyond it, which the flow through the face joins. The
// grid is fixed, so a particle that the outgoing flow carries past the face's plane (the water
// a growing bubble displaces: 0.5-1 mm at the faces in the bubble trial of docs/explosives.md)
// is put back on the plane, keeping its mass, momentum and state; when the flow turns (the
// bubble collapses) it moves in again. Taking such particles out instead (as an outflow face does) left the face
// nodes without mass once the outermost layer had gone: the water then had a free surface at
// the ambient pressure, released it, and cavitated through the domain.
void MpmSolver::hold_at_far_field_faces() {
  bool any = false;
  for (const AbsorbingFace& f : absorbing_) any = any || f.far;
  if (!any) return;
  const core::GridSettings& g = grid_.settings();
  Particles& p = particles_;
  const std::size_t n = p.size();
  // Just inside the plane, so that the particle's cell is the last one.
  const double inset = 1e-9 * grid_.cell();
#pragma omp parallel for schedule(static) if (core::worth_threads(n))
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      const double lo = g.min[a];
      const double hi = g.min[a] + grid_.cells()[static_cast<std::size_t>(a)] * grid_.cell();
      double& x = p.position[i][a];
      if (absorbing_[static_cast<std::size_t>(2 * a)].far && x < lo) x = lo + inset;
      if (absorbing_[static_cast<std::size_t>(2 * a + 1)].far && x > hi) x = hi - inset;
    }
}

}  // namespace afemp::mpm
