// The time loop every run goes through, whatever discretises it: a Model (the MPM solver, the
// FE solver, later their coupling) is advanced at its stable step to the end time, with field
// output (HDF5 + XDMF), the history CSV, the energy balance, progress reports and the guard:
// a model that throws core::SimulationError stops the run, and what was written stays on disk.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/run.hpp"
#include "core/output/field_writer.hpp"
#include "core/scene.hpp"

namespace afemp::core {

// A record the model wants in the run directory beside the history (eroded elements, ...):
// a CSV file name, its header and rows appended since the last call.
struct EventLog {
  std::string file;    // e.g. "erosion.csv"
  std::string header;  // the CSV header line, without newline
  std::vector<std::string> rows;
};

// The points that carry a body's material (Model::body_points), and how far the material of
// each reaches beyond it: half the edge of a particle's cube of volume; 0 for a mesh node, which
// lies on the surface.
struct BodyPoints {
  std::vector<Vec3> position;
  std::vector<double> half_size;
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
  // elements (Taylor, crater and hole metrics: core/reference_checks.cpp, coupling/study.cpp).
  virtual BodyPoints body_points(int body) const = 0;
};

struct RunOptions {
  std::string output_directory;  // empty: no output files at all (tests, benchmarks)
  bool write_fields = true;
  // Called about every progress_seconds of wall time (and at the end).
  std::function<void(const Progress&)> progress;
  double progress_seconds = 0.5;
};

class EventFiles;
class HistoryWriter;
class ProbeRecorder;

// The loop of one run, a step at a time (the library's Simulation steps it; run() below drives
// it to the end): the constructor writes the first history row and frame, step() advances the
// model and writes what falls due, finish() writes the final row and frame and the summary.
// Throws core::SimulationError from the model after writing what led up to it.
class TimeLoop {
 public:
  TimeLoop(Model& model, const Scene& scene, const RunOptions& options);
  ~TimeLoop();
  TimeLoop(const TimeLoop&) = delete;
  TimeLoop& operator=(const TimeLoop&) = delete;
  // Whether the run has reached scene.run.end_time, max_steps or [run] terminate.
  bool finished() const;
  // One step at the stable step, cut to land on `until` (at most the end time).
  void step(double until);
  // The final history row, probe sample and frame, and the summary with the reference checks.
  RunSummary finish();

 private:
  double elapsed() const;
  Vec3 mean_velocity(const Energies& e) const;
  // A history row (and the terminate and energy guards); returns the energy-balance error.
  double record(double dt);

  Model& model_;
  const Scene& scene_;
  RunOptions options_;
  std::chrono::steady_clock::time_point start_;
  std::unique_ptr<ProbeRecorder> probes_;
  std::unique_ptr<FieldWriter> frames_;
  std::unique_ptr<HistoryWriter> history_;
  std::unique_ptr<EventFiles> events_;
  RunSummary sum_;
  double max_kinetic_ = 0.0;
  Vec3 travelled_, last_velocity_;
  double last_time_ = 0.0;
  bool through_ = false;
  int rows_beyond_ = 0;  // consecutive history rows with the energy balance beyond its limit
  double dt_ = 0.0;
  double next_output_ = 0.0, next_progress_ = 0.0, last_error_ = 0.0;
};

// Runs `model` to scene.run.end_time (or max_steps, or [run] terminate). Throws core::SimulationError from the
// model after flushing what was written.
RunSummary run(Model& model, const Scene& scene, const RunOptions& options);

}  // namespace afemp::core
