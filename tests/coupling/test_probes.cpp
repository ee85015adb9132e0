// Scene probes ([[probes]], core/probes.hpp) against closed forms:
//  - rigid translation: an MPM block and a hexahedral block moving freely in one scene (the
//    coupled model) keep v0; a particle and a node probe read x0 + v0 t and v0, the mean
//    velocity probes read v0 and the final momentum / mass, and a box's largest vz is the
//    faster body's v0 at one of its points;
//  - a fixed-free elastic bar (nu = 0, so the bar speed c = sqrt(E / rho) holds exactly in 1D)
//    moving at v0 into its fixed end: the compressive front runs at c (arrival at two node
//    probes), the free end's velocity is a square wave of period 4 L / c (first axial mode,
//    f = c / (4 L)), and behind the front an element probe reads sigma_zz = -rho c v0, so
//    pressure rho c v0 / 3 and von Mises rho c v0 (uniaxial stress); the same bar of particles
//    gives f = c / (4 L) from a particle probe;
//  - an element that erodes leaves NaN rows from then on; a probe naming a node, element or
//    particle the body lacks stops the run with the probe's line, key and the body's range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/reference_checks.hpp"
#include "analysis/signal_metrics.hpp"
#include "core/scene.hpp"
#include "core/time_loop.hpp"
#include "coupling/make_model.hpp"
#include "fem/fe_model.hpp"
#include "fixed_free_bar_scene.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp::coupling {
namespace {

core::RunSummary run_text(const std::string& text, const std::string& directory = "") {
  const core::Scene scene = core::parse_scene(text, "scene.toml");
  const auto model = make_model(scene);
  core::RunOptions options;
  options.output_directory = directory;
  options.write_fields = false;
  return analysis::run(*model, scene, options);
}

const core::ProbeSeries& series(const core::RunSummary& s, const std::string& name) {
  for (const core::ProbeSeries& p : s.probes)
    if (p.name == name) return p;
  ADD_FAILURE() << "no probe " << name;
  return s.probes.front();
}

// Two free blocks, far apart: particles at (0, 0, 30) m/s, hexahedra at (20, 0, -50) m/s.
const std::string free_blocks = R"(
[run]
end_time = 0.02
history_every = 7
[grid]
cell = 1.0
min = [-2, -2, -2]
max = [12, 6, 10]
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "cube"
material = "steel"
shape = { box = { min = [0, 0, 2], max = [2, 2, 4] } }
velocity = [0, 0, 30]
[[bodies]]
name = "brick"
discretisation = "hexahedra"
material = "steel"
shape = { box = { min = [20, 0, 0], max = [22, 2, 2] } }
mesh = { divisions = [2, 2, 2] }
velocity = [20, 0, -50]
[[probes]]
name = "corner"
particle = { body = "cube", near = [2, 2, 4] }
[[probes]]
name = "node"
node = { body = "brick", index = 26 }
interval = 0.0025
[[probes]]
name = "cube_v"
mean_velocity = "cube"
[[probes]]
name = "brick_v"
mean_velocity = "brick"
[[probes]]
name = "fastest_up"
extreme = { field = "vz", of = "max", box = { min = [-5, -5, -5], max = [30, 5, 10] } }
[[probes]]
name = "fastest"
extreme = { field = "speed", box = { min = [-5, -5, -5], max = [30, 5, 10] } }
[[probes]]
name = "cube_top"
extreme = { field = "z", of = "max", box = { min = [-5, -5, -5], max = [30, 5, 10] }, body = "cube" }
[[probes]]
name = "brick_bottom"
extreme = { field = "z", of = "min", box = { min = [-5, -5, -5], max = [30, 5, 10] }, body = "brick" }
)";

