// The time loop every run goes through, whatever discretises it: a Model (the MPM solver, the
// FE solver, later their coupling) is advanced at its stable step to the end time, with field
// output (HDF5 + XDMF), the history CSV, the energy balance, progress reports and the guard:
// a model that throws core::SimulationError stops the run, and what was written stays on disk.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/energies.hpp"
#include "core/output/field_writer.hpp"
#include "core/scene.hpp"
#include "core/taylor_metrics.hpp"

namespace afemp::core {

// Wall seconds and calls of one named stage of a model's step.
struct StageTiming {
  std::string name;
  long count = 0;
  double seconds = 0.0;
};

// A record the model wants in the run directory beside the history (eroded elements, ...):
// a CSV file name, its header and rows appended since the last call.
struct EventLog {
  std::string file;    // e.g. "erosion.csv"
  std::string header;  // the CSV header line, without newline
  std::vector<std::string> rows;
};

class Model {
 public:
  virtual ~Model() = default;
  // The step the next call of step() may take (the scene's factor applied).
  virtual double stable_time_step() const = 0;
  // Advances by dt. Throws core::SimulationError naming the step, entity and field.
  virtual void step(double dt) = 0;
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
  // The Taylor-bar measures of scene body `body`, a cylinder.
  virtual TaylorMeasures measure_taylor(int body) const = 0;
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
  // The current positions of the points that carry body `body`'s material: its particles
  // and the nodes of its live elements (crater and hole metrics, coupling/study.cpp).
  virtual std::vector<Vec3> body_points(int body) const = 0;
};

struct Progress {
  long step = 0;
  double time = 0.0, dt = 0.0, end_time = 0.0;
  double elapsed_seconds = 0.0;
  double energy_error = 0.0;
};

struct RunOptions {
  std::string output_directory;  // empty: no output files at all (tests, benchmarks)
  bool write_fields = true;
  // Called about every progress_seconds of wall time (and at the end).
  std::function<void(const Progress&)> progress;
  double progress_seconds = 0.5;
};

// A result compared with a reference the scene states ([reference]).
struct ReferenceCheck {
  std::string name;        // "velocity of rod (z)", "taylor mean error", "energy balance"
  double value = 0.0;      // what the run gave
  double reference = 0.0;  // what it is compared with
  double error = 0.0;      // relative error (the Taylor and energy checks: the error itself)
  double tolerance = 0.0;  // 0: report only
  bool passed() const { return tolerance <= 0.0 || error <= tolerance; }
};

struct RunSummary {
  long steps = 0;
  double time = 0.0;
  double wall_seconds = 0.0;
  std::size_t particles = 0, elements = 0;
  std::size_t final_particles = 0;  // elements converted into particles add to them
  double point_steps_per_second = 0.0;  // (particles + elements) * steps / wall seconds
  double min_dt = 0.0, max_dt = 0.0;    // of the stable step (the last step may be shorter)
  Energies initial, final;
  double energy_error = 0.0;      // at the end
  double max_energy_error = 0.0;  // largest magnitude over the history rows
  std::vector<StageTiming> stages;
  std::size_t field_frames = 0;
  // Set when [run] terminate stopped the run before end_time: what ended it.
  std::string terminated;
  std::optional<TaylorMeasures> taylor;  // when the scene states a Taylor reference
  double taylor_error = 0.0;
  // Every [reference] check, the Taylor one included, in the scene's order.
  std::vector<ReferenceCheck> checks;
  // Every probe's history ([[probes]]), in the scene's order, recorded with or without an
  // output directory.
  std::vector<ProbeSeries> probes;
  bool checks_passed() const {
    for (const ReferenceCheck& c : checks)
      if (!c.passed()) return false;
    return true;
  }
};

// Runs `model` to scene.run.end_time (or max_steps, or [run] terminate). Throws core::SimulationError from the
// model after flushing what was written.
RunSummary run(Model& model, const Scene& scene, const RunOptions& options);

}  // namespace afemp::core
