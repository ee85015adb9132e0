// Output control ([run] output_times, history_interval; core/time_loop.cpp): frames at listed
// times and history rows at an interval of simulated time, each at the first step end at or
// past its time; the keys' mistakes name the file, line and key.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/reference_checks.hpp"
#include "core/output/history.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp::core {
namespace {

// A free steel cube of particles translating at 10 m/s (stable step about 5.1e-5 ms).
std::string cube(const std::string& run_keys) {
  return "[run]\nend_time = 0.01\n" + run_keys +
         "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
         "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
         "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\n"
         "shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }\nvelocity = [0, 0, 10]\n";
}

// Reference: each listed time t gets the frame of the first step end at or past it, so the
// frame lies in [t, t + dt); the rows of history_interval h likewise in [k h, k h + dt), one per
// multiple, then the final row at end_time; the first frame and row are the start's.
TEST(OutputControl, FramesAtListedTimesAndRowsAtAnIntervalOfTime) {
  test::ScratchDir dir;
  const std::vector<double> listed{0.0025, 0.005, 0.0051};
  const Scene scene = parse_scene(
      cube("history_interval = 0.001\noutput_times = [0.0025, 0.005, 0.0051]\n"), "cube.toml");
  const auto model = coupling::make_model(scene);
  const double dt = model->stable_time_step();
  RunOptions options;
  options.output_directory = dir.str();
  analysis::run(*model, scene, options);

  std::ifstream in(dir.file("fields.xmf"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string xmf = text.str();
  std::vector<double> frames;
  const std::regex time_re("Time Value=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), time_re);
       it != std::sregex_iterator(); ++it)
    frames.push_back(std::stod((*it)[1].str()));
  ASSERT_EQ(frames.size(), listed.size() + 2);  // the start, the listed, the end
  EXPECT_EQ(frames.front(), 0.0);
  for (std::size_t k = 0; k < listed.size(); ++k) {
    EXPECT_GE(frames[k + 1], listed[k] * (1 - 1e-9));
    EXPECT_LT(frames[k + 1], listed[k] + dt);
  }
  EXPECT_NEAR(frames.back(), 0.01, 1e-15);

  const CsvTable h = read_csv(dir.file("history.csv"));
  ASSERT_EQ(h.rows.size(), 11u);  // the start, nine multiples of 0.001 below 0.01, the end
  for (std::size_t k = 1; k + 1 < h.rows.size(); ++k) {
    const double t = h.rows[k][h.column("time")];
    EXPECT_GE(t, 0.001 * k * (1 - 1e-9)) << "row " << k;
    EXPECT_LT(t, 0.001 * k + dt) << "row " << k;
  }
  EXPECT_NEAR(h.rows.back()[h.column("time")], 0.01, 1e-15);
}

TEST(OutputControl, MistakesNameTheFileLineAndKey) {
  auto expect = [](const std::string& keys, const std::string& key, const std::string& what) {
    const std::string text = cube(keys);
    const std::string e = afemp::test::error_of(text, "cube.toml");
    const std::string at = "cube.toml:" + std::to_string(afemp::test::line_of(text, key + " =")) +
                           ": key 'run." + key + "'";
    EXPECT_NE(e.find(at), std::string::npos) << e;
    EXPECT_NE(e.find(what), std::string::npos) << e;
  };
  expect("history_every = 5\nhistory_interval = 0.001\n", "history_interval", "not both");
  expect("output_times = [0.005, 0.002]\n", "output_times", "must increase");
  expect("output_times = [0.02]\n", "output_times", "beyond end_time");
}

}  // namespace
}  // namespace afemp::core
