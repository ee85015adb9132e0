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
    // The materials within a cell of the face, and (with a far field) the first particle there
    // that does not start at the ambient pressure.
    std::set<int> touching;
    std::size_t off_ambient = particles_.size();
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      if (!(std::abs(particles_.position[i][a] - plane) < g.cell)) continue;
      touching.insert(particles_.material[i]);
      if (g.far_field && off_ambient == particles_.size() &&
          std::abs(core::pressure(particles_.stress[i]) - g.far_field->pressure) >
              1e-6 * std::max(g.far_field->pressure, 1.0))
        off_ambient = i;
    }
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
      if (off_ambient < particles_.size()) {
        const core::BodySpec& b =
            scene_.bodies[static_cast<std::size_t>(particles_.body[off_ambient])];
        throw core::InputError(
            b.where, "bodies." + b.name + ".pressure",
            "the body meets the far field at " + key + " and starts at pressure " +
                std::to_string(core::pressure(particles_.stress[off_ambient])) +
                "; give it pressure = " + std::to_string(far->pressure) + ", the far field's");
      }
    }
  }
}

}  // namespace afemp::mpm
