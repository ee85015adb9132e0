// The MPM solver's part of a checkpoint (core/state_archive.hpp): the particles in their
// present order (a run divided among ranks: every rank's, in id order), and every member that
// carries over from one step to the next. What the
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

void MpmSolver::prepare_checkpoint() {
  if (ranks_ == nullptr) return;
  RankCheckpoint& c = rank_checkpoint_;
  c.whole = gathered_particles(false);
  std::vector<double> sums{plastic_work_, viscous_work_, external_work_, contact_energy_};
  if (reproducible()) {  // the exact sums (the same order: plastic, viscous, external, contact;
                         // then the outflow's mass, energy and momentum)
    auto exact = exact_;
    sums = core::exact_values(ranks_, exact);
  } else {
    ranks_->sum_in_rank_order(sums);
  }
  c.plastic_work = sums[0];
  c.viscous_work = sums[1];
  c.external_work = sums[2];
  c.contact_energy = sums[3];
  // What the outflow faces took and the splits so far, every rank's (counts below 2^53).
  std::vector<double> more{outflow_mass_,
                           outflow_energy_,
                           outflow_momentum_.x,
                           outflow_momentum_.y,
                           outflow_momentum_.z,
                           static_cast<double>(outflow_count_),
                           static_cast<double>(split_count_)};
  ranks_->sum_in_rank_order(more);
  if (reproducible())
    for (std::size_t k = 0; k < 5; ++k) more[k] = sums[exact_outflow_mass + k];
  c.outflow_mass = more[0];
  c.outflow_energy = more[1];
  c.outflow_momentum = Vec3{more[2], more[3], more[4]};
  c.outflow_count = static_cast<long>(more[5]);
  c.split_count = static_cast<long>(more[6]);
  c.signal_wave = ranks_->max_over_ranks(signal_wave_);
  c.signal_flow = ranks_->max_over_ranks(signal_flow_);
  c.ready = true;
}

