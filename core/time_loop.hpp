// The time loop every run goes through, whatever discretises it: a Model (the MPM solver, the
// FE solver, later their coupling) is advanced at its stable step to the end time, with field
// output (HDF5 + XDMF), the history CSV, the energy balance, progress reports and the guard:
// a model that throws core::SimulationError stops the run, and what was written stays on disk.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/run.hpp"
#include "core/model.hpp"
#include "core/output/field_writer.hpp"
#include "core/run_warnings.hpp"
#include "core/scene.hpp"

namespace afemp::core {

struct RelaxationResult;

struct RunOptions {
  std::string output_directory;  // empty: no output files at all (tests, benchmarks)
  bool write_fields = true;
  // Called about every progress_seconds of wall time (and at the end).
  std::function<void(const Progress&)> progress;
  double progress_seconds = 0.5;
  // Asked before each step of run(): true ends the run there; finish() then writes a
  // checkpoint, the final history row, frame and summary (`afemp run` asks whether SIGINT or
  // SIGTERM came, afemp/interrupt.hpp).
  std::function<bool()> stop_requested;
  // Asked after each step: true writes a checkpoint there and the run goes on (`afemp run`
  // asks whether SIGUSR1 came; the answer must clear the request).
  std::function<bool()> checkpoint_requested;
  // A checkpoint file (core/checkpoint.hpp) to continue from: the model, built from the same
  // scene, takes its state, and the run's files in output_directory are continued from their
  // lengths then (rows, probe samples and frames written after it are dropped and written
  // again). Throws CheckpointError naming the scene keys that changed, if any.
  std::string restart_from;
  // The static and implicit phases' Newton iterations, a relaxation's checks and each phase's
  // switch are printed here, one line each, when set (the iterations are written to
  // OUTPUT/static_phase.csv and implicit_phase.csv in any case).
  std::ostream* phase_log = nullptr;
  // Set when the model is divided among MPI ranks (docs/parallel.md): every rank runs this loop
  // in step, its model's calls collective. `agree` gives the value every rank takes for one each
  // rank passes (the largest): the wall time the progress and the wall-time checkpoints go by,
  // whether a checkpoint was written, so that every rank decides alike. A failure on one rank
  // writes no last frame (the ranks that did not fail cannot join its gather); one every rank
  // meets at once (the energy guard, a failed static or implicit phase) writes it together.
  std::function<double(double)> agree;
  // This process's rank and the ranks (with agree). Rank 0 writes the run's files and its
  // checkpoints, the whole model's as one process's (Model::prepare_checkpoint); another rank's
  // output_directory is a scratch copy nobody reads, which a restart starts anew rather than
  // continues, and it writes no checkpoint.
  int rank = 0, ranks = 1;
  // On ranks, for a static or implicit phase, whose sparse solve assembles the whole model in
  // one process (TimeLoop::solve_phase_on_rank_0): a new model of the scene, undivided, that
  // rank 0 solves the phase in, and rank 0's bytes handed to every rank (the others' replaced).
  std::function<std::unique_ptr<Model>()> whole_model;
  std::function<void(std::vector<std::byte>&)> from_rank_0;
  // On ranks: each value summed over the ranks (the same on every rank).
  std::function<void(std::span<double>)> add_over_ranks;
};

class EventFiles;
class OverlapCheck;
class StateArchive;
class HistoryWriter;
class ProbeRecorder;

// The loop of one run (the library's Simulation and analysis::run drive it): the constructor
// writes the first history row and frame, step() advances the model and writes what falls due,
// run() steps to the end, finish() writes the final row and frame and the summary. Throws
// core::SimulationError from the model after writing what led up to it.
class TimeLoop {
 public:
  TimeLoop(Model& model, const Scene& scene, const RunOptions& options);
  ~TimeLoop();
  TimeLoop(const TimeLoop&) = delete;
  TimeLoop& operator=(const TimeLoop&) = delete;
  // Whether the run has reached scene.run.end_time, max_steps or [run] terminate.
  bool finished() const;
  // One step at the stable step, cut to land on `until` (at most the end time) and on the start
  // of the next static or implicit phase. A scene's static, implicit or relaxation phase is one
  // step when the clock stands at its start, whole whatever `until` says: the model then
  // stands at the phase's end.
  void step(double until);
  // Steps until finished(), calling after_step after each step, or until
  // RunOptions::stop_requested answers true before a step (the run is then stopped).
  void run(const std::function<void()>& after_step = {});
  // The final history row, probe sample and frame, and the summary (without the scene's
  // reference checks: analysis/reference_checks.hpp adds them). A stopped run first writes a
  // checkpoint of the state after its last whole step, before the final row and frame (a
  // restart drops those and goes on as if never stopped); its summary says interrupted, with
  // the checkpoint or why none could be written.
  RunSummary finish();
  // Writes a checkpoint of the state now into OUTPUT/checkpoints (keeping the newest
  // [run] checkpoint_keep) and returns its path; "" when the run has no output directory.
  // `reason` is kept in its header. Throws CheckpointError (the previous checkpoints intact)
  // when it cannot be written, e.g. on a full disk.
  std::string checkpoint(const std::string& reason);
  // The model's energies with what a relaxation phase's damping took (Energies::damped).
  Energies energies() const;
  // The checkpoints written by this loop, and the step the run continued from (0: none).
  int checkpoints_written() const { return checkpoints_written_; }
  long restarted_at() const { return restarted_at_; }

