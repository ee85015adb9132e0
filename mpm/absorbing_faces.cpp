// The wave speeds of the absorbing faces (absorbing_faces.hpp: Lysmer & Kuhlemeyer 1969):
// c_L = sqrt((K + 4G/3) / rho0) and c_S = sqrt(G / rho0) of the one material whose particles
// lie within a cell of the face at the start.
#include <cmath>
#include <set>
#include <string>

#include "afemp/errors.hpp"
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
  }
}

}  // namespace afemp::mpm
