// Sizes a scene before anything is allocated: the particles and elements its bodies will make,
// estimated from their shapes (a shape's volume over the particle spacing or element size
// cubed; lists and meshes given as arrays by their counts; mesh files are left to their
// reader, which holds them in memory once), the memory they will take, and what this machine
// has available (Linux's MemAvailable). make_model refuses a scene that cannot fit before
// building it, naming the body that makes the most points and both figures.
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/source_text.hpp"  // readable_count

namespace afemp::core {

struct SizeEstimate {
  double particles = 0.0, elements = 0.0;
  double bytes = 0.0;     // at bytes_per_point each
  int largest_body = -1;  // the body that makes the most points
  double largest_points = 0.0;
  // The lower of the bytes a particle and an element take in the solvers, measured by `afemp
  // check` on the examples (319-380); the estimate is a floor, so a refusal is certain.
  static constexpr double bytes_per_point = 300.0;
};

SizeEstimate estimate_size(const Scene& scene);
// MemAvailable from /proc/meminfo in bytes, or 0 where it cannot be read.
double available_memory();
// Throws InputError (at the largest body's line, key 'bodies') when the estimate exceeds the
// available memory, with both figures.
void refuse_oversized_scene(const Scene& scene);

// The nominal pace for wall-time estimates before a run has a pace of its own: 1.5 million
// point-steps a second per thread, a fifth of COLUMN-G's 7.5 million on one thread of the
// 2-core development machine (bench/README.md), for scenes with plasticity, contact and
// coupling (the restart test's scene, tests/coupling/test_restart.cpp: 2.5 million per thread
// there). An estimate to flag runs of days, not a promise.
inline constexpr double nominal_point_steps_per_thread_second = 1.5e6;
// Seconds `point_steps` take on `threads` at the nominal pace.
double estimated_wall_seconds(double point_steps, int threads);
// The steps a scene plans at step dt: to its end time, or max_steps when that comes first.
double planned_steps(const Scene& scene, double dt);
// A duration as a person reads it: "45 s", "3.2 min", "5.1 h", "12.4 days", "3.1e+04 years".
std::string readable_duration(double seconds);
// What `afemp check` and `run` warn when a run is estimated to take more than a day:
// `point_steps` (points x steps to the end) at the nominal pace on `threads`; "" below a day.
std::string wall_time_warning(double point_steps, int threads);
// What `afemp check` and `run` warn of a run's size before it starts, for `points` particles
// and elements at step dt on `threads`: a step count to the end time past a billion (a unit
// slip far more often than a plan; not where [run] max_steps bounds the run), or else a wall
// time past a day (wall_time_warning).
std::vector<std::string> size_warnings(const Scene& scene, double points, double dt, int threads);
// The same from a run's own pace: after `elapsed` seconds it reached `fraction` of its end
// time; "" while elapsed is under 20 s or the rest is under a day.
std::string pace_warning(double elapsed, double fraction);

}  // namespace afemp::core
