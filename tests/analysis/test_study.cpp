// `afemp study` (analysis/study.hpp) on the elastic bar of V1 (Ma 2005, §2.3.1: copper at
// 300 m/s on a rigid wall, "rebounds at about 300 m/s"). References: each run's metric is the
// same number a direct run of the same scene gives (same thread count: same bits), its error
// is |v - 300| / 300, the rebound lies within the V1 pass band's 10 % of 300 m/s (277.8 m/s
// measured with cell 1 mm, 276.8 with 0.5), and a run that goes unstable is reported as
// stopped while the others still run. The files: a CSV row per run, a Markdown table, and
// an SVG with one line per method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/reference_checks.hpp"
#include "analysis/study.hpp"
#include "analysis/study_file.hpp"
#include "core/parallel.hpp"
#include "coupling/make_model.hpp"
#include "elastic_bar_scene.hpp"
#include "scratch_dir.hpp"

namespace afemp::analysis {
namespace {

using test::elastic_bar_scene;

const std::string study_text = test::elastic_bar_study("Elastic bar on a wall") + R"(
[[runs]]
method = "MPM"
scene = "bar.toml"
resolution = [1.0, 0.5]
set = { "grid.cell" = [1.0, 0.5] }

[[runs]]
method = "MPM long step"
scene = "bar.toml"
set = { "run.time_step" = 0.001 }
)";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(Study, ElasticBarRowsMatchDirectRunsAndTheFilesHoldThem) {
  test::ScratchDir dir;
  dir.write("bar.toml", elastic_bar_scene);
  const analysis::StudyPlan plan = analysis::read_study(dir.write("study.toml", study_text));
  const StudyResult result = run_study(plan);
  ASSERT_EQ(result.rows.size(), 3u);
  ASSERT_EQ(result.value_columns, std::vector<std::string>{"rebound"});
  ASSERT_EQ(result.error_columns, std::vector<std::string>{"rebound.error"});
  const int threads_before = core::thread_count();
  core::set_thread_count(1);
  for (std::size_t k = 0; k < 2; ++k) {
    const StudyRow& row = result.rows[k];
    // The direct run of the same scene.
    const core::Scene scene = analysis::build_run_scene(plan, plan.runs[k]);
    const auto model = coupling::make_model(scene);
    const core::RunSummary s = analysis::run(*model, scene, core::RunOptions{});
    const core::BodySums bar = model->energies().bodies[0];
    // As the velocity metric takes it (momentum times the inverse mass): the same bits.
    const double v = ((1.0 / bar.mass) * bar.momentum).z;
    std::printf("%s: rebound %.2f m/s (direct run %.2f), error %.4f, %ld steps, %.2f s\n",
                row.run->label.c_str(), row.values[0], v, row.errors[0], row.steps,
                row.wall_seconds);
    EXPECT_TRUE(row.ok()) << describe_row(result, row);
    EXPECT_EQ(row.threads, 1);
    EXPECT_EQ(row.steps, s.steps);
    EXPECT_EQ(row.values[0], v);
    EXPECT_EQ(row.energy_error, s.energy_error);
    EXPECT_DOUBLE_EQ(row.errors[0], std::abs(v - 300.0) / 300.0);
    EXPECT_NEAR(row.values[0], 300.0, 30.0);
    EXPECT_GT(row.wall_seconds, 0.0);
  }
  core::set_thread_count(threads_before);
  EXPECT_EQ(result.rows[0].particles * 8, result.rows[1].particles);  // cell halved
  // The long step blows the bar up; the study says so and goes on.
  const StudyRow& bad = result.rows[2];
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.stopped.find("step"), std::string::npos) << bad.stopped;
  EXPECT_TRUE(std::isnan(bad.errors[0]));
  EXPECT_GT(bad.wall_seconds, 0.0);  // the time it ran before it stopped, not 0

  // A stability criterion: the largest energy-balance error (1.5 % for the cell of 1 mm).
  analysis::StudyPlan strict = plan;
  strict.energy_tolerance = 0.005;
  strict.runs.resize(1);
  const StudyResult checked = run_study(strict);
  EXPECT_GT(checked.rows[0].max_energy_error, 0.005);
  EXPECT_EQ(checked.rows[0].over_tolerance, std::vector<std::string>{"energy"});
  EXPECT_EQ(result.rows[0].max_energy_error, checked.rows[0].max_energy_error);

  write_study(plan, result, dir.str() + "/out");
  const std::string csv = text_of(dir.file("out/study.csv"));
  EXPECT_EQ(count(csv, "\n"), 4u) << csv;  // header + 3 runs
  EXPECT_EQ(
      csv.rfind("run,method,label,resolution,particles,elements,steps,wall_seconds,threads,"
                "energy_error,max_energy_error,rebound,rebound.error,rebound.reference,status\n",
                0),
      0u)
      << csv;
  // Every run's reference, the stopped one's too.
  EXPECT_EQ(count(csv, ",300,ok\n"), 2u) << csv;
  EXPECT_EQ(count(csv, ",300,\"stopped: step"), 1u) << csv;
  EXPECT_NE(csv.find("1,MPM,\"MPM, resolution 1\",1,"), std::string::npos) << csv;
  const std::string md = text_of(dir.file("out/study.md"));
  EXPECT_EQ(count(md, "| MPM |"), 2u) << md;
  EXPECT_NE(md.find("error_vs_time.svg"), std::string::npos);
  // One line per method: MPM with its two runs; the stopped method has no point to draw.
  const std::string svg = text_of(dir.file("out/error_vs_time.svg"));
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(count(svg, "<g class=\"series\""), 2u);
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_NE(svg.find("rebound error"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

}  // namespace
}  // namespace afemp::analysis
