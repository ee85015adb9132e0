// The interface every discretisation offers the time loop (core/time_loop.hpp): the MPM
// solver, the FE solver and their coupling each implement it (mpm/mpm_model.hpp,
// fem/fe_model.hpp, coupling/coupled_model.hpp); the loop, the probes, the reference checks
// and the studies see a model only through it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/probes.hpp"
#include "afemp/run.hpp"
#include "afemp/scene.hpp"
#include "afemp/tensor.hpp"
#include "core/output/field_writer.hpp"

namespace afemp::core {

class StateArchive;  // core/state_archive.hpp

// A record the model wants in the run directory beside the history (eroded elements, ...):
// a CSV file name, its header and rows appended since the last call.
struct EventLog {
  std::string file;    // e.g. "erosion.csv"
  std::string header;  // the CSV header line, without newline
  std::vector<std::string> rows;
};

// An energy a model's contacts book their work into, as a column of the history: its name and
// the record of Energies it reads (the time loop writes it from the row's energies).
struct EnergyColumn {
  const char* name;
  double Energies::*value;
};

// The points that carry a body's material (Model::body_points), and how far the material of
// each reaches beyond it: half the edge of a particle's cube of volume; 0 for a mesh node, which
// lies on the surface.
struct BodyPoints {
  std::vector<Vec3> position;
  std::vector<double> half_size;
};

// The stress of a body's points now (Model::body_stresses), as a preload phase prints it at
// the switch: the largest von Mises stress, and the range of the pressure -tr(sigma)/3
// (trusses: their axial stress as the uniaxial tensor).
struct BodyStress {
  std::size_t points = 0;
  double max_von_mises = 0.0;
  double min_pressure = 0.0, max_pressure = 0.0;
  // Folds in one point's stress.
  void add(const SymTensor& s) {
    const double v = von_mises(s), p = 0.0 - s.mean();  // 0 - 0 is +0, not -0
    if (points == 0) {
      max_von_mises = v;
      min_pressure = max_pressure = p;
    } else {
      max_von_mises = std::max(max_von_mises, v);
      min_pressure = std::min(min_pressure, p);
      max_pressure = std::max(max_pressure, p);
    }
    ++points;
  }
};

class Model {
 public:
  virtual ~Model() = default;
  // The step the next call of step() may take (the scene's factor applied).
  virtual double stable_time_step() const = 0;
  // What sets that step now and why, as the run summary names it when the step has fallen
  // (core/run_warnings.hpp): the element with the smallest critical step, the particle with
  // the largest wave speed + speed; "" when the model cannot say.
  virtual std::string time_step_setter() const { return {}; }
  // Advances by dt. Throws core::SimulationError naming the step, entity and field.
  virtual void step(double dt) = 0;
  // Multiplies every velocity the model integrates by `factor`, the damping of dynamic
  // relaxation (core/dynamic_relaxation.hpp): mesh nodes' v^{n+1/2}, rigid bodies' momenta and
  // angular momenta, particles' velocities and APIC affine velocities. Imposed components
  // (constraints' velocities, rigid bodies' fixed ones) keep their imposed values; 0 puts the
  // rest at rest. Positions and stresses do not change, and no energy column books the
  // kinetic energy it takes.
  virtual void scale_velocities(double factor) = 0;
  // Every point of body `body` moves at v (a mesh node its free components, a rigid body its
  // free translation with no spin; nodes bonded to particles follow them): a relaxation phase
  // holds the bodies with an initial velocity at rest, then sets them moving.
  virtual void set_body_velocity(int body, const Vec3& v) = 0;
  // Holds the deformable mesh nodes of body `body` at rest (every component imposed at zero) or
  // releases them to what was imposed before; nothing for particles and rigid bodies, whose
  // velocities a relaxation sets to zero after each step instead (zeroing a deformable mesh's
  // velocities after each step would halve the stable step's square: its stiffest mode then
  // grows at 0.9 of the critical step).
  virtual void hold_body(int /*body*/, bool /*hold*/) {}
  // Before the explicit phase (a relaxation phase ran the model to rest): the clock reads
  // `time` from here on.
  virtual void set_clock(double time) = 0;
  virtual long step_count() const = 0;
  virtual double time() const = 0;
  // Energies and per-body sums (one per scene body) of the current state.
  virtual Energies energies() const = 0;
  // Points that carry material state: particles and element integration points / trusses.
  virtual std::size_t particle_count() const = 0;
  virtual std::size_t element_count() const = 0;
  // Appends one frame of the model's fields to the writer.
  virtual void write_fields(FieldWriter& writer) = 0;
  // Stage timings in step order.
  virtual std::vector<StageTiming> stage_timings() const = 0;
  // Event rows produced since the last call (none by default).
  virtual std::vector<EventLog> take_events() { return {}; }
  // What the model warns of at the end of the run, one line each, for RunSummary::warnings
  // (failed points: eroded elements, failed particles); none by default.
  virtual std::vector<std::string> summary_warnings() const { return {}; }
  // What `afemp check` prints before the time step: the discretisation (grid, bodies, mesh
  // quality), and the stages one step runs with the reason for each.
  virtual std::string describe() const = 0;
  // Bytes held by the model's data (points, nodes, elements, grid, scratch).
  virtual std::size_t bytes() const = 0;
  // Probes (core/probes.hpp). resolve_probes finds, once at the start, the particle, node or
  // element each probe of the kinds the model holds names (by index, or nearest to a point);
  // it throws InputError naming the probe's line and key, and what exists, when one does not.
  // sample_probes writes probe_stride values per probe into out (probe k from k
  // probe_stride), in probe_columns order, for the probes of the kinds it holds: particle,
  // node, element, and its points' part of an extreme (merge_extreme; the caller fills out
  // with NaN first). Mean velocities are the time loop's, from energies(). An element that
  // is gone (eroded, converted into particles) leaves its NaN.
  virtual void resolve_probes(std::span<const ProbeSpec> probes) = 0;
  virtual void sample_probes(std::span<double> out) const = 0;
  // The points that carry body `body`'s material now: its particles and the nodes of its live
  // elements (Taylor, crater and hole metrics: analysis/reference_checks.cpp, analysis/study.cpp).
  virtual BodyPoints body_points(int body) const = 0;
  // How many of `points` lie inside the live hexahedra of body `body`, not on its outer surface
  // (where bodies touch): the run's check for bodies that come to overlap with no contact
  // between them (core/contact_warnings.hpp). 0 for a body without hexahedra.
  virtual std::size_t points_inside(int /*body*/, std::span<const Vec3> /*points*/) const {
    return 0;
  }
  // The energies the model's contacts declare (declare_energy_columns), which the history
  // writes after the body columns, each once and fixed for the run; none by default.
  virtual std::vector<EnergyColumn> energy_columns() const { return {}; }
  // Interface forces the history writes each row after those (penalty contacts, walls, rigid
  // bodies): the column names, fixed for the run, and their current values in that order.
  virtual std::vector<std::string> force_columns() const { return {}; }
  // The mechanisms of this model that take or give energy which no column of total() books
  // (an MPM contact's estimate, a kinematic catch at particles, the transfers' dissipation):
  // what the summary names when the balance does not close. None by default.
  virtual std::vector<std::string> unbooked_energies() const { return {}; }
  virtual void force_values(std::vector<double>& out) const { out.clear(); }
  // A checkpoint (core/checkpoint.hpp): saves the whole state that carries from one step to the
  // next through `archive`, or restores it into a model built from the same scene. Events must
  // have been taken (take_events) before saving.
  virtual void state(StateArchive& archive) = 0;
  // Before state() saves a checkpoint of a model divided among MPI ranks: gathers what the
  // checkpoint holds onto rank 0 (collective: every rank calls it, and the state() that follows
  // calls no other rank), so that rank 0 writes the file one process would and a failed write
  // on rank 0 leaves no rank waiting inside a gather. Nothing for a model in one process.
  virtual void prepare_checkpoint() {}
  // The scene's static or implicit phase (core/phases.hpp), before any step: solves the
  // equilibrium (static) or the implicit dynamics (Newmark, HHT-alpha) of the mesh bodies it
  // names, takes the solution as the model's state and sets the clock to the phase's end;
  // returns the energy the phase dissipated (0 for a static phase; an implicit one's numerical
  // damping, booked as Energies::damped). Each Newton iteration is printed to `log` when set.
  // Throws InputError for what the solve cannot take and SimulationError when a solve fails. A
  // model without meshes has nothing such a phase solves (check_scene refuses such a scene).
  virtual double run_implicit_phase(const PhaseSpec& phase, std::ostream* log);
  // Per scene body, the stress of its live points now (BodyStress); on ranks, of this rank's
  // points (the time loop folds the ranks' together).
  virtual std::vector<BodyStress> body_stresses() const = 0;
};

// The energies of a contact that books its impulses' work as the sliding energy: Energies::sliding
// (LS-DYNA's sliding interface energy) and friction's part of it, Energies::friction.
inline constexpr EnergyColumn kSlidingEnergies[] = {{"sliding", &Energies::sliding},
                                                    {"friction", &Energies::friction}};
// The energy the rigid walls took from mesh nodes (Energies::wall).
inline constexpr EnergyColumn kWallEnergy[] = {{"wall", &Energies::wall}};

// Appends the energy columns a contact declares to the model's, each once however many of its
// contacts declare it.
inline void declare_energy_columns(std::vector<EnergyColumn>& columns,
                                   std::span<const EnergyColumn> declared) {
  for (const EnergyColumn& d : declared)
    if (std::none_of(columns.begin(), columns.end(),
                     [&](const EnergyColumn& c) { return c.value == d.value; }))
      columns.push_back(d);
}

// The five columns of an interface force (a contact or a wall): NAME.fx, .fy, .fz, .normal,
// .tangential, appended to `columns`; and their values for the force f, split along the unit
// normal n (the lengths of its normal and tangential parts).
inline void append_force_columns(std::vector<std::string>& columns, const std::string& name) {
  for (const char* part : {".fx", ".fy", ".fz", ".normal", ".tangential"})
    columns.push_back(name + part);
}
inline void append_force_values(std::vector<double>& out, const Vec3& f, const Vec3& n) {
  const double fn = dot(f, n);
  out.insert(out.end(), {f.x, f.y, f.z, fn < 0.0 ? -fn : fn, norm(f - fn * n)});
}

}  // namespace afemp::core
