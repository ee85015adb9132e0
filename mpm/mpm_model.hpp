// The MPM solver as a core::Model, so that core::run drives it: particle fields for the output
// (pressure, von Mises, density derived per frame), stage timings and the particles of a body.
#pragma once

#include <vector>

#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_probes.hpp"

namespace afemp::mpm {

// The history's columns of the scene's grid contacts, NAME.fx, .fy, .fz, .normal, .tangential
// (the force on the contact's first body), and their values (MpmSolver::grid_contact_forces);
// the coupled model reports them too.
void append_grid_contact_columns(std::vector<std::string>& columns, const core::Scene& scene);
void append_grid_contact_values(std::vector<double>& out, const MpmSolver& solver);

// The particles' mechanisms whose energy no column of total() books (core::Model::
// unbooked_energies): the transfers between particles and grid, grid contacts, grid faces that
// hold the material, walls at particles.
std::vector<std::string> unbooked_particle_energies(const core::Scene& scene);

class MpmModel final : public core::Model {
 public:
  explicit MpmModel(const core::Scene& scene);
  explicit MpmModel(core::Scene&&) = delete;  // kept by reference: a temporary would dangle
  MpmSolver& solver() { return solver_; }
  const MpmSolver& solver() const { return solver_; }

  double stable_time_step() const override { return solver_.stable_time_step(); }
  std::string time_step_setter() const override { return solver_.time_step_setter(); }
  void step(double dt) override { solver_.step(dt); }
  void scale_velocities(double factor) override { solver_.scale_velocities(factor); }
  void set_body_velocity(int body, const core::Vec3& v) override {
    solver_.set_body_velocity(body, v);
  }
  void set_clock(double time) override { solver_.set_clock(time); }
  std::vector<core::BodyStress> body_stresses() const override {
    std::vector<core::BodyStress> out(scene_.bodies.size());
    const Particles& p = solver_.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      out[static_cast<std::size_t>(p.body[i])].add(p.stress[i]);
    return out;
  }
  long step_count() const override { return solver_.step_count(); }
  double time() const override { return solver_.time(); }
  core::Energies energies() const override { return solver_.energies(); }
  // Walls that name particle bodies book friction's work as the sliding energy
  // (particle_wall_contact.cpp).
  std::vector<core::EnergyColumn> energy_columns() const override;
  std::vector<std::string> force_columns() const override;
  void force_values(std::vector<double>& out) const override;
  std::vector<std::string> unbooked_energies() const override {
    return unbooked_particle_energies(scene_);
  }
  std::size_t particle_count() const override {
    return solver_.on_ranks() ? solver_.whole_particle_count() : solver_.particles().size();
  }
  std::size_t element_count() const override { return 0; }
  void write_fields(core::FieldWriter& writer) override;
  std::vector<core::StageTiming> stage_timings() const override;
  // Bins the particles first so that the active cells and memory describe the first step.
  std::string describe() const override;
  std::size_t bytes() const override { return solver_.bytes(); }
  // On ranks (collective): resolved among every rank's particles, sampled on each rank and
  // merged on every rank (ParticleProbes::merge_ranks).
  void resolve_probes(std::span<const core::ProbeSpec> probes) override;
  void sample_probes(std::span<double> out) const override;
  core::BodyPoints body_points(int body) const override;
  // Per body with failed particles (damage 1): how many of its particles failed.
  std::vector<std::string> summary_warnings() const override;
  void state(core::StateArchive& archive) override;
  void prepare_checkpoint() override { solver_.prepare_checkpoint(); }
  // The particles' block of one output frame (valid until the next call).
  // On ranks (collective): every rank's particles, gathered on rank 0 in id order (the block
  // is empty on the other ranks, whose frames are not kept).
  core::PointBlock particle_block();
  // Divides the run among MPI ranks (MpmSolver::divide_among_ranks; docs/parallel.md). Output
  // frames then hold every rank's particles in id order, written by rank 0 (the others write
  // frames of none); the particle count, the body points and the summary's warnings are the
  // whole run's. Throws std::invalid_argument for what does not divide yet, naming it.
  void divide_among_ranks(core::RankLink& link, const core::RankBalance& balance = {});

 private:
  const core::Scene& scene_;
  mutable MpmSolver solver_;                            // describe() bins the particles
  std::vector<double> pressure_, von_mises_, density_;  // derived, per frame
  std::vector<std::vector<double>> integers_;  // integer fields (body, id) as doubles, per frame
  std::vector<std::vector<double>> history_;   // user models' history variables, per variable
  std::vector<std::string> history_names_;     // core::history_field_names
  std::vector<core::FieldView> fields_;
  ParticleProbes probes_;
  Particles gathered_;  // on ranks: the particles of the frame being written

  core::PointBlock particle_block(const Particles& p);
};

}  // namespace afemp::mpm