void MpmSolver::state(core::StateArchive& a) {
  // On ranks, a checkpoint holds the whole run as one process's would: saving writes what
  // prepare_checkpoint() gathered (the particle walls' force, sliding and friction and the
  // far-field lags are whole on every rank as they are); restoring reads it whole on every rank
  // and divides it among this run's ranks.
  const bool whole_on_ranks = ranks_ != nullptr && !a.loading();
  if (whole_on_ranks && !rank_checkpoint_.ready)
    throw std::logic_error("MpmSolver::state: prepare_checkpoint() first on ranks");
  RankCheckpoint& c = rank_checkpoint_;
  const core::StateArchive::Group group(a, "mpm");
  visit_particles(a, whole_on_ranks ? c.whole : particles_);
  a.item("steps", steps_);
  a.item("time", time_);
  a.item("step_dt", step_dt_);
  // The signal speed the next stable step comes from, and its two parts (whose maxima over the
  // ranks make it on ranks; a later item: a checkpoint without them has its sum alone).
  double signal[3] = {signal_speed_, signal_wave_, signal_flow_};
  if (whole_on_ranks) signal[0] = (signal[1] = c.signal_wave) + (signal[2] = c.signal_flow);
  a.item("signal_speed", signal[0]);
  if (!a.loading() || a.has("signal_wave")) {
    a.item("signal_wave", signal[1]);
    a.item("signal_flow", signal[2]);
  }
  // Parts that do not make the speed (an older checkpoint; a speed raised by particles added
  // in one process): the whole speed as the wave's, which the step on ranks then equals.
  if (a.loading() && !(signal[1] + signal[2] == signal[0])) {
    signal[1] = signal[0];
    signal[2] = 0.0;
  }
  a.item("sweep_axis", sweep_axis_);
  // Scratch of one step (the kinematics pass's L): a divided run saves none.
  std::vector<core::Mat3> no_gradient;
  a.item("velocity_gradient", whole_on_ranks ? no_gradient : velocity_gradient_);
  a.item("field_self_updated", field_self_updated_);
  double contact = whole_on_ranks ? c.contact_energy : contact_energy_;
  if (reproducible() && !a.loading() && !whole_on_ranks) contact = exact_[exact_contact].value();
  a.item("contact_energy", contact);
  double work[3] = {plastic_work_, viscous_work_, external_work_};
  if (reproducible() && !a.loading() && !whole_on_ranks) {  // one process: the exact sums
    work[0] = exact_[exact_plastic].value();
    work[1] = exact_[exact_viscous].value();
    work[2] = exact_[exact_external].value();
  }
  if (whole_on_ranks) {
    work[0] = c.plastic_work;
    work[1] = c.viscous_work;
    work[2] = c.external_work;
  }
  a.item("plastic_work", work[0]);
  a.item("viscous_work", work[1]);
  a.item("external_work", work[2]);
  double outflow_mass = whole_on_ranks ? c.outflow_mass : outflow_mass_;
  double outflow_energy = whole_on_ranks ? c.outflow_energy : outflow_energy_;
  Vec3 outflow_momentum = whole_on_ranks ? c.outflow_momentum : outflow_momentum_;
  if (reproducible() && !a.loading() && !whole_on_ranks) {  // one process: the exact sums
    outflow_mass = exact_[exact_outflow_mass].value();
    outflow_energy = exact_[exact_outflow_energy].value();
    for (std::size_t k = 0; k < 3; ++k)
      outflow_momentum[static_cast<int>(k)] = exact_[exact_outflow_momentum + k].value();
  }
  a.item("outflow_mass", outflow_mass);
  a.item("outflow_energy", outflow_energy);
  a.item("outflow_momentum", outflow_momentum);
  if (a.loading()) {
    outflow_mass_ = outflow_mass;
    outflow_energy_ = outflow_energy;
    outflow_momentum_ = outflow_momentum;
  }
  a.item("outflow_count", whole_on_ranks ? c.outflow_count : outflow_count_);
  a.item("split_count", whole_on_ranks ? c.split_count : split_count_);
  // The far-field lags: whole on every rank (share_far_field_lags).
  a.item("far_field_lag", far_lag_);
  a.item("wall_force", wall_force_);
  a.item("wall_sliding", wall_sliding_);
  a.item("wall_friction", wall_friction_);
  a.item("stage_counts", stage_counts_);
  a.item("stage_seconds", stage_seconds_);
  a.item("reorder_seconds", reorder_seconds_);
  if (whole_on_ranks) {
    c = RankCheckpoint{};  // the gathered copy goes
    return;
  }
  if (!a.loading()) return;
  if (stage_counts_.size() != plan_.stages.size())
    throw core::CheckpointError(
        a.where("stage_counts") + ": " + std::to_string(stage_counts_.size()) +
        " stages, the scene's plan has " + std::to_string(plan_.stages.size()));
  signal_speed_ = signal[0];
  signal_wave_ = signal[1];
  signal_flow_ = signal[2];
  plastic_work_ = work[0];
  viscous_work_ = work[1];
  external_work_ = work[2];
  contact_energy_ = contact;
  // The reproducible mode's exact works start from the checkpoint's (rank 0's alone on ranks).
  for (core::ExactSum& e : exact_) e.clear();
  if (ranks_ == nullptr || ranks_->rank() == 0) {
    exact_[exact_plastic].add(work[0]);
    exact_[exact_viscous].add(work[1]);
    exact_[exact_external].add(work[2]);
    exact_[exact_contact].add(contact);
    exact_[exact_outflow_mass].add(outflow_mass_);
    exact_[exact_outflow_energy].add(outflow_energy_);
    for (std::size_t k = 0; k < 3; ++k)
      exact_[exact_outflow_momentum + k].add(outflow_momentum_[static_cast<int>(k)]);
  }
  if (ranks_ == nullptr) {
    rebuild_batches();
    if (!fused_kinematics()) velocity_gradient_.resize(particles_.size());
    return;
  }
  // Every rank read every particle and the run's sums: the sums go on rank 0 alone (energies()
  // adds them in rank order), the particles to the ranks of a partition made anew.
  keep_own_particles();
  signal_speed_ = signal[0];
  signal_wave_ = signal[1];
  signal_flow_ = signal[2];
  if (ranks_->rank() != 0) {
    plastic_work_ = viscous_work_ = external_work_ = contact_energy_ = 0.0;
    outflow_mass_ = outflow_energy_ = 0.0;
    outflow_momentum_ = {};
    outflow_count_ = split_count_ = 0;
  }
}

}  // namespace afemp::mpm