TEST(Probes, RigidTranslationReadsX0PlusV0TAndMeanVelocityIsMomentumOverMass) {
  const core::Scene scene = core::parse_scene(free_blocks, "scene.toml");
  const auto model = make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, {});
  ASSERT_EQ(s.probes.size(), 8u);
  // The particle nearest (2, 2, 4): the lattice's top corner particle at (1.75, 1.75, 3.75).
  const core::ProbeSeries& p = series(s, "corner");
  ASSERT_EQ(p.columns.size(), 9u);
  ASSERT_GE(p.rows(), 10u);
  for (std::size_t r = 0; r < p.rows(); ++r) {
    EXPECT_NEAR(p.at(r, 0), 1.75, 1e-12);
    EXPECT_NEAR(p.at(r, 2), 3.75 + 30.0 * p.time[r], 1e-9);
    EXPECT_NEAR(p.at(r, 5), 30.0, 1e-9);
    EXPECT_NEAR(p.at(r, 6), 0.0, 1e-9);  // no stress in a rigid motion
  }
  // Node 26 of the 3 x 3 x 3 nodes is the last: (22, 2, 2). At the start, then at the first
  // step end at or past each multiple of the interval (the last: the end, 0.02).
  const core::ProbeSeries& n = series(s, "node");
  ASSERT_EQ(n.rows(), 9u);
  for (std::size_t r = 0; r < n.rows(); ++r) {
    EXPECT_GE(n.time[r], 0.0025 * static_cast<double>(r) * (1.0 - 1e-9));
    EXPECT_LT(n.time[r], 0.0025 * static_cast<double>(r) + s.max_dt);
    EXPECT_NEAR(n.at(r, 0), 22.0 + 20.0 * n.time[r], 1e-9);
    EXPECT_NEAR(n.at(r, 2), 2.0 - 50.0 * n.time[r], 1e-9);
    EXPECT_NEAR(n.at(r, 3), 20.0, 1e-9);
    EXPECT_NEAR(n.at(r, 5), -50.0, 1e-9);
  }
  // Mean velocities: v0, and at the end the final momentum / mass (conservation).
  const std::string names[] = {"cube_v", "brick_v"};
  const core::Vec3 v0[] = {{0, 0, 30}, {20, 0, -50}};
  for (int b = 0; b < 2; ++b) {
    const core::ProbeSeries& m = series(s, names[b]);
    const core::BodySums& sums = s.final.bodies[static_cast<std::size_t>(b)];
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(m.at(m.rows() - 1, static_cast<std::size_t>(a)), sums.momentum[a] / sums.mass,
                  1e-12);
      for (std::size_t r = 0; r < m.rows(); ++r)
        EXPECT_NEAR(m.at(r, static_cast<std::size_t>(a)), v0[b][a], 1e-9);
    }
    EXPECT_EQ(m.time.back(), s.time);
  }
  // The largest vz in the box: the cube's 30, at one of its particles; the largest speed: the
  // brick's sqrt(20^2 + 50^2), at one of its element centroids (x > 20).
  const core::ProbeSeries& up = series(s, "fastest_up");
  const core::ProbeSeries& fast = series(s, "fastest");
  for (std::size_t r = 0; r < up.rows(); ++r) {
    EXPECT_NEAR(up.at(r, 0), 30.0, 1e-9);
    EXPECT_LT(up.at(r, 1), 2.0);
    EXPECT_NEAR(fast.at(r, 0), std::hypot(20.0, 50.0), 1e-9);
    EXPECT_GT(fast.at(r, 1), 20.0);
  }
  // Positions: the cube's highest particle rises with it, 3.75 + 30 t; the brick's lowest
  // element centroids (z = 0.5 at the start) sink with it, 0.5 - 50 t. The value is the
  // point's coordinate, so the columns after it repeat it.
  const core::ProbeSeries& top = series(s, "cube_top");
  const core::ProbeSeries& bottom = series(s, "brick_bottom");
  ASSERT_GE(top.rows(), 10u);
  for (std::size_t r = 0; r < top.rows(); ++r) {
    EXPECT_NEAR(top.at(r, 0), 3.75 + 30.0 * top.time[r], 1e-9);
    EXPECT_EQ(top.at(r, 3), top.at(r, 0));
    EXPECT_NEAR(bottom.at(r, 0), 0.5 - 50.0 * bottom.time[r], 1e-9);
    EXPECT_GT(bottom.at(r, 1), 20.0);
  }
}

TEST(Probes, FilesHoldWhatTheSummaryHolds) {
  test::ScratchDir dir;
  const core::RunSummary s = run_text(free_blocks, dir.str());
  const core::ProbeSeries& n = series(s, "node");
  std::ifstream in(dir / "probes" / "node.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time,x,y,z,vx,vy,vz");
  std::size_t rows = 0;
  for (std::string line; std::getline(in, line); ++rows) {
    std::stringstream fields(line);
    std::string f;
    std::getline(fields, f, ',');
    EXPECT_NEAR(std::stod(f), n.time[rows], 1e-9 * (1.0 + n.time[rows]));
    for (std::size_t c = 0; c < n.columns.size(); ++c) {
      std::getline(fields, f, ',');
      EXPECT_NEAR(std::stod(f), n.at(rows, c), 1e-7 * (1.0 + std::abs(n.at(rows, c))));
    }
  }
  EXPECT_EQ(rows, n.rows());
}

