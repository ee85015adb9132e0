// The FE solver as a core::Model: mesh fields for the output (hexahedra and trusses as mesh
// blocks of the same HDF5/XDMF frame particles use), the step plan and mesh quality that
// `afemp check` prints, the erosion log and the nodes of a body.
#pragma once

#include <vector>

#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "fem/fe_solver.hpp"
#include "fem/mesh_probes.hpp"
#include "fem/points_inside_mesh.hpp"

namespace afemp::fem {

class FeModel final : public core::Model {
 public:
  explicit FeModel(const core::Scene& scene);
  explicit FeModel(core::Scene&&) = delete;  // kept by reference: a temporary would dangle
  FeSolver& solver() { return solver_; }
  const FeSolver& solver() const { return solver_; }

  double stable_time_step() const override { return solver_.stable_time_step(); }
  std::string time_step_setter() const override { return solver_.time_step_setter(); }
  void step(double dt) override { solver_.step(dt); }
  void scale_velocities(double factor) override { solver_.scale_velocities(factor); }
  long step_count() const override { return solver_.step_count(); }
  double time() const override { return solver_.time(); }
  core::Energies energies() const override { return solver_.energies(); }
  std::size_t particle_count() const override { return 0; }
  std::size_t element_count() const override {
    return solver_.hexahedra().size() + solver_.trusses().size();
  }
  void write_fields(core::FieldWriter& writer) override;
  std::vector<core::StageTiming> stage_timings() const override;
  std::vector<core::EventLog> take_events() override;
  // Per body whose elements eroded: how many of its elements did.
  std::vector<std::string> summary_warnings() const override;
  std::string describe() const override;
  // Its first part: the bodies, mesh quality and smallest step (the step plan follows).
  std::string describe_mesh() const;
  // The mesh blocks of one output frame (valid until the next call).
  const std::vector<core::MeshBlock>& mesh_blocks();
  std::size_t bytes() const override { return solver_.bytes(); }
  void resolve_probes(std::span<const core::ProbeSpec> probes) override {
    probes_.resolve(probes, solver_, scene_);
  }
  // On MPI ranks (collective): rank 0 gathers the elements' state first when a probe reads it.
  void sample_probes(std::span<double> out) const override;
  // Penalty contacts book the work of their impulses as the sliding energy (mesh_contact.cpp).
  std::vector<core::EnergyColumn> energy_columns() const override;
  // Per penalty contact NAME: NAME.fx, .fy, .fz (the force on its first body), NAME.normal and
  // NAME.tangential (the lengths of the resultant normal and tangential forces; a self-contact,
  // whose resultant on its body is zero: the sums of its pairs' force magnitudes); per [[walls]]
  // entry wallK (K from 1) the same of the force the wall exerts on the nodes; per rigid body
  // NAME: NAME.fx, .fy, .fz, .mx, .my, .mz (the resultant on it and its moment about the
  // centre of mass: contacts, loads and gravity) and, for a body with fixed components,
  // NAME.rfx, .rfy, .rfz, .rmx, .rmy, .rmz (the reaction of its supports).
  std::vector<std::string> force_columns() const override;
  void force_values(std::vector<double>& out) const override { force_values(out, {}); }
  // The same, each wall's force with what it gave other points added (one per wall, or empty):
  // a coupled scene's walls also act on particles.
  void force_values(std::vector<double>& out, std::span<const core::Vec3> wall_extra) const;
  // The nodes of the body's live elements, each with half size 0 (on the surface).
  core::BodyPoints body_points(int body) const override {
    core::BodyPoints out{live_node_positions(solver_, body), {}};
    out.half_size.assign(out.position.size(), 0.0);
    return out;
  }
  std::size_t points_inside(int body, std::span<const core::Vec3> points) const override {
    return fem::points_inside(solver_.hexahedra(), solver_.nodes().position, body, points);
  }
  void state(core::StateArchive& archive) override;
  void prepare_checkpoint() override { solver_.prepare_checkpoint(); }
  // Divides the run among MPI ranks (FeSolver::divide_among_ranks; docs/parallel.md): every
  // rank moves every node, its own elements' points live on it; rank 0 writes the frames,
  // probes, records and checkpoints one process would.
  void divide_among_ranks(core::RankLink& link);
  void set_body_velocity(int body, const core::Vec3& v) override {
    solver_.set_body_velocity(body, v);
  }
  void set_clock(double time) override { solver_.set_clock(time); }
  void hold_body(int body, bool hold) override { solver_.hold_body(body, hold); }
  std::vector<core::BodyStress> body_stresses() const override;
  // fem/static_phase.cpp.
  double run_implicit_phase(const core::PhaseSpec& phase, std::ostream* log) override;

 private:
  const core::Scene& scene_;
  FeSolver solver_;
  long hourglass_warning_step_ = -1;
  // The static or implicit phase's Newton iterations (static_phase.csv, implicit_phase.csv)
  // and the implicit phase's energies (implicit_energies.csv), taken with the events.
  std::vector<core::EventLog> phase_logs_;
  std::vector<long> eroded_;  // elements eroded so far, per body (counted in take_events)
  // Derived fields, per frame.
  std::vector<core::Vec3> displacement_;
  // Hexahedra: the element means of the point fields written (element_store.hpp), by type.
  std::vector<std::vector<double>> hex_scalars_;
  std::vector<std::vector<core::SymTensor>> hex_tensors_;
  std::vector<double> hex_pressure_, hex_von_mises_, hex_density_, hex_alive_, hex_body_;
  std::vector<double> truss_stress_, truss_force_, truss_plastic_, truss_temperature_, truss_alive_,
      truss_body_;
  // User strength models' history variables per element (hexahedra: means of the points).
  std::vector<std::vector<double>> hex_history_, truss_history_;
  std::vector<std::string> history_names_;  // core::history_field_names
  std::vector<std::int32_t> hex_connectivity_, truss_connectivity_;
  std::vector<core::FieldView> node_fields_, hex_fields_, truss_fields_;
  std::vector<core::MeshBlock> blocks_;
  MeshProbes probes_;
};

}  // namespace afemp::fem
