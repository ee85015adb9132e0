// The `afemp` command on FE scenes (apps/main.cpp, fem/fe_model.cpp): `afemp check` prints the FE
// plan (no background grid, no grid stage, the mesh quality), where an MPM scene's plan lists
// its grid stages; `afemp run` writes the mesh fields and a history with the FE energy columns;
// a scene mixing particle and mesh bodies is rejected.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/output/history.hpp"
#include "core/output/run_directory.hpp"
#include "mpm/test_support.hpp"

namespace afemp::fem {
namespace {

using mpm::test::CommandResult;
using mpm::test::run_afemp;
using mpm::test::ScratchDir;

std::string example(const std::string& name) {
  return std::string(AFEMP_SOURCE_DIR) + "/examples/" + name;
}

// Reference: fem/fe_model.cpp describe(): an FE scene allocates no background grid and runs no
// grid stage (the plan says so), prints each body's element count (the quarter bar of
// examples/elastic_bar/fe.toml: 8 core + 2 ring divisions on the quarter arc, 20 along the
// axis: (4^2 + 8 x 2) x 20 = 640 hexahedra) and the mesh quality line; the MPM example's plan
// names its grid and grid stages instead.
TEST(FeCli, CheckPrintsTheFePlanWithoutGridStagesAndTheMeshQuality) {
  ScratchDir dir;
  const CommandResult fe = run_afemp("check \"" + example("elastic_bar/fe.toml") + "\"", dir);
  ASSERT_EQ(fe.exit_code, 0) << fe.out << fe.err;
  EXPECT_NE(fe.out.find("no background grid is allocated and no grid stage runs"),
            std::string::npos)
      << fe.out;
  EXPECT_NE(fe.out.find("body bar: 640 hexahedra of copper"), std::string::npos) << fe.out;
  EXPECT_NE(fe.out.find("mesh quality: min scaled Jacobian"), std::string::npos) << fe.out;
  EXPECT_NE(fe.out.find("0 inverted"), std::string::npos) << fe.out;
  EXPECT_NE(fe.out.find("rigid walls"), std::string::npos) << fe.out;
  EXPECT_EQ(fe.out.find("grid:"), std::string::npos) << fe.out;
  EXPECT_EQ(fe.out.find("p2g"), std::string::npos) << fe.out;

  const CommandResult mpm = run_afemp("check \"" + example("elastic_bar/mpm.toml") + "\"", dir);
  ASSERT_EQ(mpm.exit_code, 0) << mpm.out << mpm.err;
  EXPECT_NE(mpm.out.find("grid: cell 1"), std::string::npos) << mpm.out;
  EXPECT_NE(mpm.out.find("p2g mass momentum force"), std::string::npos) << mpm.out;
  EXPECT_NE(mpm.out.find("grid momentum update"), std::string::npos) << mpm.out;
  EXPECT_EQ(mpm.out.find("no background grid"), std::string::npos) << mpm.out;
}

// Reference: core::run writes the fields under core::OutputPaths{}.fields_stem (.h5 + .xmf) and
// history.csv; an FE run's history has the hourglass, bulk-viscous and eroded energy columns,
// its first row is the initial state (kinetic energy 1/2 m v0^2 of the bar's nodes, no
// hourglass energy yet) and its last row the end time.
TEST(FeCli, RunWritesMeshFieldsAndHistoryWithFeEnergyColumns) {
  ScratchDir dir;
  const std::string out = dir.file("out");
  const CommandResult r = run_afemp(
      "run \"" + example("elastic_bar/fe.toml") + "\" -o \"" + out + "\" --threads 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const core::OutputPaths paths;
  for (const std::string& f :
       {paths.fields_stem + ".h5", paths.fields_stem + ".xmf", paths.history_file})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  EXPECT_FALSE(std::filesystem::exists(out + "/erosion.csv")) << "nothing eroded";
  const std::string xmf = mpm::test::slurp(out + "/" + paths.fields_stem + ".xmf");
  EXPECT_NE(xmf.find("Hexahedron"), std::string::npos) << "the mesh is written as hexahedra";

  const core::CsvTable h = core::read_csv(out + "/" + paths.history_file);
  ASSERT_GE(h.rows.size(), 2u);
  for (const char* c : {"hourglass", "viscous", "eroded", "external_work", "energy_error"})
    EXPECT_NO_THROW((void)h.column(c)) << c;
  const double mass = 0.277809;  // the quarter bar, from `afemp check` (6 digits)
  EXPECT_NEAR(h.rows[0][h.column("kinetic")], 0.5 * mass * 300.0 * 300.0,
              1e-5 * 0.5 * mass * 300.0 * 300.0);
  EXPECT_EQ(h.rows[0][h.column("hourglass")], 0.0);
  EXPECT_NEAR(h.rows.back()[h.column("time")], 0.02, 1e-12);
  EXPECT_GT(h.rows.back()[h.column("hourglass")], 0.0);
  EXPECT_GT(h.rows.back()[h.column("viscous")], 0.0);
  EXPECT_EQ(h.rows.back()[h.column("eroded")], 0.0);
}

// Reference: core/scene_parser.cpp: particle and mesh bodies run in separate scenes in this
// version; a scene with both is an input error (exit status 1) that says so.
// A scene with particle and mesh bodies runs both on one clock; `afemp check` says how each
// mesh body meets the grid (here: not at all, then through grid contact).
TEST(FeCli, CheckSaysHowMeshBodiesMeetTheGrid) {
  ScratchDir dir;
  const std::string scene =
      "[run]\nend_time = 1.0\n[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [8, 8, 8]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
      "[[bodies]]\nname = \"particles\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }\n"
      "[[bodies]]\nname = \"mesh\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [4, 4, 4], max = [6, 6, 6] } }\nmesh = { size = 1.0 }\n";
  CommandResult r = run_afemp("check \"" + dir.write("mixed.toml", scene) + "\"", dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("body mesh: FE only"), std::string::npos) << r.out;
  r = run_afemp(
      "check \"" +
          dir.write("contact.toml", scene + "[[contact]]\nbodies = [\"mesh\", \"particles\"]\n") +
          "\"",
      dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("body mesh: 27 nodes in grid contact (CFEMP"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 velocity fields"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace afemp::fem
