// `afemp study`: runs each run of a study (analysis/study_file.hpp) to its end, measures its wall
// time and metrics, and writes a CSV row per run, a Markdown table, a log-log plot of the
// plotted metric's error against wall time, one line per method, and optionally a linear plot
// of one value against the runs' resolution beside its references (docs/study-format.md).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "analysis/study_file.hpp"

namespace afemp::analysis {

struct StudyRow {
  const StudyRun* run = nullptr;
  std::size_t particles = 0;  // at the end (conversion adds particles)
  std::size_t elements = 0;   // at the start
  long steps = 0;
  double wall_seconds = 0.0;  // of the time loop, no output written
  int threads = 0;
  double energy_error = 0.0;      // the energy-balance error at the end
  double max_energy_error = 0.0;  // its largest magnitude over the run
  std::vector<double> values;     // StudyResult::value_columns
  // StudyResult::error_columns (NaN: the run stopped, or has no reference for the metric)
  std::vector<double> errors;
  std::vector<double> references;  // StudyResult::reference_columns (NaN: none in this run)
  std::string stopped;             // the simulation error that stopped the run, if one did
  std::vector<std::string> over_tolerance;  // metrics whose error exceeds their tolerance
  bool ok() const { return stopped.empty() && over_tolerance.empty(); }
};

struct StudyResult {
  std::vector<std::string> value_columns;  // "taylor.L", ..., "velocity"
  std::vector<std::string> error_columns;  // "taylor.error", ... (metrics with a reference)
  // What each run was measured against, for those metrics: "taylor.reference_L", ...,
  // "crater.reference_depth", "crater.reference_diameter", "velocity.reference", or for a
  // metric with a band in any run "hole.reference_low", "hole.reference_high" (a single value
  // fills both).
  std::vector<std::string> reference_columns;
  std::vector<StudyRow> rows;
  // The plotted error of a row: the plot metric's error, or |energy error|.
  double plotted_error(const StudyPlan& plan, const StudyRow& row) const;
};

// A value's error against a scalar reference: for one value |v - v_ref| / |v_ref|; for a band,
// 0 inside it, else the distance to the nearer bound relative to that bound, (low - v) / |low|
// below and (v - high) / |high| above (one value is a band of no width). NaN for a NaN value.
double reference_error(double value, const ScalarReference& reference);

// Runs the study; `report` is called after each run with the result so far and its row.
StudyResult run_study(const StudyPlan& plan,
                      const std::function<void(const StudyResult&, const StudyRow&)>& report = {});

// The files written to `directory` (created if needed).
struct StudyFiles {
  std::string csv = "study.csv", markdown = "study.md", plot = "error_vs_time.svg";
  std::string value_plot = "value_vs_resolution.svg";  // with [study] plot_value
};
void write_study(const StudyPlan& plan, const StudyResult& result, const std::string& directory);

// One line of text per run for the terminal.
std::string describe_row(const StudyResult& result, const StudyRow& row);

}  // namespace afemp::analysis
