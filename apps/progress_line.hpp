// How `afemp run` reports progress: one live line on a terminal, plain periodic lines
// otherwise (logs, CI), and the end-of-run summary.
#pragma once

#include <cstdio>

#include "afemp/run.hpp"
#include "afemp/scene.hpp"

namespace afemp::apps {

class ProgressReporter {
 public:
  explicit ProgressReporter(std::FILE* out);
  void operator()(const Progress& p);
  // Ends the live line so that following output starts on a fresh line.
  void finish();
  bool live() const { return live_; }
  // Seconds between reports suited to the output: often on a terminal, rarely in a log.
  double interval() const { return live_ ? 0.25 : 10.0; }

 private:
  std::FILE* out_;
  bool live_;
  bool pending_newline_ = false;
  bool pace_warned_ = false;
};

void print_summary(std::FILE* out, const Scene& scene, const RunSummary& s);

}  // namespace afemp::apps
