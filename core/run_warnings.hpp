// The warnings of a run's summary (RunSummary::warnings) from what the time loop saw on the
// way, so that a run that ends with numbers is not read as a clean one: hourglass energy past
// 10 % of the internal energy (LS-DYNA's guideline), an energy-balance error past 5 %, a stable
// step that fell more than 10-fold (and what set it), mass that left the model; then the
// model's own (Model::summary_warnings: failed points).
#pragma once

#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "core/model.hpp"

namespace afemp::core {

class StateArchive;

class RunWarnings {
 public:
  // At the start: the run's first stable step, which a fall is measured from.
  void start(double first_step) { first_step_ = first_step; }
  // A history row at `time`: its energies and energy-balance error.
  void row(double time, const Energies& e, double error);
  // A stable step below every earlier one, taken at `time` (the loop calls this only then).
  // Once it is 10-fold below the first, the model says what sets it, again at each further
  // 1 % down: a falling step costs a few hundred scans of the model at most, not one a step.
  void new_low(double step, double time, const Model& model);
  // The warnings at the end, one line each.
  std::vector<std::string> summary(const Model& model, const Energies& initial,
                                   const Energies& final, double final_error) const;
  // A checkpoint: what was seen so far.
  void state(StateArchive& a);

 private:
  double first_step_ = 0.0;
  double hourglass_peak_ = 0.0, hourglass_time_ = 0.0;  // largest hourglass / internal
  double hourglass_peak_energy_ = 0.0, hourglass_peak_internal_ = 0.0;  // both then
  double error_peak_ = 0.0, error_time_ = 0.0;      // the error of largest magnitude
  double low_ = 1e300, low_time_ = 0.0;             // the smallest stable step
  double setter_step_ = 1e300, setter_time_ = 0.0;  // when the model was last asked
  std::string setter_;                              // and what it said
};

}  // namespace afemp::core
