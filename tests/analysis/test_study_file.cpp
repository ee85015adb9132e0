// The study file (analysis/study_file.hpp): runs expand one per resolution, overrides reach the
// scene (tables, bodies by name, inline tables), and every mistake names the study file, its
// line and key, and what is allowed, before anything runs.
#include <gtest/gtest.h>

#include <string>

#include "analysis/study_file.hpp"
#include "scene_errors.hpp"
#include "elastic_bar_scene.hpp"
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
  EXPECT_EQ(*plan.metrics[0].reference, 300.0);
  ASSERT_EQ(plan.runs.size(), 3u);
  EXPECT_EQ(plan.runs[0].label, "MPM, resolution 1");
  EXPECT_EQ(plan.runs[1].label, "MPM, resolution 0.5");
  EXPECT_EQ(*plan.runs[1].resolution, 0.5);
  EXPECT_FALSE(plan.runs[2].resolution.has_value());
  const Scene fine = build_run_scene(plan, plan.runs[1]);
  EXPECT_EQ(fine.mpm.grid.cell, 0.5);
  EXPECT_EQ(fine.bodies[0].particles_per_cell, 1);
  EXPECT_EQ(fine.mpm.grid.max.z, 16.0);  // the rest as in the scene file
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
  e = study_error(replaced(study_text, "\"mpm.scheme\" = \"USF\"", "\"bodies.rod.velocity\" = [0, 0, 1]"));
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
  e = study_error(replaced(study_text, "\"grid.cell\" = [1.0, 0.5]", "\"grid.cell\" = [1.0, -0.5]"));
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
  e = study_error(replaced(study_text, "scene = \"bar.toml\"\nresolution", "scene = \"rod.toml\"\nresolution"));
  EXPECT_NE(e.find("cannot open scene file"), std::string::npos) << e;
  EXPECT_NE(e.find("rod.toml"), std::string::npos) << e;
}

}  // namespace
}  // namespace afemp::analysis