// A 1 x 1 x 50 steel bar of hexahedra (nu = 0) held at z = 0, moving at -10 m/s.
constexpr double young = 200e3, density = 7.85e-3, v0 = 10.0, length = 50.0;
const double c = std::sqrt(young / density);  // 5047.5 m/s
std::string fixed_free_bar(const std::string& extra = "") {
  return test::fixed_free_bar_scene(extra) + R"(
[[probes]]
name = "z10"
node = { body = "bar", near = [1, 1, 10] }
[[probes]]
name = "z40"
node = { body = "bar", near = [1, 1, 40] }
[[probes]]
name = "tip"
node = { body = "bar", near = [1, 1, 50] }
[[probes]]
name = "e5"
element = { body = "bar", near = [0.5, 0.5, 5] }
[[probes]]
name = "peak"
extreme = { field = "von_mises", box = { min = [0, 0, 0], max = [1, 1, 10] } }
)";
}

TEST(Probes, FixedFreeBarFrontSpeedFrequencyAndStressBehindTheFront) {
  const core::RunSummary s = run_text(fixed_free_bar());
  const core::ProbeSeries &a = series(s, "z10"), &b = series(s, "z40"), &tip = series(s, "tip");
  // Arrival: half the first jump, so the histories end before the reflection from the free
  // end reaches z = 40 (at 60 mm of travel), where the change would double.
  const auto first_passage = [&](const core::ProbeSeries& p) {
    std::vector<double> t, q;
    for (std::size_t r = 0; r < p.rows() && p.time[r] < 55.0 / c; ++r)
      t.push_back(p.time[r]), q.push_back(p.at(r, 5));
    return analysis::arrival_time(t, q, 0.5);
  };
  const double ta = first_passage(a), tb = first_passage(b);
  const double speed = (b.at(0, 2) - a.at(0, 2)) / (tb - ta);
  const double f = analysis::zero_crossing_frequency(tip.time, tip.series(5));
  std::printf(
      "front speed %.1f (c = %.1f, %+.2f %%), first axial frequency %.3f /ms (c / 4L = "
      "%.3f, %+.2f %%)\n",
      speed, c, 100 * (speed / c - 1), f, c / (4 * length), 100 * (f * 4 * length / c - 1));
  EXPECT_NEAR(speed, c, 0.02 * c);
  EXPECT_NEAR(f, c / (4.0 * length), 0.02 * c / (4.0 * length));
  // Element at z = 5 between the front's passing (5 / c) and the unloading's return from the
  // free end ((2 L - 5) / c), away from both by 20 % of L / c: the mean of its rows.
  const core::ProbeSeries& e = series(s, "e5");
  double pressure = 0.0, mises = 0.0, vz = 0.0;
  int n = 0;
  for (std::size_t r = 0; r < e.rows(); ++r) {
    if (e.time[r] < (5.0 + 10.0) / c || e.time[r] > (2 * length - 5.0 - 10.0) / c) continue;
    pressure += e.at(r, 6), mises += e.at(r, 7), vz += e.at(r, 5), ++n;
  }
  pressure /= n, mises /= n, vz /= n;
  const double sigma = density * c * v0;  // 396.2 MPa
  std::printf(
      "behind the front: pressure %.2f (rho c v0 / 3 = %.2f), von Mises %.2f (rho c v0 = "
      "%.2f), vz %.3f (0), %d rows\n",
      pressure, sigma / 3, mises, sigma, vz, n);
  EXPECT_NEAR(pressure, sigma / 3.0, 0.01 * sigma / 3.0);
  EXPECT_NEAR(mises, sigma, 0.01 * sigma);
  EXPECT_NEAR(vz, 0.0, 0.01 * v0);
  // The largest von Mises stress in the first 10 mm once the front has left them and before
  // the unloading returns: rho c v0, with the front's ringing behind it.
  const core::ProbeSeries& peak = series(s, "peak");
  double largest = 0.0;
  for (std::size_t r = 0; r < peak.rows(); ++r)
    if (peak.time[r] > 20.0 / c && peak.time[r] < 80.0 / c)
      largest = std::max(largest, peak.at(r, 0));
  std::printf("largest von Mises in z < 10 mm, 20-80 mm of travel: %.2f (%+.2f %% of rho c v0)\n",
              largest, 100 * (largest / sigma - 1));
  EXPECT_NEAR(largest, sigma, 0.03 * sigma);
}

