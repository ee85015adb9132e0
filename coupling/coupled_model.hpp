// FE and MPM bodies in one scene, tied through the background grid
// (Lian et al. 2013, §2.4 and §2.6):
//   - contact coupling (CFEMP): the nodes of a mesh body named in a [[contact]] map their
//     mass, momentum and FE-update force into their own velocity field; grid contact corrects
//     that field against the particles' and each node receives sum N dv of the correction.
//     Elsewhere (no other body at its grid nodes) a node moves by the FE update alone.
//   - bonded coupling (HFEMP): the nodes of a mesh body with `bonded_to` map mass, momentum
//     and element forces into their host's field and move with the grid solution like its
//     particles (perfect bond: rebar in concrete).
//   - adaptive conversion (AFEMP, Lian et al. 2013, §2.6): hexahedra of a body with `conversion`
//     that meet a criterion retire from the mesh (fem/element_retirement.cpp) and become
//     particles of the same body (coupling/element_conversion.cpp); the nodes they shared
//     with live elements then join the body's field as bonded nodes, so the remaining mesh and its
//     particles move together (the same bonded coupling).
// Mesh bodies in neither take no part in the grid step. One step with dt = the smaller of the
// FE and grid stable steps:
//   1. FE: v^{n+1/2} of the free and contact nodes from the element forces at x^n;
//   2. grid: particles and coupled nodes (node_points.hpp, through the
//      MPM solver's grid-points hook), the scene's MPM scheme;
//   3. contact nodes add the contact change; bonded nodes move with the grid velocity;
//   4. FE: x^{n+1} of the other nodes, then element stress and forces at x^{n+1}.
// Surface contacts (particles at mesh faces) act in step 2 on the grid's updated velocity and
// the nodes' v^{n+1/2}; rigid bodies take their impulses before step 4.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "coupling/node_points.hpp"
#include "coupling/particle_surface_contact.hpp"
#include "fem/fe_model.hpp"
#include "fem/surface_faces.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::coupling {

class CoupledModel final : public core::Model {
 public:
  // Throws core::InputError when a constraint holds a bonded node.
  explicit CoupledModel(const core::Scene& scene);
  explicit CoupledModel(core::Scene&&) = delete;  // kept by reference: a temporary would dangle

  fem::FeSolver& fe() { return fe_.solver(); }
  const fem::FeSolver& fe() const { return fe_.solver(); }
  mpm::MpmSolver& mpm() { return mpm_.solver(); }
  const mpm::MpmSolver& mpm() const { return mpm_.solver(); }
  // The FE nodes the grid step carries, and the FE node of each.
  const NodePoints& node_points() const { return points_; }
  const std::vector<std::size_t>& coupled_nodes() const { return fe_node_; }

