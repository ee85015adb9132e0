// Sizing a scene before it is built (core/resource_guard.hpp).
#include <gtest/gtest.h>

#include <string>

#include "afemp/errors.hpp"
#include "core/resource_guard.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "scene_errors.hpp"

namespace afemp::core {
namespace {

// The Taylor bar (a quarter cylinder, radius 3.8, length 25.4) with cells of `cell` and n
// particles per cell per direction.
std::string taylor(double cell, int n) {
  return "[run]\nend_time = 0.072\n[grid]\ncell = " + std::to_string(cell) +
         "\nmin = [0, 0, 0]\nmax = [10, 10, 26]\n[materials.copper]\ndensity = 8.93e-3\n"
         "E = 117e3\nnu = 0.35\n[[bodies]]\nname = \"bar\"\nmaterial = \"copper\"\n"
         "shape = { cylinder = { base = [0, 0, 0], axis = [0, 0, 1], radius = 3.8, length = "
         "25.4 } }\nparticles_per_cell = " +
         std::to_string(n) + "\n";
}

// Reference: the estimate is the shape's volume over the particle spacing cubed: pi 3.8^2 25.4
// / (0.5 / 2)^3 = 73,774 for the full cylinder the shape describes (the generator keeps what
// lies inside the grid, a quarter of it: 18,666 in the V2 example), within 1e-12; a box mesh
// by its divisions exactly.
TEST(ResourceGuard, TheEstimateIsTheShapeVolumeOverTheSpacingCubed) {
  const Scene s = parse_scene(taylor(0.5, 2), "taylor.toml");
  const SizeEstimate e = estimate_size(s);
  const double expected = 3.14159265358979323846 * 3.8 * 3.8 * 25.4 / (0.25 * 0.25 * 0.25);
  EXPECT_NEAR(e.particles, expected, 1e-12 * expected);
  EXPECT_EQ(e.elements, 0.0);
  EXPECT_EQ(e.largest_body, 0);
  const Scene m = parse_scene(
      "[run]\nend_time = 1\n[materials.steel]\ndensity = 7.85e-3\nE = 2e5\nnu = 0.3\n"
      "[[bodies]]\nname = \"block\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\nmesh = { divisions = [3, 4, 5] }\n",
      "block.toml");
  EXPECT_EQ(estimate_size(m).elements, 60.0);
}

// Reference: an axisymmetric grid's particles are rings, one per r-z square: the cylinder's
// section 3.8 x 25.4 over (0.5 / 2)^2 = 1544.3 (the generator makes 1530), within 1e-12.
TEST(ResourceGuard, AnAxisymmetricEstimateIsTheSectionOverTheSpacingSquared) {
  std::string text = taylor(0.5, 2);
  text.replace(text.find("max = [10, 10, 26]"), 18, "max = [10, 0, 26]\naxisymmetric = true");
  const SizeEstimate e = estimate_size(parse_scene(text, "taylor.toml"));
  const double expected = 3.8 * 25.4 / (0.25 * 0.25);
  EXPECT_NEAR(e.particles, expected, 1e-12 * expected);
}

// Reference: the scene of the issue (cells of 0.05 mm, 8 particles per cell per direction:
// about 4.7e9 particles, over 1.3 TiB) is refused before anything is allocated, at the body's
// line, naming both memory figures; it takes no time (no particle is made).
TEST(ResourceGuard, AScenePastTheMachinesMemoryIsRefusedWithBothFigures) {
  ASSERT_GT(available_memory(), 0.0);
  ASSERT_LT(available_memory(), 1e12);  // this test needs a machine with less than 1 TB free
  const std::string text = taylor(0.05, 8);
  const Scene s = parse_scene(text, "taylor.toml");
  try {
    coupling::make_model(s);
    ADD_FAILURE() << "make_model built a scene of 4.7e9 particles";
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string at =
        "taylor.toml:" + std::to_string(afemp::test::line_of(text, "[[bodies]]")) +
        ": key 'bodies'";
    EXPECT_NE(what.find(at), std::string::npos) << what;
    EXPECT_NE(what.find("about 4.7e+09 particles"), std::string::npos) << what;
    EXPECT_NE(what.find("GiB of memory"), std::string::npos) << what;
    EXPECT_NE(what.find("GiB available"), std::string::npos) << what;
  }
}

TEST(ResourceGuard, CountsReadAsAPersonWritesThem) {
  EXPECT_EQ(readable_count(0.0), "0");
  EXPECT_EQ(readable_count(999.0), "999");
  EXPECT_EQ(readable_count(12345.4), "12,345");
  EXPECT_EQ(readable_count(123456789.0), "123,456,789");
  EXPECT_EQ(readable_count(3.2e304), "3.2e+304");
  EXPECT_EQ(readable_count(1e308 * 10.0), "more than 1e+308");
}

TEST(ResourceGuard, DurationsReadAsAPersonWritesThem) {
  EXPECT_EQ(readable_duration(45.2), "45 s");
  EXPECT_EQ(readable_duration(600.0), "10.0 min");
  EXPECT_EQ(readable_duration(5.0 * 3600.0), "5.0 h");
  EXPECT_EQ(readable_duration(3.0 * 86400.0), "3.0 days");
  EXPECT_EQ(readable_duration(1e20), "3.2e+12 years");
  EXPECT_EQ(readable_duration(1e308 * 10.0), "forever");
}

// Reference: the nominal pace, 1.5e6 point-steps per thread and second. 3e11 point-steps on one
// thread take 2e5 s = 2.3 days (warned of); on four, 0.58 days (not); 1e11 on one, 0.77 days.
TEST(ResourceGuard, ARunOfDaysAtTheNominalPaceIsWarnedOfWithItsFigures) {
  const std::string w = wall_time_warning(3e11, 1);
  EXPECT_EQ(w.rfind("the run is estimated to take 2.3 days (3.0e+11 point-steps on 1 thread(s) at "
                    "about 1.5 million per thread and second)",
                    0),
            0u)
      << w;
  EXPECT_NE(w.find("checkpoint_wall_every"), std::string::npos) << w;
  EXPECT_EQ(wall_time_warning(3e11, 4), "");
  EXPECT_EQ(wall_time_warning(1e11, 1), "");
}

// Reference: at 0.01 % of the end time after 30 s, the rest takes 30 x 0.9999 / 1e-4 s = 3.5
// days; the pace is not judged before 20 s, and half done after 30 s leaves 30 s.
TEST(ResourceGuard, ARunWhosePaceSaysDaysIsWarnedOfOnce) {
  const std::string w = pace_warning(30.0, 1e-4);
  EXPECT_EQ(w.rfind("at its pace so far (0.01 % of the end time in 30 s) the run needs 3.5 days "
                    "more",
                    0),
            0u)
      << w;
  EXPECT_EQ(pace_warning(10.0, 1e-4), "");
  EXPECT_EQ(pace_warning(30.0, 0.5), "");
}

}  // namespace
}  // namespace afemp::core
