// The `afemp` command (apps/main.cpp) as a user meets it: `afemp check` rejects a scene with a
// typo, naming file, line, key and the allowed keys, with a non-zero exit status; `afemp run`
// writes the field output and a history whose first row is the scene's initial state.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/output/history.hpp"
#include "test_support.hpp"

namespace afemp::mpm {
namespace {

// Reference: docs/scene-format.md "Checking": an unknown key is an error reading
// "FILE:LINE: key 'DOTTED.KEY': unknown key; allowed keys here: ...", exit status 1 (input
// error). The typo `densty` is on line 8 of the file.
TEST(Cli, CheckRejectsMisspeltKeyNamingFileLineKeyAndAllowedKeys) {
  test::ScratchDir dir;
  const std::string path = dir.write("typo.toml",
                                     "[run]\n"                    // 1
                                     "end_time = 1.0\n"           // 2
                                     "[grid]\n"                   // 3
                                     "cell = 1.0\n"               // 4
                                     "min = [0, 0, 0]\n"          // 5
                                     "max = [4, 4, 4]\n"          // 6
                                     "[materials.steel]\n"        // 7
                                     "densty = 7.85e-3\n"         // 8
                                     "E = 200e3\n"                // 9
                                     "nu = 0.3\n"                 // 10
                                     "[[bodies]]\n"               // 11
                                     "name = \"b\"\n"             // 12
                                     "material = \"steel\"\n"     // 13
                                     "shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }\n");
  const test::CommandResult r = test::run_afemp("check \"" + path + "\"", dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.exit_code, 1) << "input errors exit with status 1";
  EXPECT_NE(r.err.find(path + ":8:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("materials.steel.densty"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("allowed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("density"), std::string::npos) << "the allowed list names the right key: "
                                                       << r.err;
}

// Reference: a 2 x 2 x 2-cell steel box at n = 2 particles per cell per direction holds
// 4^3 = 64 particles of volume (h / n)^3 = 0.125 mm^3, so m = rho 64 (h / n)^3 =
// 7.85e-3 x 8 = 0.0628 g, and with v = (3, -4, 12) m/s (|v|^2 = 169) the first history row
// (step 0, before any step) has KE = m |v|^2 / 2 = 5.3066 (g mm^2 / ms^2). Tolerance 1e-10
// relative (the CSV keeps 11 significant digits). The run must exit 0 and leave
// fields.h5, fields.xmf and history.csv in the directory given with -o.
TEST(Cli, RunWritesFieldsAndHistoryStartingFromTheSceneKineticEnergy) {
  test::ScratchDir dir;
  const std::string path = dir.write("tiny.toml",
                                     "[run]\nend_time = 1.0\nmax_steps = 20\nhistory_every = 5\n"
                                     "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
                                     "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
                                     "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\n"
                                     "particles_per_cell = 2\nvelocity = [3, -4, 12]\n"
                                     "shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }\n");
  const std::string out = dir.file("out");
  const test::CommandResult r =
      test::run_afemp("run \"" + path + "\" -o \"" + out + "\" --threads 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  for (const char* f : {"fields.h5", "fields.xmf", "history.csv"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;

  const core::CsvTable h = core::read_csv(out + "/history.csv");
  ASSERT_GE(h.rows.size(), 2u);
  const double h_cell = 1.0, n = 2.0, rho = 7.85e-3;
  const double mass = rho * 64 * (h_cell / n) * (h_cell / n) * (h_cell / n);
  const double kinetic = 0.5 * mass * (3.0 * 3.0 + 4.0 * 4.0 + 12.0 * 12.0);
  EXPECT_EQ(h.rows[0][h.column("step")], 0.0);
  EXPECT_NEAR(h.rows[0][h.column("kinetic")], kinetic, 1e-10 * kinetic);
  EXPECT_NEAR(h.rows[0][h.column("cube.pz")], mass * 12.0, 1e-10 * mass * 12.0);
  // The last row is the 20th step (max_steps), and the free rigid translation kept its
  // kinetic energy.
  EXPECT_EQ(h.rows.back()[h.column("step")], 20.0);
  EXPECT_NEAR(h.rows.back()[h.column("kinetic")], kinetic, 1e-10 * kinetic);
}

}  // namespace
}  // namespace afemp::mpm