 private:
  void restore(const std::string& path);
  // A static, implicit or relaxation phase (core/phases.hpp), one step of the loop when the
  // clock reaches its start: the model solves or relaxes it, and its state at the phase's end
  // gets a history row, a frame and a checkpoint (a last phase's: the run's final row and
  // frame).
  void run_phase(const PhaseSpec& phase);
  // Dynamic relaxation (core/dynamic_relaxation.hpp) with a history row at each check; the
  // bodies with an initial velocity held at rest and set moving at the end; the clock then
  // reads the phase's end.
  void run_relaxation(const PhaseSpec& phase);
  // A static or implicit phase on ranks: rank 0 gathers the state (as for a checkpoint), solves
  // the phase in an undivided model of its own (RunOptions::whole_model), writes its events and
  // hands the state it ends in to every rank, which each takes its part of as a restart does.
  // Returns the energy the phase dissipated. A solve that fails throws on every rank: rank 0
  // its own error, the others one that names it.
  double solve_phase_on_rank_0(const PhaseSpec& phase);
  // To RunOptions::phase_log: the force the damping held on each body at convergence.
  void print_damping_force(const RelaxationResult& r) const;
  // What the explicit phase starts from, to RunOptions::phase_log: the energies, and per body
  // its largest von Mises stress and its range of pressure (Model::body_stresses, every rank's:
  // on ranks it is called on every rank, collective, whatever its phase_log).
  void print_switch(const PhaseSpec& phase) const;
  void visit(StateArchive& archive);
  double elapsed() const;
  Vec3 mean_velocity(const Energies& e) const;
  // A history row (and the terminate and energy guards); returns the energy-balance error.
  double record(double dt);
  // A run stopped as unstable (SimulationError from the model or the energy guard): the
  // model's events so far, and a last frame of the state it stopped in, NaN and all, so that
  // where it went bad can be seen; then the error goes on. On ranks only when every rank fails
  // at once (every_rank: the energy guard, a static or implicit phase solved on rank 0).
  void keep_failure(bool every_rank = false);

  Model& model_;
  const Scene& scene_;
  RunOptions options_;
  std::chrono::steady_clock::time_point start_;
  std::unique_ptr<ProbeRecorder> probes_;
  std::unique_ptr<FieldWriter> frames_;
  std::unique_ptr<HistoryWriter> history_;
  std::unique_ptr<EventFiles> events_;
  RunSummary sum_;
  RunWarnings warnings_;
  std::unique_ptr<OverlapCheck> overlaps_;  // null: no pair of bodies to check
  double max_kinetic_ = 0.0;
  std::vector<EnergyColumn> energy_columns_;  // the model's, fixed for the run
  std::vector<double> forces_;                // the model's force values of a history row
  Vec3 travelled_, last_velocity_;
  double last_time_ = 0.0;
  bool through_ = false;
  int rows_beyond_ = 0;  // consecutive history rows with the energy balance beyond its limit
  double dt_ = 0.0;
  double next_output_ = 0.0, next_progress_ = 0.0, last_error_ = 0.0;
  double next_history_ = 0.0;       // [run] history_interval: the next row's time
  std::size_t next_listed_ = 0;     // [run] output_times: the next listed frame
  bool last_step_recorded_ = true;  // the last step wrote a history row (the start did)
  double saving_wall_ = 0.0;        // the agreed wall seconds a checkpoint saves
  double wall_offset_ = 0.0;        // wall seconds of the run before a restart
  double next_checkpoint_ = 1e300;  // [run] checkpoint_every: the next one's time
  double next_checkpoint_wall_ = 1e300;
  int checkpoints_written_ = 0;
  long restarted_at_ = 0;
  bool stopped_ = false;  // RunOptions::stop_requested ended run()
  double damped_ = 0.0;   // Energies::damped
};

}  // namespace afemp::core
