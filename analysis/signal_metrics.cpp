// Arrival times, front speed and zero-crossing frequency (analysis/signal_metrics.hpp).
#include "analysis/signal_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace afemp::analysis {

double arrival_time(std::span<const double> t, std::span<const double> q, double fraction) {
  const std::size_t n = std::min(t.size(), q.size());
  if (n == 0) return std::nan("");
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isnan(q[i])) peak = std::max(peak, std::abs(q[i] - q[0]));
  if (!(peak > 0.0)) return std::nan("");
  const double level = fraction * peak;
  for (std::size_t i = 1; i < n; ++i) {
    const double a = std::abs(q[i - 1] - q[0]), b = std::abs(q[i] - q[0]);
    if (b >= level) return b == a ? t[i] : t[i - 1] + (level - a) / (b - a) * (t[i] - t[i - 1]);
  }
  return std::nan("");
}

double front_speed(std::span<const double> distance, std::span<const double> arrival) {
  const std::size_t n = std::min(distance.size(), arrival.size());
  if (n < 2) return std::nan("");
  double mt = 0.0, md = 0.0;
  for (std::size_t i = 0; i < n; ++i) mt += arrival[i], md += distance[i];
  mt /= static_cast<double>(n), md /= static_cast<double>(n);
  double stt = 0.0, std_ = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    stt += (arrival[i] - mt) * (arrival[i] - mt);
    std_ += (arrival[i] - mt) * (distance[i] - md);
  }
  return stt > 0.0 ? std_ / stt : std::nan("");
}

double zero_crossing_frequency(std::span<const double> t, std::span<const double> q) {
  const std::size_t n = std::min(t.size(), q.size());
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += q[i];
  mean /= static_cast<double>(std::max<std::size_t>(n, 1));
  int crossings = 0;
  double first = 0.0, last = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double a = q[i - 1] - mean, b = q[i] - mean;
    if (!((a < 0.0 && b >= 0.0) || (a >= 0.0 && b < 0.0))) continue;
    const double tc = t[i - 1] + a / (a - b) * (t[i] - t[i - 1]);
    if (crossings++ == 0) first = tc;
    last = tc;
  }
  if (crossings < 2 || !(last > first)) return std::nan("");
  return (crossings - 1) / (2.0 * (last - first));
}

}  // namespace afemp::analysis
