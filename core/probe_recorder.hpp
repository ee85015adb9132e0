// Records the scene's probes during a run (core/probes.hpp): each probe's rows in memory, for
// RunSummary::probes and the study metrics, and, with a run directory, in
// DIRECTORY/probes/NAME.csv ("time," then probe_columns, one row per sample, flushed as it
// goes; "nan" where the entity is gone).
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "afemp/probes.hpp"
#include "core/time_loop.hpp"

namespace afemp::core {

class ProbeRecorder {
 public:
  // Resolves the probes on the model (Model::resolve_probes: throws InputError for a probe
  // naming what the model does not have) and opens their files when `directory` is not empty.
  // `resume`: the files of an earlier run are continued by state() (a restart) instead.
  ProbeRecorder(Model& model, const std::vector<ProbeSpec>& probes, const std::string& directory,
                bool resume = false);
  // Saves or restores (a checkpoint) the rows so far, the next sample times and the files'
  // lengths; restoring cuts each file to its length then and appends from there.
  void state(StateArchive& archive);
  // Samples the probes due at the model's time: a probe without interval at each history row
  // (history_row), one with an interval once the next multiple of it is reached; `last`:
  // every probe not yet sampled at this time (the end of the run).
  void sample(const Model& model, bool history_row, bool last = false);
  std::vector<ProbeSeries> take() { return std::move(series_); }

 private:
  std::vector<ProbeSpec> specs_;
  std::vector<ProbeSeries> series_;
  std::vector<double> next_;  // time of the next sample (probes with an interval)
  std::vector<char> due_;
  std::vector<double> buffer_;  // probe_stride values per probe
  // Force probes: per probe the model's force columns it reads (empty for other kinds).
  std::vector<std::vector<std::size_t>> force_columns_;
  std::vector<double> forces_;
  std::vector<double>
      force_row_;  // a force probe's values (more than probe_stride for a rigid body)
  std::vector<std::ofstream> files_;
  std::string directory_;  // DIRECTORY/probes, or empty
  std::string path(const ProbeSeries& s) const;
};

}  // namespace afemp::core
