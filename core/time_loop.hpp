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
#include "core/model.hpp"
#include "core/output/field_writer.hpp"
#include "core/scene.hpp"

namespace afemp::core {

struct RunOptions {
  std::string output_directory;  // empty: no output files at all (tests, benchmarks)
  bool write_fields = true;
  // Called about every progress_seconds of wall time (and at the end).
  std::function<void(const Progress&)> progress;
  double progress_seconds = 0.5;
  // Asked before each step: true ends the run there, with the final history row, frame and
  // summary written (`afemp run` asks whether SIGINT or SIGTERM came, core/interrupt.hpp).
  std::function<bool()> stop_requested;
};

class EventFiles;
class HistoryWriter;
class ProbeRecorder;

// The loop of one run, a step at a time (the library's Simulation steps it;
// analysis::run drives it to the end): the constructor writes the first history row and frame, step() advances the
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
  // The final history row, probe sample and frame, and the summary (without the scene's
  // reference checks: analysis/reference_checks.hpp adds them).
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
  std::vector<double> forces_;  // the model's force values of a history row
  Vec3 travelled_, last_velocity_;
  double last_time_ = 0.0;
  bool through_ = false;
  int rows_beyond_ = 0;  // consecutive history rows with the energy balance beyond its limit
  double dt_ = 0.0;
  double next_output_ = 0.0, next_progress_ = 0.0, last_error_ = 0.0;
  double next_history_ = 0.0;      // [run] history_interval: the next row's time
  std::size_t next_listed_ = 0;    // [run] output_times: the next listed frame
  bool last_step_recorded_ = true;  // the last step wrote a history row (the start did)
};

}  // namespace afemp::core