TEST(Probes, ParticleBarFirstAxialFrequency) {
  // The same bar of particles, 30 mm long, the grid's zmin fixed.
  const double l = 30.0;
  const core::RunSummary s = run_text(R"(
[run]
end_time = 0.0476
history_every = 1
[grid]
cell = 0.5
min = [0, 0, 0]
max = [3, 3, 31]
boundary = { xmin = "symmetric", ymin = "symmetric", zmin = "fixed" }
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0
[[bodies]]
name = "bar"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 30] } }
velocity = [0, 0, -10]
[[probes]]
name = "tip"
particle = { body = "bar", near = [0, 0, 30] }
)");
  const core::ProbeSeries& tip = series(s, "tip");
  const double f = analysis::zero_crossing_frequency(tip.time, tip.series(5));
  std::printf("particles: first axial frequency %.3f /ms (c / 4L = %.3f, %+.2f %%)\n", f,
              c / (4 * l), 100 * (f * 4 * l / c - 1));
  EXPECT_NEAR(f, c / (4.0 * l), 0.03 * c / (4.0 * l));
}

TEST(Probes, AnErodedElementLeavesNanRows) {
  // Elements erode once compressed by 0.1 %: the front (strain v0 / c = 0.2 %) takes them.
  // The first element, at the fixed end, goes when the front has crossed it.
  const std::string text = fixed_free_bar("erosion = { volume_ratio = 0.999 }\n") +
                           "[[probes]]\nname = \"e0\"\nelement = { body = \"bar\", index = 0 }\n";
  const core::Scene scene = core::parse_scene(text, "scene.toml");
  fem::FeModel model(scene);
  core::RunSummary s = analysis::run(model, scene, {});
  const core::ProbeSeries& e = series(s, "e0");
  const std::size_t element = 0;
  ASSERT_FALSE(model.solver().hexahedra().alive[element]);
  std::size_t first_nan = e.rows();
  for (std::size_t r = 0; r < e.rows(); ++r)
    if (std::isnan(e.at(r, 0))) {
      first_nan = r;
      break;
    }
  ASSERT_GT(first_nan, 0u);
  ASSERT_LT(first_nan, e.rows());
  EXPECT_NEAR(e.at(0, 2), 0.5, 1e-12);
  for (std::size_t r = first_nan; r < e.rows(); ++r)
    for (std::size_t col = 0; col < e.columns.size(); ++col) EXPECT_TRUE(std::isnan(e.at(r, col)));
  std::printf("element probe: NaN from t = %.5f (the front crosses the element by %.5f)\n",
              e.time[first_nan], 1.0 / c);
}

TEST(Probes, NamingWhatTheBodyLacksStopsTheRunWithLineKeyAndRange) {
  const auto start_error = [](const std::string& text) -> std::string {
    const core::Scene scene = core::parse_scene(text, "scene.toml");
    const auto model = make_model(scene);
    try {
      analysis::run(*model, scene, {});
    } catch (const core::InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
  };
  std::string text =
      fixed_free_bar() + "[[probes]]\nname = \"far\"\nnode = { body = \"bar\", index = 5000 }\n";
  EXPECT_EQ(start_error(text),
            "scene.toml:" + std::to_string(test::line_of(text, "name = \"far\"") - 1) +
                ": key 'probes[5].node.index': node 5000 of body 'bar' does not exist; its nodes "
                "are 0..203");
  text =
      fixed_free_bar() + "[[probes]]\nname = \"far\"\nelement = { body = \"bar\", index = 50 }\n";
  EXPECT_NE(
      start_error(text).find("key 'probes[5].element.index': hexahedron 50 of body 'bar' does "
                             "not exist; its elements are 0..49"),
      std::string::npos);
  text = free_blocks + "[[probes]]\nname = \"far\"\nparticle = { body = \"cube\", index = 64 }\n";
  EXPECT_NE(
      start_error(text).find("key 'probes[8].particle.index': particle 64 of body 'cube' does "
                             "not exist; its particles are 0..63"),
      std::string::npos);
}

}  // namespace
}  // namespace afemp::coupling
