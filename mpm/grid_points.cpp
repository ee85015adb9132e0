// The solver's side of the grid-points hook (grid_points.hpp): attaching the points, what a stage
// lends their owner, and the shift of a shared field to its particles' part.
#include "mpm/grid_points.hpp"

#include <stdexcept>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::set_grid_points(GridPoints* points) {
  // USL updates the stress before the points could take their update; USAVG's two half
  // updates are not built for them.
  if (points &&
      (plan_.scheme == core::UpdateScheme::USL || plan_.scheme == core::UpdateScheme::USAVG))
    throw std::invalid_argument(
        "points on the grid beside the particles need the MUSL or USF scheme (the scene "
        "parser says so too)");
  points_ = points;
  field_self_updated_.clear();
  if (!points) return;
  // A field that only self-updating points use: no particle body and no body whose points
  // the grid moves.
  field_self_updated_.assign(static_cast<std::size_t>(grid_.field_count()), 1);
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b)
    if (scene_.bodies[b].discretisation == core::Discretisation::particles ||
        !points->updates_itself(static_cast<int>(b)))
      field_self_updated_[static_cast<std::size_t>(field_of_body_[b])] = 0;
  for (std::size_t i = 0; i < particles_.size(); ++i)
    field_self_updated_[static_cast<std::size_t>(
        field_of_body_[static_cast<std::size_t>(particles_.body[i])])] = 0;
}

GridStepAccess MpmSolver::access() {
  return GridStepAccess{grid_,
                        scene_,
                        plan_,
                        particles_,
                        field_of_body_,
                        multi_field_,
                        field_in_contact_,
                        field_self_updated_,
                        contact_normal_,
                        contact_change_,
                        shared_,
                        step_dt_,
                        steps_,
                        time_,
                        ranks_ ? &partition_ : nullptr,
                        ranks_,
                        reproducible() ? &fixed_ : nullptr};
}

void MpmSolver::apply_shared_shifts() {
  if (!shared_.any) return;
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.field_slot_count();
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
  for (std::size_t s = 0; s < slots; ++s)
    if (shared_.mass[s] > 0.0) {
      g.velocity[s] += shared_.start[s];
      g.velocity_new[s] += shared_.updated[s];
    }
}

}  // namespace afemp::mpm
