// V1: the elastic copper bar of Ma 2005, §2.3.1 (L 10, R 2, quarter model, cell 1, 260
// particles, 300 m/s) on a rigid frictionless wall, from examples/elastic_bar/mpm.toml,
// with each update scheme. Prints the rebound speed and the energy balance of each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/reference_checks.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_model.hpp"

namespace afemp::mpm {
namespace {

std::string example_text() {
  std::ifstream in(std::string(AFEMP_SOURCE_DIR) + "/examples/elastic_bar/mpm.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The example with another scheme and time-step factor.
// `method`: extra [mpm] lines (shape function, transfer).
core::Scene elastic_bar(const std::string& scheme, double factor, const std::string& method) {
  std::string text = example_text();
  const std::string key = "scheme = \"MUSL\"";
  const auto at = text.find(key);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, key.size(), "scheme = \"" + scheme + "\"\n" + method);
  const std::string run = "[run]\n";
  text.insert(text.find(run) + run.size(), "time_step_factor = " + std::to_string(factor) + "\n");
  return core::parse_scene(text, "examples/elastic_bar/mpm.toml");
}

struct Rebound {
  double speed, max_error, end_error, kinetic_ratio;
};

Rebound run(const std::string& scheme, double factor, const std::string& method = "") {
  const core::Scene scene = elastic_bar(scheme, factor, method);
  MpmModel sim(scene);
  const core::RunSummary s = analysis::run(sim, scene, {});
  const BodySums& bar = s.final.bodies.at(0);
  const Rebound r{bar.momentum.z / bar.mass, s.max_energy_error, s.energy_error,
                  s.final.kinetic / s.initial.kinetic};
  std::printf(
      "V1 %-4s %s %s factor %.2f: rebound %.1f m/s (v0 300), kinetic energy back %.1f %%, "
      "energy balance error %+.2f %% at the end, largest %.2f %%, %ld steps\n",
      scheme.c_str(), core::to_string(scene.mpm.shape), core::to_string(scene.mpm.transfer), factor,
      r.speed, 100.0 * r.kinetic_ratio, 100.0 * r.end_error, 100.0 * r.max_error, s.steps);
  return r;
}

// Reference: the bar leaves the wall at v0 = 300 m/s in 1D theory; in 3D a short bar
// (L/D = 2.5) keeps part of its energy in lateral (Poisson) vibration: at 30 m/s (strains
// under 1 %) the rebound converges to 0.943 v0 (cell 1 and 0.5, time_step_factor 0.3 and
// 0.1), and at 300 m/s refinement lowers it further (MUSL, cell 1 / 0.5 / 0.25: 277.8 /
// 271.6 / 263.7 m/s). So the rebound is checked between 0.9 v0 and the 305 m/s no scheme
// may exceed without creating energy. The energy balance must close within 2 % (VALIDATION V1) with
// time_step_factor 0.1; USF needs it (4.4 % at 0.3: its strain is taken before the wall
// decides which nodes it holds), MUSL meets it at 0.3 as well.
TEST(ElasticBar, MuslReboundsAndClosesEnergyBalance) {
  for (double factor : {0.3, 0.1}) {
    const Rebound r = run("MUSL", factor);
    EXPECT_GT(r.speed, 270.0);
    EXPECT_LT(r.speed, 305.0);
    EXPECT_LT(r.max_error, 0.02);
  }
}

TEST(ElasticBar, UsfReboundsAndClosesEnergyBalance) {
  const Rebound r = run("USF", 0.1);
  EXPECT_GT(r.speed, 270.0);
  EXPECT_LT(r.speed, 305.0);
  EXPECT_LT(r.max_error, 0.02);
}

// USAVG (Wallstedt & Guilkey 2008: half the strain from the start velocity, half from the
// remapped end velocity) meets the marks at the default factor 0.3 as MUSL does.
TEST(ElasticBar, UsavgReboundsAndClosesEnergyBalance) {
  const Rebound r = run("USAVG", 0.3);
  EXPECT_GT(r.speed, 270.0);
  EXPECT_LT(r.speed, 305.0);
  EXPECT_LT(r.max_error, 0.02);
}

TEST(ElasticBar, UslFiguresAreReportedBesideTheOthers) {
  // USL dissipates and is unstable at free surfaces (Lian et al. 2013, §2.1.2); its figures are
  // reported, and the only assertion is that it neither blows up nor gains energy beyond
  // the 20 % the old wall treatment showed.
  const Rebound r = run("USL", 0.1);
  EXPECT_TRUE(std::isfinite(r.speed));
  EXPECT_LT(r.max_error, 0.20);
}

// The same bar with uGIMP weights (MUSL, factor 0.3). With FLIP it meets the marks the
// linear hat meets (measured 282.3 m/s, balance within 1.6 %). The affine transfer rebounds
// as fast (281.7 m/s) but damps the lateral ringing the short bar carries away from the
// wall: measured -9.3 % of the energy at the end, a loss and never a gain. Its figures are
// reported, and the assertion is that it loses energy (at most 15 %) rather than creating
// any (the balance stays below +0.5 %).
TEST(ElasticBar, GimpWithFlipMeetsTheMarksAndApicIsReportedBeside) {
  const Rebound flip = run("MUSL", 0.3, "shape_function = \"gimp\"\n");
  EXPECT_GT(flip.speed, 270.0);
  EXPECT_LT(flip.speed, 305.0);
  EXPECT_LT(flip.max_error, 0.02);
  const Rebound apic = run("MUSL", 0.3, "shape_function = \"gimp\"\ntransfer = \"apic\"\n");
  EXPECT_GT(apic.speed, 270.0);
  EXPECT_LT(apic.speed, 305.0);
  EXPECT_LT(apic.end_error, 0.005);
  EXPECT_GT(apic.end_error, -0.15);
}

// The quadratic and cubic B-splines and CPDI with FLIP (MUSL, factor 0.3): the marks the
// linear hat meets. The bar strikes the wall at the grid's face, where the B-splines' bases are
// modified and CPDI's domains reach the node beyond it.
TEST(ElasticBar, BsplinesAndCpdiMeetTheMarks) {
  for (const char* shape : {"bspline2", "bspline3", "cpdi1", "cpdi2"}) {
    const Rebound r = run("MUSL", 0.3, std::string("shape_function = \"") + shape + "\"\n");
    std::printf("[ elastic bar %s ] rebound %.1f m/s, largest balance error %.2f %%\n", shape,
                r.speed, 100.0 * r.max_error);
    EXPECT_GT(r.speed, 270.0) << shape;
    EXPECT_LT(r.speed, 305.0) << shape;
    EXPECT_LT(r.max_error, 0.02) << shape;
  }
}

}  // namespace
}  // namespace afemp::mpm