  double stable_time_step() const override;
  // Of the FE step, the grid's and the coupled nodes' crossing of the grid, the smallest's.
  std::string time_step_setter() const override;
  void step(double dt) override;
  // The mesh's (bonded nodes too, which the grid moves) and the particles'.
  void set_body_velocity(int body, const core::Vec3& v) override {
    fe_.set_body_velocity(body, v);
    mpm_.set_body_velocity(body, v);
  }
  void hold_body(int body, bool hold) override { fe_.hold_body(body, hold); }
  // Particles made from converted elements add to their hexahedra body's.
  std::vector<core::BodyStress> body_stresses() const override {
    std::vector<core::BodyStress> out = fe_.body_stresses();
    const std::vector<core::BodyStress> particles = mpm_.body_stresses();
    for (std::size_t b = 0; b < out.size(); ++b)
      if (out[b].points == 0)
        out[b] = particles[b];
      else if (particles[b].points > 0) {
        out[b].max_von_mises = std::max(out[b].max_von_mises, particles[b].max_von_mises);
        out[b].min_pressure = std::min(out[b].min_pressure, particles[b].min_pressure);
        out[b].max_pressure = std::max(out[b].max_pressure, particles[b].max_pressure);
        out[b].points += particles[b].points;
      }
    return out;
  }
  void set_clock(double time) override {
    fe_.set_clock(time);
    mpm_.set_clock(time);
  }
  void scale_velocities(double factor) override {
    fe_.scale_velocities(factor);
    mpm_.scale_velocities(factor);
  }
  long step_count() const override { return mpm().step_count(); }
  double time() const override { return mpm().time(); }
  // FE and MPM energies added; per-body sums from whichever holds the body.
  core::Energies energies() const override;
  // The FE side's energy columns and the MPM side's, each once. The surface contacts declare
  // none: friction's work there joins the sliding energy, but the history of a scene with only
  // them has never had its columns.
  std::vector<core::EnergyColumn> energy_columns() const override;
  // The FE side's, then per surface and grid contact NAME.fx, .fy, .fz, .normal, .tangential
  // (the force on its first body), then per bonded body NAME.fx, .fy, .fz (the bond's force on
  // it) and NAME.axial_max, .axial_min (its trusses' largest tension and compression, signed).
  std::vector<std::string> force_columns() const override;
  void force_values(std::vector<double>& out) const override;
  // The particles' (mpm::unbooked_particle_energies) and the normal catch of surface contacts.
  std::vector<std::string> unbooked_energies() const override;
  std::size_t particle_count() const override { return mpm_.particle_count(); }
  std::size_t element_count() const override { return fe_.element_count(); }
  void write_fields(core::FieldWriter& writer) override;
  std::vector<core::StageTiming> stage_timings() const override;
  std::vector<core::EventLog> take_events() override;
  // The FE side's, then the MPM side's.
  std::vector<std::string> summary_warnings() const override;
  std::string describe() const override;
  std::size_t bytes() const override;
  // Particle probes from the MPM part, node and element probes from the FE part, extremes
  // over both.
  void resolve_probes(std::span<const core::ProbeSpec> probes) override {
    mpm_.resolve_probes(probes);
    fe_.resolve_probes(probes);
  }
  void sample_probes(std::span<double> out) const override {
    mpm_.sample_probes(out);
    fe_.sample_probes(out);
  }
  // The body's particles (converted elements' included) and the nodes of its live elements.
  core::BodyPoints body_points(int body) const override;
  std::size_t points_inside(int body, std::span<const core::Vec3> points) const override {
    return fe_.points_inside(body, points);
  }
  void state(core::StateArchive& archive) override;
  void prepare_checkpoint() override {
    fe_.prepare_checkpoint();
    mpm_.prepare_checkpoint();
  }
  // Divides the run among MPI ranks (docs/parallel.md): the particles by the grid's blocks
  // (MpmModel::divide_among_ranks), the elements in runs dealt round the ranks with every node
  // on every rank (FeModel::divide_among_ranks); a node on the grid is scattered by the rank of
  // its block and its result sent to every rank (NodePoints), so the contact and bonded
  // couplings divide with them; the hexahedra that convert into particles (AFEMP) are sent
  // with their points' state to every rank, which makes the same particles of them and keeps
  // those of its blocks; the contacts of particles with mesh faces (surface contact) are sent
  // to every rank and swept by each in the particles' id order (mpm/contact_nodes.hpp). A static
  // or implicit phase is solved on rank 0 (core::TimeLoop::solve_phase_on_rank_0).
  void divide_among_ranks(core::RankLink& link, const core::RankBalance& balance = {});
  // The meshes' static or implicit phase (the particles held); both clocks then read its end.
  double run_implicit_phase(const core::PhaseSpec& phase, std::ostream* log) override {
    const double dissipated = fe_.run_implicit_phase(phase, log);
    mpm().set_clock(phase.end_time);
    return dissipated;
  }

 private:
  // Copies the FE nodes' state into the node points before the grid step.
  void load_points(double dt);
  // Adds a node point for FE node i (bonded or contact), or returns its index.
  std::size_t add_point(std::size_t i, bool bonded, bool surface);
  // Turns the elements the FE step converted into particles, and bonds the nodes they shared
  // with live elements to the body's field.
  void convert_elements();

  const core::Scene& scene_;
  fem::FeModel fe_;
  mutable mpm::MpmModel mpm_;  // describe() bins the particles
  NodePoints points_;
  std::vector<std::size_t> fe_node_;          // FE node of each node point
  std::vector<std::int64_t> point_of_node_;   // node point of each FE node, or -1
  std::vector<std::uint8_t> driven_;          // FE nodes the grid moves (bonded)
  std::vector<std::string> conversion_rows_;  // conversion.csv rows not yet taken
  std::vector<core::Vec3> start_velocity_;    // contact nodes: v^{n-1/2}
  // The surface of the hexahedral contact bodies, rebuilt when elements erode.
  std::vector<char> surface_body_;
  fem::SurfaceFaces surface_;
  std::size_t surface_live_ = 0;    // live hexahedra when surface_ was built
  std::vector<core::Vec3> normal_;  // per FE node
  double coupling_seconds_ = 0.0;
  double converted_energy_ = 0.0;  // Energies::converted: what conversion's interpolation lost
  // Particles at mesh faces ([[contact]] method "surface"), when the scene has any.
  std::unique_ptr<ParticleSurfaceContacts> surface_contacts_;
  // Bodies with `bonded_to` (rebar): per scene body, the bond's force on it over the last step
  // (its momentum change less its weight: its elements' forces on it sum to zero).
  std::vector<int> bonded_bodies_;
  std::vector<std::uint8_t> bonds_body_;  // per body: 1 when it is bonded to particles
  std::vector<core::Vec3> bond_force_;
};

}  // namespace afemp::coupling
