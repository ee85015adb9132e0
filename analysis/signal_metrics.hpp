// Measures of probe histories (docs/study-format.md, metrics "wave_front" and "frequency"):
// when a wave arrives at a probe, the speed of a front from the arrival times at probes along
// its path, and a history's first natural frequency.
#pragma once

#include <span>

namespace afemp::analysis {

// The first time |q(t) - q(t_0)| reaches `fraction` of its largest value over the history,
// linearly interpolated between the samples around it. NaN when q never departs from q(t_0).
double arrival_time(std::span<const double> t, std::span<const double> q, double fraction);

// The front's speed: the least-squares slope of distance against arrival time over the
// probes (with two: their distance over their time difference). NaN with fewer than two, or
// when the arrivals are all at one time.
double front_speed(std::span<const double> distance, std::span<const double> arrival);

// The first natural frequency of a history: the mean zero-crossing period of q - mean(q).
// Each crossing's time is interpolated linearly between the samples around it; with n
// crossings at t_1 .. t_n, f = (n - 1) / (2 (t_n - t_1)) (half a period between successive
// crossings). NaN with fewer than two crossings. The history should span whole periods (or
// many), or the mean is off and the crossings with it; a signal dominated by higher modes
// crosses more often.
double zero_crossing_frequency(std::span<const double> t, std::span<const double> q);

}  // namespace afemp::analysis
