// The MPM solver's part of a checkpoint (core/state_archive.hpp): the particles in their
// present order, and every member that carries over from one step to the next. What the
// constructor derives from the scene (plan, grid, contact laws, absorbing faces) is rebuilt by
// constructing the solver from the same scene; the grid itself holds nothing between steps
// (every step starts by clearing and rebinning it).
#include <stdexcept>

#include "core/state_archive.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void visit_particles(core::StateArchive& a, Particles& p) {
  const core::StateArchive::Group group(a, "particles");
  p.for_each_field([&a](const ParticleField& field, auto& array) { a.item(field.name, array); });
  a.item("optional_fields", p.optional_fields);
  a.item("history", p.history);
  a.item("history_count", p.history_count);
}

void MpmSolver::state(core::StateArchive& a) {
  // A rank's particles alone would not restart the run; the checkpoint of a divided run
  // gathers them first (docs/parallel.md), which is not built yet.
  if (ranks_) throw std::invalid_argument("a run divided among ranks cannot be checkpointed yet");
  const core::StateArchive::Group group(a, "mpm");
  visit_particles(a, particles_);
  a.item("steps", steps_);
  a.item("time", time_);
  a.item("step_dt", step_dt_);
  a.item("signal_speed", signal_speed_);
  a.item("sweep_axis", sweep_axis_);
  a.item("velocity_gradient", velocity_gradient_);
  a.item("field_self_updated", field_self_updated_);
  a.item("contact_energy", contact_energy_);
  a.item("plastic_work", plastic_work_);
  a.item("viscous_work", viscous_work_);
  a.item("external_work", external_work_);
  a.item("outflow_mass", outflow_mass_);
  a.item("outflow_energy", outflow_energy_);
  a.item("outflow_momentum", outflow_momentum_);
  a.item("outflow_count", outflow_count_);
  a.item("split_count", split_count_);
  a.item("far_field_lag", far_lag_);
  a.item("wall_force", wall_force_);
  a.item("wall_sliding", wall_sliding_);
  a.item("wall_friction", wall_friction_);
  a.item("stage_counts", stage_counts_);
  a.item("stage_seconds", stage_seconds_);
  a.item("reorder_seconds", reorder_seconds_);
  if (a.loading()) {
    if (stage_counts_.size() != plan_.stages.size())
      throw core::CheckpointError(
          a.where("stage_counts") + ": " + std::to_string(stage_counts_.size()) +
          " stages, the scene's plan has " + std::to_string(plan_.stages.size()));
    rebuild_batches();
  }
}

}  // namespace afemp::mpm
