// A whole run: the time loop around MpmSolver with field output (HDF5 + XDMF), the history
// CSV, the energy balance, progress reports and the NaN/Inf guard. The guard stops the run
// with the step, particle and field; everything written before stays on disk.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/taylor_metrics.hpp"

namespace afemp::mpm {

// Relative energy-balance error: (E - E0 - W_ext) / max(E0 + |W_ext|, max kinetic so far),
// E = kinetic + internal. The denominator is the energy the run has handled.
double energy_balance_error(const Energies& now, const Energies& initial, double max_kinetic);

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

struct RunSummary {
  long steps = 0;
  double time = 0.0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0;
  double min_dt = 0.0, max_dt = 0.0;  // of the stable step (the last step may be shorter)
  std::size_t particles = 0;
  Energies initial, final;
  double energy_error = 0.0;      // at the end
  double max_energy_error = 0.0;  // largest magnitude over the history rows
  std::vector<long> stage_counts;
  std::vector<double> stage_seconds;  // wall seconds per plan stage
  std::size_t field_frames = 0;
  std::optional<TaylorMeasures> taylor;  // when the scene states a Taylor reference
  double taylor_error = 0.0;
};

class Simulation {
 public:
  explicit Simulation(const core::Scene& scene);
  MpmSolver& solver() { return solver_; }
  const MpmSolver& solver() const { return solver_; }
  // Runs to scene.run.end_time (or max_steps). Throws core::SimulationError from the guard
  // after flushing what was written.
  RunSummary run(const RunOptions& options);

 private:
  const core::Scene& scene_;
  MpmSolver solver_;
};

}  // namespace afemp::mpm
