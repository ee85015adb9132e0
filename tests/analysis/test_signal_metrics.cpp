// Arrival times, front speed and zero-crossing frequency (analysis/signal_metrics.hpp) on signals
// of known form: a ramp-up arriving at a known time, fronts at known speeds, and sine and
// square waves of known frequency sampled off their crossings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/signal_metrics.hpp"

namespace afemp::analysis {
namespace {

// A step from q0 to q0 + jump arriving at t_a and rising linearly over `rise`, sampled at dt.
void step_signal(double t_a, double rise, double q0, double jump, double dt, std::vector<double>& t,
                 std::vector<double>& q) {
  t.clear();
  q.clear();
  for (int i = 0; i <= 1000; ++i) {
    const double s = i * dt;
    t.push_back(s);
    q.push_back(q0 + jump * std::clamp((s - t_a) / rise, 0.0, 1.0));
  }
}

TEST(SignalMetrics, ArrivalIsWhereTheChangeReachesTheFractionOfItsPeak) {
  std::vector<double> t, q;
  // From -300 to 0 (an unloading wave): the change is +300; half of it at t_a + rise / 2.
  step_signal(0.4, 0.1, -300.0, 300.0, 0.0037, t, q);
  EXPECT_NEAR(arrival_time(t, q, 0.5), 0.45, 1e-12);  // linear between samples: exact on a ramp
  EXPECT_NEAR(arrival_time(t, q, 0.1), 0.41, 1e-12);
  step_signal(0.4, 0.1, 5.0, -2.0, 0.0037, t, q);  // a drop is a change too
  EXPECT_NEAR(arrival_time(t, q, 0.5), 0.45, 1e-12);
  const std::vector<double> still(t.size(), 1.0);
  EXPECT_TRUE(std::isnan(arrival_time(t, still, 0.5)));
}

TEST(SignalMetrics, FrontSpeedIsTheSlopeOfDistanceAgainstArrival) {
  const double c = 3352.0;
  const std::vector<double> d{0.0, 20.0, 45.0}, ta{0.001, 0.001 + 20.0 / c, 0.001 + 45.0 / c};
  EXPECT_NEAR(front_speed(d, ta), c, 1e-9 * c);
  const std::vector<double> d2{10.0, 30.0}, t2{0.002, 0.007};
  EXPECT_NEAR(front_speed(d2, t2), 20.0 / 0.005, 1e-9);
  EXPECT_TRUE(std::isnan(front_speed(std::vector<double>{1.0}, std::vector<double>{1.0})));
}

TEST(SignalMetrics, ZeroCrossingFrequencyOfSineAndSquareWaves) {
  const double f = 7.3, offset = 2.5;
  std::vector<double> t, sine, square;
  // Ten whole periods sampled at an interval that does not divide the period.
  const double dt = 1.0 / (f * 97.3);
  for (double s = 0.0; s <= 10.0 / f; s += dt) {
    t.push_back(s);
    sine.push_back(offset + std::sin(2.0 * std::numbers::pi * f * s + 0.3));
    square.push_back(offset + (std::sin(2.0 * std::numbers::pi * f * s + 0.3) >= 0.0 ? 1.0 : -1.0));
  }
  EXPECT_NEAR(zero_crossing_frequency(t, sine), f, 2e-3 * f);
  // The square wave's crossings are interpolated across one sample: within dt of each.
  EXPECT_NEAR(zero_crossing_frequency(t, square), f, 2e-2 * f);
  EXPECT_TRUE(std::isnan(zero_crossing_frequency(t, std::vector<double>(t.size(), 1.0))));
}

}  // namespace
}  // namespace afemp::analysis
