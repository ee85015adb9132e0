#include "coupling/make_model.hpp"

#include "core/resource_guard.hpp"
#include "coupling/coupled_model.hpp"
#include "fem/fe_model.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::coupling {

std::unique_ptr<core::Model> make_model(const core::Scene& scene) {
  // Before anything is allocated: a scene that cannot fit in memory is refused with its size.
  core::refuse_oversized_scene(scene);
  if (core::has_mesh(scene) && (core::has_particles(scene) || core::has_grid_coupling(scene)))
    return std::make_unique<CoupledModel>(scene);
  if (core::has_mesh(scene)) return std::make_unique<fem::FeModel>(scene);
  return std::make_unique<mpm::MpmModel>(scene);
}

}  // namespace afemp::coupling
