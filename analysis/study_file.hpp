// A study: one or more scenes run over a list of variations, each run measured for its wall
// time and for metrics compared with reference values (docs/study-format.md). This file reads
// and checks the study file and builds each run's scene: the scene file with the run's
// overrides ("grid.cell" = 0.25) applied before the scene is checked, so a bad override is
// reported like any other scene error, with the study file and run named in front.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "core/scene.hpp"

namespace afemp::analysis {

// What a metric measures at the end of a run.
enum class MetricKind {
  taylor,      // a Taylor bar's L, D, W and the mean error (Ma 2005, eq 2-42)
  velocity,    // a body's mean velocity (one component or the magnitude): residual, rebound
  crater,      // a target's crater depth and diameter (analysis/crater_metrics.hpp)
  hole,        // the diameter of the hole in a plate (analysis/crater_metrics.hpp)
  wave_front,  // a front's speed from its arrival at probes (analysis/signal_metrics.hpp)
  frequency,   // a probe history's first natural frequency (analysis/signal_metrics.hpp)
  force,       // a force probe's value at the end: a platen's or support's reaction
};

// A crater's reference depth and diameter.
struct CraterReference {
  double depth = 0.0, diameter = 0.0;
};

// A scalar metric's reference: one value (low = high), or a band [low, high] the value should
// lie in, as two published laws bound a hole's diameter. Neither bound is 0 and both have one
// sign: the error is relative to the nearer bound.
struct ScalarReference {
  double low = 0.0, high = 0.0;
  bool band = false;  // written as [low, high]: listed and plotted as two bounds
};

// What a metric's value is compared with: a Taylor bar's L, D, W (its error is eq 2-42), a
// crater's depth and diameter (the mean of the two relative errors), the other kinds' scalar
// (analysis::reference_error); none: the value is reported only.
struct MetricReference {
  std::optional<TaylorReference> taylor;
  std::optional<CraterReference> crater;
  std::optional<ScalarReference> scalar;
  bool has_value() const { return taylor || crater || scalar; }
};

struct MetricSpec {
  MetricKind kind = MetricKind::velocity;
  std::string name;    // column prefix, unique in the study
  std::string body;    // the scene body it measures (every run's scene must have it); empty
                       // for wave_front, frequency and force, which read probes
  int component = -1;  // velocity: 0, 1, 2 for x, y, z; -1 for the magnitude
  // crater, hole: the impact axis, through `point` along the unit `normal` of the struck face.
  Vec3 point, normal;
  double ring = 0.0, threshold = 0.0;  // crater: ring width, drop that marks the crater
  double band = 0.0;                   // hole: half thickness of the slab about the mid-plane
  // wave_front: the probes along the path (two or more); frequency, force: one. Every run's
  // scene must have them; `quantity` is the column read.
  std::vector<std::string> probes;
  std::string quantity;
  double fraction = 0.5;  // wave_front: the arrival threshold, a fraction of the peak
  double until = 0.0;     // wave_front: > 0: only the samples up to this time count
  // The study-wide reference; a [[runs]] table may give its runs their own
  // (StudyRun::references).
  MetricReference reference;
  double tolerance = 0.0;  // > 0: a run whose error exceeds it fails the study
  SourceLocation where;
};

// The metric's value columns: NAME.L, NAME.D, NAME.W (taylor), NAME.depth, NAME.diameter
// (crater), NAME (the others).
std::vector<std::string> value_columns(const MetricSpec& m);

// One run: a scene and the overrides applied to it.
struct StudyRun {
  std::string method;                // the plot's line ("MPM", "FE", "AFEMP", ...)
  std::string label;                 // "MPM, resolution 0.5"
  std::optional<double> resolution;  // the resolution column (cell or element size, ...)
  std::string scene_path;            // resolved against the study file's folder
  // Overrides: a dotted path into the scene ("grid.cell", "bodies.bar.mesh.size") and the
  // value as TOML text.
  struct Override {
    std::string path;
    std::string value;
  };
  std::vector<Override> overrides;
  // One per metric, in StudyPlan::metrics' order: what this run is measured against, the
  // metric's study-wide reference unless the [[runs]] table gives its own (a crater struck at
  // its own speed has its own published depth).
  std::vector<MetricReference> references;
  SourceLocation where;  // the [[runs]] table
};

struct StudyPlan {
  std::string path;  // the study file
  std::string title;
  int threads = 0;  // OpenMP threads for every run; 0: the default
  // > 0: a run whose energy-balance error ever exceeds this in magnitude fails ("energy"):
  // the stability criterion of a time-step or scheme sweep.
  double energy_tolerance = 0.0;
  std::vector<MetricSpec> metrics;
  // The metric whose error is plotted against wall time ("energy": the energy-balance
  // error's magnitude); by default the first metric with a reference, else "energy".
  std::string plot;
  // A value column ("hole", "crater.depth") plotted against the runs' resolution, labelled
  // x_label (the resolution may be an impact speed); empty: no such plot.
  std::string plot_value;
  std::string x_label = "resolution";
  std::vector<StudyRun> runs;
  // Whether any run measures the metric (by its index) against a reference: the metric then
  // has an error column.
  bool has_reference(std::size_t metric) const;
};

// Reads and checks a study file (every run's scene is built once here, so a bad scene or
// override stops the study before anything runs). Throws InputError.
StudyPlan read_study(const std::string& path);
StudyPlan parse_study(const std::string& text, const std::string& path);

// The run's scene: its scene file with the overrides applied, checked by the scene parser.
// An element of a list of tables is picked by its `name` ("bodies.bar.mesh.size") or, for
// lists whose tables have none, by its index from 0 ("constraints.2.curve", "phases.0.end_time").
// Errors name the study file, the run and the override.
Scene build_run_scene(const StudyPlan& plan, const StudyRun& run);

const char* to_string(MetricKind k);

}  // namespace afemp::analysis
