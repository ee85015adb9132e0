// What a run reports: its size estimated before it starts, the progress it reports while it
// runs, its summary (steps, wall time, energies, reference checks, probe histories) and the
// stage timings of a step; and the numbers and durations as `afemp` writes them.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/probes.hpp"

namespace afemp::core {

/// How a run divided among MPI ranks keeps its ranks' loads even (docs/parallel.md): every
/// `every` steps each rank's cost since the last check is compared with the ranks' mean; above
/// `imbalance` times the mean, the grid's blocks are split among the ranks anew, each block
/// weighted by its particles times its rank's cost per particle, and the particles move to their
/// new ranks. The cost: a rank's particle count (a run then repeats itself bit for bit), or the
/// wall seconds of its stages less those spent summing shared nodes with the other ranks
/// (which include waiting for them): faster where particles differ in cost (plastic flow,
/// damage), but a run then depends on the timings, to round-off. Nothing in one process.
struct RankBalance {
  enum class Cost { off, particles, time };
  Cost cost = Cost::particles;
  double imbalance = 1.1;
  long every = 100;
};

/// Wall seconds and calls of one named stage of a model's step.
struct StageTiming {
  std::string name{};
  long count = 0;
  double seconds = 0.0;
};

/// Progress of a run, reported about every SimulationOptions::progress_seconds of wall time.
struct Progress {
  long step = 0;
  double time = 0.0, dt = 0.0, end_time = 0.0;
  double elapsed_seconds = 0.0;
  double energy_error = 0.0;
};

/// The size of a run before it starts (`afemp check` prints it), at the nominal pace of 1.5
/// million point-steps a second per thread: an estimate to flag runs of days, not a promise
/// (plasticity, contact and coupling cost more, simple elastic particles less).
struct RunEstimate {
  double time_step = 0.0;      ///< the first step: the stable step x factor, or the fixed step
  double steps = 0.0;          ///< steps to the end time at that step
  double planned_steps = 0.0;  ///< the same, or [run] max_steps when that comes first
  std::size_t points = 0;      ///< particles and elements
  std::size_t bytes = 0;       ///< memory the model holds
  int threads = 1;             ///< thread_count()
  double wall_seconds = 0.0;   ///< points x planned_steps on `threads`
  /// A step count past a billion (a unit slip far more often than a plan) or, else, a wall
  /// time past a day: what `afemp check` and `afemp run` warn of.
  std::vector<std::string> warnings{};
};

/// Taylor-bar measures: final length L, impact-face diameter D and diameter W at 0.2 L0 from
/// the wall (Ma 2005, §2.3.2).
struct TaylorMeasures {
  double length = 0.0, impact_diameter = 0.0, bulge_diameter = 0.0;
};

/// A result compared with a reference the scene states ([reference]).
struct ReferenceCheck {
  std::string name;        ///< "velocity of rod (z)", "taylor mean error", "energy balance"
  double value = 0.0;      ///< what the run gave
  double reference = 0.0;  ///< what it is compared with
  double error = 0.0;      ///< relative error (the Taylor and energy checks: the error itself)
  double tolerance = 0.0;  ///< 0: report only
  bool passed() const { return tolerance <= 0.0 || error <= tolerance; }
};

/// What a finished run reports (afemp run prints it; Simulation::run and finish return it).
struct RunSummary {
  long steps = 0;
  double time = 0.0;
  double wall_seconds = 0.0;
  std::size_t particles = 0, elements = 0;
  std::size_t final_particles = 0;      ///< elements converted into particles add to them
  double point_steps_per_second = 0.0;  ///< (particles + elements) * steps / wall seconds
  double min_dt = 0.0, max_dt = 0.0;    ///< of the stable step (the last step may be shorter)
  Energies initial{}, final{};
  double energy_error = 0.0;      ///< at the end
  double max_energy_error = 0.0;  ///< largest magnitude over the history rows
  std::vector<StageTiming> stages{};
  int ranks =
      1;  ///< MPI ranks the run was divided among; with more than one, `stages` are rank 0's
  std::size_t field_frames = 0;
  /// Set when [run] terminate stopped the run before end_time: what ended it.
  std::string terminated{};
  /// Set when SimulationOptions::stop_requested ended the run before its end (a signal, for
  /// `afemp run`): the step and time it stopped at.
  bool interrupted = false;
  /// An interrupted run: the checkpoint written before it stopped (empty: none written, see
  /// checkpoint_error), to continue with `afemp run SCENE --restart DIR`.
  std::string checkpoint{};
  std::string checkpoint_error{};
  /// A restarted run: the step it continued from (0: it started at the beginning).
  long restarted_at = 0;
  std::optional<TaylorMeasures> taylor{};  ///< when the scene states a Taylor reference
  double taylor_error = 0.0;
  /// Every [reference] check, the Taylor one included, in the scene's order.
  std::vector<ReferenceCheck> checks{};
  /// Every probe's history ([[probes]]), in the scene's order, recorded with or without an
  /// output directory.
  std::vector<ProbeSeries> probes{};
  /// What the results should be read with, one line each (`afemp run` prints them last and
  /// writes them to warnings.txt in the run directory; the exit code stays 0): hourglass energy
  /// past 10 % of the internal energy, an energy-balance error past 5 %, a stable step that fell
  /// more than 10-fold and what set it, failed points, mass that left the model, bodies that
  /// came to overlap with no contact between them, and what the model adds of its own.
  std::vector<std::string> warnings{};
  bool checks_passed() const {
    for (const ReferenceCheck& c : checks)
      if (!c.passed()) return false;
    return true;
  }
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::Progress;
using core::RankBalance;
using core::ReferenceCheck;
using core::RunEstimate;
using core::RunSummary;
using core::StageTiming;
using core::TaylorMeasures;

/// A count as a person reads it: whole, with thousands separated ("1,250,000"); past a billion
/// in exponent form ("3.2e+10").
std::string readable_count(double count);
/// A duration as a person reads it: "45 s", "3.2 min", "5.1 h", "12.4 days", "3.1e+04 years".
std::string readable_duration(double seconds);
/// What a run's progress warns once it has a pace of its own: after `elapsed` wall seconds it
/// reached `fraction` of its end time; "" while elapsed is under 20 s or the rest is under a
/// day.
std::string pace_warning(double elapsed, double fraction);
}  // namespace afemp
