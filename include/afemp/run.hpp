// What a run reports: its summary (steps, wall time, energies, reference checks, probe
// histories), the progress it reports while it runs, and the stage timings of a step.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/probes.hpp"

namespace afemp::core {

/// Wall seconds and calls of one named stage of a model's step.
struct StageTiming {
  std::string name{};
  long count = 0;
  double seconds = 0.0;
};

/// Progress of a run, reported about every RunOptions::progress_seconds of wall time.
struct Progress {
  long step = 0;
  double time = 0.0, dt = 0.0, end_time = 0.0;
  double elapsed_seconds = 0.0;
  double energy_error = 0.0;
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
  std::size_t field_frames = 0;
  /// Set when [run] terminate stopped the run before end_time: what ended it.
  std::string terminated{};
  /// Set when RunOptions::stop_requested ended the run before its end (a signal, for
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
using core::ReferenceCheck;
using core::RunSummary;
using core::StageTiming;
using core::TaylorMeasures;
}  // namespace afemp
