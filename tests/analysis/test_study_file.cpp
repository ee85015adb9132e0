// The study file (analysis/study_file.hpp): runs expand one per resolution, overrides and
// per-run references reach the run they are for (tables, bodies by name, inline tables; the
// k-th value of a sweep for its k-th run), and every mistake names the study file, its line
// and key, and what is allowed, before anything runs.
#include <gtest/gtest.h>

#include <string>

#include "analysis/study_file.hpp"
#include "elastic_bar_scene.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp::analysis {
namespace {

using test::elastic_bar_scene;

const std::string study_text = test::elastic_bar_study("Elastic bar") + R"(
[[runs]]
method = "MPM"
scene = "bar.toml"
resolution = [1.0, 0.5]
set = { "grid.cell" = [1.0, 0.5], "bodies.bar.particles_per_cell" = [2, 1] }

[[runs]]
method = "MPM USF"
scene = "bar.toml"
set = { "mpm.scheme" = "USF" }
)";

struct StudyFiles {
  test::ScratchDir dir;
  std::string study;
  explicit StudyFiles(const std::string& text, const std::string& scene = elastic_bar_scene) {
    dir.write("bar.toml", scene);
    study = dir.write("study.toml", text);
  }
};

std::string study_error(const std::string& text) {
  StudyFiles f(text);
  try {
    read_study(f.study);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return "";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

TEST(StudyFile, RunsExpandPerResolutionAndOverridesReachTheScene) {
  StudyFiles f(study_text);
  const StudyPlan plan = read_study(f.study);
  EXPECT_EQ(plan.title, "Elastic bar");
  EXPECT_EQ(plan.threads, 1);
  EXPECT_EQ(plan.plot, "rebound");  // the first metric with a reference
  ASSERT_EQ(plan.metrics.size(), 1u);
  EXPECT_EQ(plan.metrics[0].component, 2);
  EXPECT_EQ(plan.metrics[0].reference.scalar->low, 300.0);
  EXPECT_EQ(plan.metrics[0].reference.scalar->high, 300.0);
  EXPECT_FALSE(plan.metrics[0].reference.scalar->band);
  ASSERT_EQ(plan.runs.size(), 3u);
  EXPECT_EQ(plan.runs[0].label, "MPM, resolution 1");
  EXPECT_EQ(plan.runs[1].label, "MPM, resolution 0.5");
  EXPECT_EQ(*plan.runs[1].resolution, 0.5);
  EXPECT_FALSE(plan.runs[2].resolution.has_value());
  const Scene fine = build_run_scene(plan, plan.runs[1]);
  EXPECT_EQ(fine.mpm.grid.cell, 0.5);
  EXPECT_EQ(fine.bodies[0].particles_per_cell, 1);
  EXPECT_EQ(fine.mpm.grid.max.z, 16.0);                   // the rest as in the scene file
  const Scene usf = build_run_scene(plan, plan.runs[2]);  // the scene has no [mpm]: started
  EXPECT_EQ(usf.mpm.scheme, UpdateScheme::USF);
  EXPECT_EQ(usf.mpm.grid.cell, 1.0);
  // An inline table's key: the cylinder's radius.
  StudyFiles g(replaced(study_text, "\"mpm.scheme\" = \"USF\"",
                        "\"bodies.bar.shape.cylinder.radius\" = 1.5"));
  const StudyPlan p2 = read_study(g.study);
  const auto& bar = std::get<CylinderShape>(build_run_scene(p2, p2.runs[2]).bodies[0].shape);
  EXPECT_EQ(bar.radius, 1.5);
}

TEST(StudyFile, MistakesNameTheFileLineKeyAndWhatIsAllowed) {
  std::string e = study_error(replaced(study_text, "threads = 1", "thread = 1"));
  EXPECT_NE(e.find("study.toml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("study.thread"), std::string::npos) << e;
  EXPECT_NE(e.find("title, threads, plot"), std::string::npos) << e;
  e = study_error(replaced(study_text, "kind = \"velocity\"", "kind = \"penetration\""));
  EXPECT_NE(e.find("metrics[0].kind"), std::string::npos) << e;
  EXPECT_NE(e.find("\"taylor\", \"velocity\""), std::string::npos) << e;
  e = study_error(replaced(study_text, "\"bodies.bar.particles_per_cell\" = [2, 1]",
                           "\"bodies.bar.particles_per_cell\" = 2"));
  EXPECT_NE(e.find("every set value must be an array of 2 values"), std::string::npos) << e;
  e = study_error(
      replaced(study_text, "\"mpm.scheme\" = \"USF\"", "\"bodies.rod.velocity\" = [0, 0, 1]"));
  EXPECT_NE(e.find("no 'bodies' named \"rod\"; it has \"bar\""), std::string::npos) << e;
  e = study_error(replaced(study_text, "\"mpm.scheme\" = \"USF\"", "\"grid.cell.x\" = 1"));
  EXPECT_NE(e.find("'grid.cell' in scene"), std::string::npos) << e;
  EXPECT_NE(e.find("is not a table"), std::string::npos) << e;
  // A key the scene does not know: the scene parser's message, with the run in front.
  e = study_error(replaced(study_text, "\"mpm.scheme\" = \"USF\"", "\"mpm.schema\" = \"USF\""));
  EXPECT_NE(e.find("run \"MPM USF\""), std::string::npos) << e;
  EXPECT_NE(e.find("mpm.schema"), std::string::npos) << e;
  EXPECT_NE(e.find("scheme"), std::string::npos) << e;  // among the allowed keys
  // An override value the scene parser refuses names its range.
  e = study_error(
      replaced(study_text, "\"grid.cell\" = [1.0, 0.5]", "\"grid.cell\" = [1.0, -0.5]"));
  EXPECT_NE(e.find("MPM, resolution 0.5"), std::string::npos) << e;
  EXPECT_NE(e.find("grid.cell"), std::string::npos) << e;
  e = study_error(replaced(study_text, "body = \"bar\"", "body = \"rod\""));
  EXPECT_NE(e.find("measures body \"rod\""), std::string::npos) << e;
  e = study_error(replaced(study_text, "reference = 300\n", ""));
  EXPECT_NE(e.find("a tolerance needs a reference"), std::string::npos) << e;
  e = study_error(replaced(study_text, "kind = \"velocity\"", "kind = \"taylor\""));
  EXPECT_NE(e.find("component"), std::string::npos) << e;
  e = study_error(replaced(study_text, "title = \"Elastic bar\"", "plot = \"speed\""));
  EXPECT_NE(e.find("study.plot"), std::string::npos) << e;
  EXPECT_NE(e.find("\"rebound\""), std::string::npos) << e;
  e = study_error("[study]\ntitle = \"nothing\"\n");
  EXPECT_NE(e.find("at least one [[runs]]"), std::string::npos) << e;
  e = study_error(
      replaced(study_text, "scene = \"bar.toml\"\nresolution", "scene = \"rod.toml\"\nresolution"));
  EXPECT_NE(e.find("cannot open scene file"), std::string::npos) << e;
  EXPECT_NE(e.find("rod.toml"), std::string::npos) << e;
}

// Per-run references: the rebound's band study-wide, a value and a band of its own for each
// run of the sweep; a crater and a Taylor bar with no study-wide reference, given theirs run
// by run (the crater's tolerance is fine: the runs without a reference report it only).
const std::string references_text =
    replaced(replaced(test::elastic_bar_study("Elastic bar"), "reference = 300",
                      "reference = [280, 320]"),
             "threads = 1\n",
             "threads = 1\nplot_value = \"crater.depth\"\nx_label = \"impact speed (m/s)\"\n") +
    R"(
[[metrics]]
kind = "crater"
body = "bar"
point = [2, 2, 10.5]
normal = [0, 0, 1]
ring = 0.5
threshold = 0.1
tolerance = 0.2

[[metrics]]
kind = "taylor"
body = "bar"

[[runs]]
method = "MPM"
scene = "bar.toml"
resolution = [1.0, 0.5]
set = { "grid.cell" = [1.0, 0.5] }
reference = { rebound = [300, [290, 310]], crater = [{ depth = 1, diameter = 4 }, { depth = 2, diameter = 5 }] }

[[runs]]
method = "MPM USF"
scene = "bar.toml"
set = { "mpm.scheme" = "USF" }
reference = { crater = { depth = 3, diameter = 6 }, taylor = { L = 9, D = 5, W = 4.5 } }
)";

TEST(StudyFile, RunsTakeTheirOwnReferencesAndBands) {
  StudyFiles f(references_text);
  const StudyPlan plan = read_study(f.study);
  ASSERT_EQ(plan.metrics.size(), 3u);
  const ScalarReference wide = *plan.metrics[0].reference.scalar;
  EXPECT_EQ(wide.low, 280.0);
  EXPECT_EQ(wide.high, 320.0);
  EXPECT_TRUE(wide.band);
  EXPECT_FALSE(plan.metrics[1].reference.has_value());
  EXPECT_FALSE(plan.metrics[2].reference.has_value());
  ASSERT_EQ(plan.runs.size(), 3u);
  for (const StudyRun& run : plan.runs) ASSERT_EQ(run.references.size(), 3u);
  // The sweep's k-th value for its k-th run.
  const ScalarReference r0 = *plan.runs[0].references[0].scalar,
                        r1 = *plan.runs[1].references[0].scalar;
  EXPECT_EQ(r0.low, 300.0);
  EXPECT_EQ(r0.high, 300.0);
  EXPECT_FALSE(r0.band);
  EXPECT_EQ(r1.low, 290.0);
  EXPECT_EQ(r1.high, 310.0);
  EXPECT_TRUE(r1.band);
  EXPECT_EQ(plan.runs[0].references[1].crater->depth, 1.0);
  EXPECT_EQ(plan.runs[1].references[1].crater->diameter, 5.0);
  EXPECT_FALSE(plan.runs[0].references[2].has_value());
  // The USF run: the rebound's study-wide band, its own crater and Taylor bar.
  EXPECT_EQ(plan.runs[2].references[0].scalar->low, 280.0);
  EXPECT_EQ(plan.runs[2].references[0].scalar->high, 320.0);
  EXPECT_EQ(plan.runs[2].references[1].crater->depth, 3.0);
  EXPECT_EQ(plan.runs[2].references[1].crater->diameter, 6.0);
  EXPECT_EQ(plan.runs[2].references[2].taylor->length, 9.0);
  EXPECT_EQ(plan.runs[2].references[2].taylor->impact_diameter, 5.0);
  EXPECT_EQ(plan.runs[2].references[2].taylor->bulge_diameter, 4.5);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_TRUE(plan.has_reference(k)) << k;
  EXPECT_EQ(plan.plot, "rebound");
  EXPECT_EQ(plan.plot_value, "crater.depth");
  EXPECT_EQ(plan.x_label, "impact speed (m/s)");
  // Without the key, no value plot; the x label's default.
  StudyFiles g(study_text);
  const StudyPlan plain = read_study(g.study);
  EXPECT_EQ(plain.plot_value, "");
  EXPECT_EQ(plain.x_label, "resolution");
}

TEST(StudyFile, ReferenceMistakesNameTheFileLineKeyAndWhatIsAllowed) {
  const std::string sweep = "reference = { rebound = [300, [290, 310]], ";
  std::string e = study_error(replaced(references_text, "taylor = { L", "speed = 3, taylor = { L"));
  EXPECT_NE(e.find("study.toml:40: key 'runs[1].reference.speed': no metric is named \"speed\"; "
                   "reference = { NAME = ... } takes a [[metrics]] name: \"rebound\", \"crater\", "
                   "\"taylor\""),
            std::string::npos)
      << e;
  e = study_error(replaced(references_text, sweep, "reference = { rebound = [300], "));
  EXPECT_NE(e.find("study.toml:34: key 'runs[0].reference.rebound': with resolution = [2 values], "
                   "every reference value must be an array of 2 values, one per run"),
            std::string::npos)
      << e;
  e = study_error(replaced(references_text, sweep, "reference = { rebound = [300, \"fast\"], "));
  EXPECT_NE(e.find("study.toml:34: key 'runs[0].reference.rebound[1]': expected a number or a band "
                   "[low, high] of two numbers, got a string"),
            std::string::npos)
      << e;
  e = study_error(
      replaced(references_text, sweep, "reference = { rebound = [300, [290, \"310\"]], "));
  EXPECT_NE(e.find("key 'runs[0].reference.rebound[1]': expected a number or a band [low, high] of "
                   "two numbers, got an array of an integer and a string"),
            std::string::npos)
      << e;
  e = study_error(
      replaced(references_text, sweep, "reference = { rebound = [300, [290, 300, 310]], "));
  EXPECT_NE(e.find("key 'runs[0].reference.rebound[1]': expected a number or a band [low, high] of "
                   "two numbers, got an array of 3 elements"),
            std::string::npos)
      << e;
  e = study_error(replaced(references_text, sweep, "reference = { rebound = [300, [310, 290]], "));
  EXPECT_NE(e.find("key 'runs[0].reference.rebound[1]': a band [low, high] needs low <= high; got "
                   "[310, 290]"),
            std::string::npos)
      << e;
  e = study_error(replaced(references_text, sweep, "reference = { rebound = [0, [-10, 10]], "));
  EXPECT_NE(
      e.find("key 'runs[0].reference.rebound[0]': the error is relative to the reference, which "
             "must not be 0"),
      std::string::npos)
      << e;
  e = study_error(replaced(references_text, "reference = [280, 320]", "reference = [-10, 10]"));
  EXPECT_NE(
      e.find("study.toml:13: key 'metrics[0].reference': a band's bounds must have one sign and "
             "neither be 0"),
      std::string::npos)
      << e;
  e = study_error(replaced(references_text, "crater = { depth = 3, diameter = 6 }", "crater = 3"));
  EXPECT_NE(
      e.find("key 'runs[1].reference.crater': expected { depth = ..., diameter = ... }, got an "
             "integer"),
      std::string::npos)
      << e;
  e = study_error(
      replaced(references_text, "{ depth = 2, diameter = 5 }", "{ depth = 2, diam = 5 }"));
  EXPECT_NE(e.find("runs[0].reference.crater[1].diam"), std::string::npos) << e;
  e = study_error(replaced(references_text, "W = 4.5", "W = -4.5"));
  EXPECT_NE(e.find("key 'runs[1].reference.taylor.W': value -4.5 is out of range"),
            std::string::npos)
      << e;
  // A tolerance with no reference in any run.
  e = study_error(replaced(replaced(references_text, "crater = { depth = 3, diameter = 6 }, ", ""),
                           ", crater = [{ depth = 1, diameter = 4 }, { depth = 2, diameter = 5 }]",
                           ""));
  EXPECT_NE(
      e.find("study.toml:23: key 'metrics[1].tolerance': a tolerance needs a reference to "
             "compare with: reference = ... here, or reference = { crater = ... } in a [[runs]] "
             "table"),
      std::string::npos)
      << e;
  e = study_error(replaced(references_text, "\"crater.depth\"", "\"crater.width\""));
  EXPECT_NE(e.find("study.toml:5: key 'study.plot_value': names the value column plotted against "
                   "resolution: \"rebound\", \"crater.depth\", \"crater.diameter\", \"taylor.L\", "
                   "\"taylor.D\", \"taylor.W\""),
            std::string::npos)
      << e;
  e = study_error(replaced(replaced(study_text, "resolution = [1.0, 0.5]\n", ""), "threads = 1\n",
                           "threads = 1\nplot_value = \"rebound\"\n"));
  EXPECT_NE(e.find("key 'study.plot_value': plots the value against the runs' resolution, and no "
                   "[[runs]] table gives one"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace afemp::analysis
