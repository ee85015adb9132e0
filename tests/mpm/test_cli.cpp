// The `afemp` command (apps/main.cpp) as a user meets it: `afemp check` rejects a scene with a
// typo, naming file, line, key and the allowed keys, with a non-zero exit status; `afemp run`
// writes the field output and a history whose first row is the scene's initial state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "afemp/run_directory.hpp"
#include "copper_bar_on_wall.hpp"
#include "core/output/history.hpp"
#include "fem/phase_test_support.hpp"
#include "striker_on_plate.hpp"
#include "taylor_bar_scene.hpp"
#include "test_support.hpp"

namespace afemp::mpm {
namespace {

// Reference: docs/scene-format.md "Checking": an unknown key is an error reading
// "FILE:LINE: key 'DOTTED.KEY': unknown key; allowed keys here: ...", exit status 1 (input
// error). The typo `densty` is on line 8 of the file.
TEST(Cli, CheckRejectsMisspeltKeyNamingFileLineKeyAndAllowedKeys) {
  test::ScratchDir dir;
  const std::string path = dir.write("typo.toml",
                                     "[run]\n"                 // 1
                                     "end_time = 1.0\n"        // 2
                                     "[grid]\n"                // 3
                                     "cell = 1.0\n"            // 4
                                     "min = [0, 0, 0]\n"       // 5
                                     "max = [4, 4, 4]\n"       // 6
                                     "[materials.steel]\n"     // 7
                                     "densty = 7.85e-3\n"      // 8
                                     "E = 200e3\n"             // 9
                                     "nu = 0.3\n"              // 10
                                     "[[bodies]]\n"            // 11
                                     "name = \"b\"\n"          // 12
                                     "material = \"steel\"\n"  // 13
                                     "shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }\n");
  const test::CommandResult r = test::run_afemp("check \"" + path + "\"", dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.exit_code, 1) << "input errors exit with status 1";
  EXPECT_NE(r.err.find(path + ":8:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("materials.steel.densty"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("allowed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("density"), std::string::npos)
      << "the allowed list names the right key: " << r.err;
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

// A small particle scene for the launcher tests: a steel cube in flight, 64 particles.
const char* const tiny_cube =
    "[run]\nend_time = 1.0\nmax_steps = 5\n"
    "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
    "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
    "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\n"
    "particles_per_cell = 2\nvelocity = [3, -4, 12]\n"
    "shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }\n";

// Reference: apps/main.cpp: afemp started by a launcher as one of several MPI processes where it
// cannot divide the run refuses, exit status 1, naming the count and the variable, before it
// reads the scene or writes anything (each process would run the whole scene and write over the
// others' output): another MPI's launcher (MPICH's PMI_SIZE, MVAPICH2's MV2_COMM_WORLD_SIZE) in a
// build with Open MPI, or any launcher in a build without MPI; a command other than `run`. One
// process under a launcher runs as usual, its first history row the scene's kinetic energy.
TEST(Cli, RunRefusesToBeOneOfSeveralProcessesItCannotDivideAndWritesNothing) {
  test::ScratchDir dir;
  const std::string path = dir.write("tiny.toml", tiny_cube);
#ifdef AFEMP_MPIEXEC
  const std::vector<std::string> launchers = {"PMI_SIZE", "MV2_COMM_WORLD_SIZE"};
#else
  const std::vector<std::string> launchers = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"};
#endif
  for (const std::string& variable : launchers) {
    const std::string out = dir.file("out_" + variable);
    const test::CommandResult r =
        test::run_captured(variable + "=4 \"" + AFEMP_BINARY + "\" run \"" + path + "\" -o \"" +
                               out + "\" --threads 1",
                           dir);
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_NE(r.err.find("one of 4 MPI processes"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(variable + "=4"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing written";
  }
  const test::CommandResult check = test::run_captured(
      "PMI_SIZE=3 \"" + std::string(AFEMP_BINARY) + "\" check \"" + path + "\"", dir);
  EXPECT_EQ(check.exit_code, 1) << check.out << check.err;
  EXPECT_NE(check.err.find("one of 3 MPI processes"), std::string::npos) << check.err;
  const std::string out = dir.file("out_one");
  const test::CommandResult one =
      test::run_captured("OMPI_COMM_WORLD_SIZE=1 \"" + std::string(AFEMP_BINARY) + "\" run \"" +
                             path + "\" -o \"" + out + "\" --threads 1",
                         dir);
  ASSERT_EQ(one.exit_code, 0) << one.out << one.err;
  const core::CsvTable h = core::read_csv(out + "/history.csv");
  ASSERT_GE(h.rows.size(), 1u);
  const double mass = 7.85e-3 * 64 * 0.125;
  EXPECT_NEAR(h.rows[0][h.column("kinetic")], 0.5 * mass * 169.0, 1e-10 * 0.5 * mass * 169.0);
}

#ifdef AFEMP_MPIEXEC
// Open MPI's launcher for the tests: as root (CI), two ranks on however many cores, shared
// memory copied twice (containers forbid cross-memory attach).
std::string mpiexec(int ranks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "OMPI_MCA_btl_vader_single_copy_mechanism=none \"" AFEMP_MPIEXEC "\" --oversubscribe -n " +
         std::to_string(ranks) + " ";
}

// `afemp run` of a scene in one process into `one`, then on 2 MPI ranks into `two` (a thread
// each): the two results.
struct AloneAndOnRanks {
  test::CommandResult alone, ranks;
};

AloneAndOnRanks run_alone_and_on_two_ranks(const std::string& path, const std::string& one,
                                           const std::string& two, const test::ScratchDir& dir) {
  // Appended in turn: GCC 12's -Wrestrict warns, falsely, on "\"" + std::string&& here.
  std::string afemp = "\"";
  afemp += AFEMP_BINARY;
  afemp += "\" run \"";
  afemp += path;
  afemp += "\" --threads 1 -o \"";
  AloneAndOnRanks r;
  r.alone = test::run_captured(afemp + one + "\"", dir);
  r.ranks = test::run_captured(mpiexec(2) + afemp + two + "\"", dir);
  return r;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The particles of an XDMF index's first frame (its first 3-component DataItem).
std::size_t first_frame_points(const std::string& xmf) {
  std::smatch m;
  const std::string text = read_text(xmf);
  if (!std::regex_search(text, m, std::regex("Dimensions=\"([0-9]+) 3\""))) return 0;
  return std::stoul(m[1].str());
}

// How many 3-component DataItems of the XDMF index hold `n` points (positions, velocities, ...
// of every frame).
int frames_of(const std::string& xmf, std::size_t n) {
  const std::string text = read_text(xmf);
  const std::string key = "Dimensions=\"" + std::to_string(n) + " 3\"";
  int count = 0;
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1))
    ++count;
  return count;
}

// The times of an XDMF index's frames, as written.
std::vector<std::string> frame_times(const std::string& xmf_text) {
  std::vector<std::string> times;
  const std::regex time("<Time Value=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(xmf_text.begin(), xmf_text.end(), time);
       it != std::sregex_iterator(); ++it)
    times.push_back((*it)[1].str());
  return times;
}

// Every value of a run's history within `tolerance` of its column's largest magnitude in the
// reference history (the same rows and columns).
void expect_history_near(const std::string& reference, const std::string& run, double tolerance) {
  const core::CsvTable h1 = core::read_csv(reference);
  const core::CsvTable h2 = core::read_csv(run);
  ASSERT_EQ(h1.header, h2.header);
  ASSERT_EQ(h1.rows.size(), h2.rows.size()) << run;
  for (std::size_t c = 0; c < h1.header.size(); ++c) {
    double scale = 0.0;
    for (const auto& row : h1.rows) scale = std::max(scale, std::abs(row[c]));
    for (std::size_t r = 0; r < h1.rows.size(); ++r)
      EXPECT_NEAR(h2.rows[r][c], h1.rows[r][c], tolerance * scale)
          << run << ": " << h1.header[c] << ", row " << r;
  }
}

// The copper bar on a wall for `steps` steps (about 6e-5 ms each), MUSL, a history row every 5
// steps, frames every 0.004 ms and checkpoints every 0.002 ms (steps 34 and 67).
std::string bar_steps(int steps) {
  return afemp::test::copper_bar_on_wall(
      "end_time = 1.0\nmax_steps = " + std::to_string(steps) +
          "\noutput_every = 0.004\nhistory_every = 5\ncheckpoint_every = 0.002\n",
      "scheme = \"MUSL\"\n");
}

// Reference: the same scene run as one process. `mpiexec -n 2 afemp run` divides it among two
// ranks (docs/parallel.md): one "afemp run" line (rank 1 prints nothing), every history and
// probe value within 1e-10 of its column's largest magnitude of the one-process run's (round-off:
// the shared nodes add in another order), every frame with every particle (written by rank 0), and
// no scratch directory of rank 1 left behind. A copper bar on a wall, 2,300 particles, 100 steps,
// moving across the ranks' blocks.
TEST(Cli, RunDividedAmongTwoMpiRanksGivesTheOneProcessHistoryAndFrames) {
  test::ScratchDir dir;
  const std::string path = dir.write(
      "bar.toml",
      afemp::test::copper_bar_on_wall(
          "end_time = 1.0\nmax_steps = 100\noutput_every = 0.004\nhistory_every = 5\n",
          "scheme = \"MUSL\"\n") +
          // The probes sample particles on whichever rank holds them, and extremes
          // over every rank's: the top of the bar, a particle by index, the largest
          // pressure, the lowest point.
          "[[probes]]\nname = \"top\"\nparticle = { body = \"bar\", near = [0, 0, 25.4] }\n"
          "[[probes]]\nname = \"p100\"\nparticle = { body = \"bar\", index = 100 }\n"
          "[[probes]]\nname = \"peak\"\nextreme = { field = \"pressure\", of = \"max\", "
          "box = { min = [0, 0, 0], max = [10, 10, 28] } }\n"
          "[[probes]]\nname = \"lowest\"\nextreme = { field = \"z\", of = \"min\", "
          "box = { min = [0, 0, 0], max = [10, 10, 28] } }\n");
  const std::string one = dir.file("one"), two = dir.file("two");
  const std::string args = " run \"" + path + "\" --threads 1 -o ";
  const test::CommandResult a =
      test::run_captured("\"" + std::string(AFEMP_BINARY) + "\"" + args + "\"" + one + "\"", dir);
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  const std::string tmp = dir.file("tmp");
  std::filesystem::create_directories(tmp);
  const test::CommandResult b =
      test::run_captured("TMPDIR=\"" + tmp + "\" " + mpiexec(2) + "\"" + AFEMP_BINARY + "\"" +
                             args + "\"" + two + "\"",
                         dir);
  ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  std::size_t lines = 0;
  for (std::size_t at = b.out.find("afemp run "); at != std::string::npos;
       at = b.out.find("afemp run ", at + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << b.out;
  EXPECT_NE(b.out.find("2 MPI ranks x 1 thread(s)"), std::string::npos) << b.out;
  for (const auto& entry : std::filesystem::directory_iterator(tmp))
    EXPECT_EQ(entry.path().filename().string().rfind("afemp-rank-", 0), std::string::npos)
        << "rank 1's scratch directory is removed: " << entry.path();

  const core::CsvTable h1 = core::read_csv(one + "/history.csv");
  ASSERT_GE(h1.rows.size(), 20u);
  EXPECT_EQ(h1.rows.back()[h1.column("step")], 100.0);
  expect_history_near(one + "/history.csv", two + "/history.csv", 1e-10);
  EXPECT_GT(h1.rows.back()[h1.column("plastic")], 0.0);  // the foot yields
  for (const char* probe : {"top", "p100"})
    expect_history_near(one + "/probes/" + probe + ".csv", two + "/probes/" + probe + ".csv",
                        1e-10);
  // An extreme's value (where several points hold it to round-off, which one is named may
  // differ: its position is not compared).
  for (const char* probe : {"peak", "lowest"}) {
    const core::CsvTable p1 = core::read_csv(one + "/probes/" + probe + ".csv");
    const core::CsvTable p2 = core::read_csv(two + "/probes/" + probe + ".csv");
    ASSERT_EQ(p1.rows.size(), p2.rows.size()) << probe;
    ASSERT_GE(p1.rows.size(), 20u) << probe;
    const std::size_t c = p1.column("value");
    double scale = 0.0;
    for (const auto& row : p1.rows) scale = std::max(scale, std::abs(row[c]));
    for (std::size_t r = 0; r < p1.rows.size(); ++r)
      EXPECT_NEAR(p2.rows[r][c], p1.rows[r][c], 1e-10 * scale) << probe << ", row " << r;
  }
  EXPECT_GT(core::read_csv(one + "/probes/peak.csv").rows.back()[1], 100.0);  // MPa, at the foot
  // Every frame of the divided run holds every particle, as the one-process run's do (the
  // positions, velocities and other vectors of each frame).
  const std::size_t particles = first_frame_points(one + "/fields.xmf");
  EXPECT_GT(particles, 2000u);
  const int frames = frames_of(one + "/fields.xmf", particles);
  EXPECT_GE(frames, 6);
  EXPECT_EQ(frames_of(two + "/fields.xmf", particles), frames);

  // Rebalanced by measured time at step 100 (an imbalance of 1: any rank above the mean), the
  // run still ends with the one-process history, and the summary counts the rebalance.
  const std::string timed = dir.file("timed");
  const test::CommandResult c =
      test::run_captured(mpiexec(2) + "\"" + AFEMP_BINARY + "\"" + args + "\"" + timed +
                             "\" --balance time --imbalance 1",
                         dir);
  ASSERT_EQ(c.exit_code, 0) << c.out << c.err;
  EXPECT_NE(c.out.find("rebalance (1 time)"), std::string::npos) << c.out;
  expect_history_near(one + "/history.csv", timed + "/history.csv", 1e-10);
  EXPECT_EQ(frames_of(timed + "/fields.xmf", particles), frames);
}

// The reproducible mode ([run] reproducible = true): the bar of particles with probes of a
// particle and an extreme, run in one process at one thread and at two, and on 2 and 3 ranks;
// an eroding bar of hexahedra, and a striker of converting hexahedra on a plate of particles,
// at two threads and on 2 ranks. Reference: the one-process files,
// byte for byte: the history and every probe (the mode's sums do not depend on their order,
// docs/parallel.md "The reproducible mode"). The particle scene without the mode on 2 ranks
// differs from one process (in the last bits: the mode is what makes them equal).
TEST(Cli, ReproducibleRunGivesTheSameFilesOnAnyRankAndThreadCount) {
  test::ScratchDir dir;
  const std::string probes =
      "[[probes]]\nname = \"top\"\nparticle = { body = \"bar\", near = [0, 0, 25.4] }\n"
      "[[probes]]\nname = \"peak\"\nextreme = { field = \"pressure\", of = \"max\", "
      "box = { min = [0, 0, 0], max = [10, 10, 28] } }\n";
  const std::string run = "end_time = 1.0\nmax_steps = 100\nhistory_every = 5\n";
  const std::string path = dir.write(
      "bar.toml",
      afemp::test::copper_bar_on_wall(run + "reproducible = true\n", "scheme = \"MUSL\"\n") +
          probes);
  const std::string plain =
      dir.write("plain.toml", afemp::test::copper_bar_on_wall(run, "scheme = \"MUSL\"\n") + probes);
  auto afemp = [&](const std::string& launcher, const std::string& scene, const std::string& out,
                   int threads) {
    const test::CommandResult r = test::run_captured(
        launcher + "\"" + std::string(AFEMP_BINARY) + "\" run \"" + scene + "\" --threads " +
            std::to_string(threads) + " -o \"" + dir.file(out) + "\"",
        dir);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    return dir.file(out);
  };
  const std::string one = afemp("", path, "one", 1);
  const std::string history = read_text(one + "/history.csv");
  ASSERT_GT(std::count(history.begin(), history.end(), '\n'), 20);
  for (const std::string& other : {afemp("", path, "threads", 2), afemp(mpiexec(2), path, "two", 1),
                                   afemp(mpiexec(3), path, "three", 1)}) {
    EXPECT_EQ(read_text(other + "/history.csv"), history) << other;
    for (const char* probe : {"/probes/top.csv", "/probes/peak.csv"})
      EXPECT_EQ(read_text(other + probe), read_text(one + probe)) << other << probe;
  }
  const std::string plain_one = afemp("", plain, "plain_one", 1);
  const std::string plain_two = afemp(mpiexec(2), plain, "plain_two", 1);
  EXPECT_NE(read_text(plain_two + "/history.csv"), read_text(plain_one + "/history.csv"));
  expect_history_near(one + "/history.csv", plain_one + "/history.csv", 1e-10);

  // A mesh: the coarse Taylor bar of one-point hexahedra, eroding, 150 steps, on 2 ranks and
  // at 2 threads: the history byte for byte.
  std::string mesh = afemp::test::taylor_bar_scene(true);
  mesh.replace(mesh.find("end_time = 0.01"), 15,
               "end_time = 1.0\nmax_steps = 150\nhistory_every = 5\nreproducible = true");
  mesh.replace(mesh.find("velocity = [0, 0, -190]"), 23,
               "velocity = [0, 0, -400]\nerosion = { plastic_strain = 0.8 }");
  const std::string mesh_path = dir.write("mesh.toml", mesh);
  const std::string mesh_history = read_text(afemp("", mesh_path, "mesh_one", 1) + "/history.csv");
  EXPECT_EQ(read_text(afemp("", mesh_path, "mesh_threads", 2) + "/history.csv"), mesh_history);
  EXPECT_EQ(read_text(afemp(mpiexec(2), mesh_path, "mesh_two", 1) + "/history.csv"), mesh_history);

  // Meshes and particles coupled: the striker's hexahedra in grid contact with the plate's
  // particles, converting as they yield, beside trusses bonded into the plate, 100 steps on 2
  // ranks and at 2 threads: the history (the contact's and the bond's forces, the converted
  // energy) byte for byte.
  std::string coupled = afemp::test::striker_on_plate(
      true, "end_time = 1.0\nmax_steps = 100\nhistory_every = 5\nreproducible = true\n");
  const std::string hexes = "mesh = { size = 1.0, sectors = 1 }";
  coupled.replace(coupled.find(hexes), hexes.size(),
                  hexes + "\nconversion = { plastic_strain = 0.05, points = 2 }");
  const std::string coupled_path = dir.write("coupled.toml", coupled);
  const std::string coupled_history =
      read_text(afemp("", coupled_path, "coupled_one", 1) + "/history.csv");
  ASSERT_GT(std::count(coupled_history.begin(), coupled_history.end(), '\n'), 20);
  EXPECT_EQ(read_text(afemp("", coupled_path, "coupled_threads", 2) + "/history.csv"),
            coupled_history);
  EXPECT_EQ(read_text(afemp(mpiexec(2), coupled_path, "coupled_two", 1) + "/history.csv"),
            coupled_history);
}

// Reference: the same scene run as one process. A mesh scene divides by its elements, every
// rank moving every node (docs/parallel.md): the coarse Taylor bar of one-point hexahedra with
// erosion, 150 steps on 2 and 3 ranks. Every history value within 1e-10 of its column's largest
// magnitude (the nodes' figures are one process's to the bit, the element energies added over
// the ranks in rank order), the node and element probes the same, the erosion records rank 0
// writes every rank's in one process's order (their energies to 1e-10), every frame written.
TEST(Cli, MeshRunDividedAmongMpiRanksGivesTheOneProcessHistoryProbesAndErosion) {
  test::ScratchDir dir;
  std::string scene = afemp::test::taylor_bar_scene(true);
  scene.replace(scene.find("end_time = 0.01"), 15,
                "end_time = 1.0\nmax_steps = 150\noutput_every = 0.004\nhistory_every = 5");
  scene.replace(scene.find("velocity = [0, 0, -190]"), 23,
                "velocity = [0, 0, -400]\nerosion = { plastic_strain = 0.8 }");
  scene +=
      "[[probes]]\nname = \"top\"\nnode = { body = \"bar\", near = [0, 0, 25.4] }\n"
      "[[probes]]\nname = \"foot\"\nelement = { body = \"bar\", near = [1, 1, 6] }\n"
      "[[probes]]\nname = \"peak\"\nextreme = { field = \"von_mises\", of = \"max\", "
      "box = { min = [0, 0, 0], max = [10, 10, 28] } }\n";
  const std::string path = dir.write("bar.toml", scene);
  const std::string afemp = "\"" + std::string(AFEMP_BINARY) + "\"";
  const std::string one = dir.file("one");
  const test::CommandResult a =
      test::run_captured(afemp + " run \"" + path + "\" --threads 1 -o \"" + one + "\"", dir);
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  const core::CsvTable h1 = core::read_csv(one + "/history.csv");
  EXPECT_EQ(h1.rows.back()[h1.column("step")], 150.0);
  EXPECT_GT(h1.rows.back()[h1.column("eroded")], 0.0);  // the foot eroded
  // erosion.csv: time,kind,id,body,reason,energy,mass per row.
  const auto erosion_rows = [](const std::string& file) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(read_text(file));
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) {
      std::vector<std::string> cells;
      std::istringstream cut(line);
      for (std::string cell; std::getline(cut, cell, ',');) cells.push_back(cell);
      rows.push_back(cells);
    }
    return rows;
  };
  const auto e1 = erosion_rows(one + "/erosion.csv");
  ASSERT_GT(e1.size(), 4u);
  const std::size_t points = first_frame_points(one + "/fields.xmf");
  const int frames = frames_of(one + "/fields.xmf", points);
  EXPECT_GE(frames, 3);
  for (int ranks : {2, 3}) {
    const std::string out = dir.file("ranks" + std::to_string(ranks));
    const test::CommandResult b = test::run_captured(
        mpiexec(ranks) + afemp + " run \"" + path + "\" --threads 1 -o \"" + out + "\"", dir);
    ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
    EXPECT_NE(b.out.find(std::to_string(ranks) + " MPI ranks x 1 thread(s)"), std::string::npos)
        << b.out;
    EXPECT_NE(b.out.find("element results to every rank"), std::string::npos) << b.out;
    expect_history_near(one + "/history.csv", out + "/history.csv", 1e-10);
    for (const char* probe : {"top", "foot", "peak"})
      expect_history_near(one + "/probes/" + probe + ".csv", out + "/probes/" + probe + ".csv",
                          1e-10);
    const auto e2 = erosion_rows(out + "/erosion.csv");
    ASSERT_EQ(e2.size(), e1.size()) << out;
    for (std::size_t r = 0; r < e1.size(); ++r) {
      ASSERT_EQ(e2[r].size(), 7u) << out << ", row " << r;
      for (std::size_t c : {0, 1, 2, 3, 4, 6}) EXPECT_EQ(e2[r][c], e1[r][c]) << "row " << r;
      const double energy = std::stod(e1[r][5]);
      EXPECT_NEAR(std::stod(e2[r][5]), energy, 1e-10 * std::abs(energy)) << "row " << r;
    }
    EXPECT_EQ(frames_of(out + "/fields.xmf", points), frames);
  }
}

// Reference: the coupled run in one process (120 steps): the striker of hexahedra onto the plate
// of particles in grid contact (CFEMP), a rod of trusses bonded into the plate (HFEMP), with a
// node probe on the striker, a particle probe in the plate and an extreme over both. On 2 and 3
// ranks: every history value (energies, the contact's and the bond's forces) within 1e-10 of
// its column's largest magnitude, the probes the same, every frame with every particle.
TEST(Cli, CoupledRunDividedAmongMpiRanksGivesTheOneProcessHistoryAndProbes) {
  test::ScratchDir dir;
  std::string scene = afemp::test::striker_on_plate(
      true, "end_time = 1.0\nmax_steps = 120\noutput_every = 0.004\nhistory_every = 5\n");
  scene +=
      "[[probes]]\nname = \"tail\"\nnode = { body = \"striker\", near = [0, 0, 12.2] }\n"
      "[[probes]]\nname = \"below\"\nparticle = { body = \"plate\", near = [0.5, 0.5, 0.5] }\n"
      "[[probes]]\nname = \"peak\"\nextreme = { field = \"von_mises\", of = \"max\", "
      "box = { min = [0, 0, 0], max = [16, 16, 14] } }\n";
  const std::string path = dir.write("coupled.toml", scene);
  const std::string afemp = "\"" + std::string(AFEMP_BINARY) + "\"";
  const std::string one = dir.file("one");
  const test::CommandResult a =
      test::run_captured(afemp + " run \"" + path + "\" --threads 1 -o \"" + one + "\"", dir);
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  const core::CsvTable h1 = core::read_csv(one + "/history.csv");
  EXPECT_EQ(h1.rows.back()[h1.column("step")], 120.0);
  EXPECT_GT(h1.rows.back()[h1.column("contact")], 0.0);  // the contact acted
  const std::size_t points = first_frame_points(one + "/fields.xmf");
  const int frames = frames_of(one + "/fields.xmf", points);
  EXPECT_GE(frames, 2);
  for (int ranks : {2, 3}) {
    const std::string out = dir.file("ranks" + std::to_string(ranks));
    const test::CommandResult b = test::run_captured(
        mpiexec(ranks) + afemp + " run \"" + path + "\" --threads 1 -o \"" + out + "\"", dir);
    ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
    EXPECT_NE(b.out.find(std::to_string(ranks) + " MPI ranks x 1 thread(s)"), std::string::npos)
        << b.out;
    expect_history_near(one + "/history.csv", out + "/history.csv", 1e-10);
    for (const char* probe : {"tail", "below", "peak"})
      expect_history_near(one + "/probes/" + probe + ".csv", out + "/probes/" + probe + ".csv",
                          1e-10);
    EXPECT_EQ(frames_of(out + "/fields.xmf", points), frames);
  }
}

// Reference: the run in one process. A steel column (fem/phase_test_support.hpp) solved static
// under its weight, then run explicitly: on 2 ranks rank 0 solves the phase in an undivided
// model and every rank takes its state. The history's energies and the top's velocity within
// 1e-10 of their largest magnitude (the explicit steps add the ranks' elements in rank order),
// and static_phase.csv written by rank 0 byte for byte as one process writes it (the sparse
// solve's BLAS runs the run's thread count, not as many as the launcher's binding leaves it). A
// solve that cannot converge (tolerance 1e-30) stops every rank with the one-process exit status,
// rank 0 giving the solver's message and its iterations' file, the other rank naming rank 0's,
// and the run's last frame (the state the solve failed in) written as one process writes it.
TEST(Cli, RunOnMpiRanksSolvesAStaticPhaseOnRankZeroAsOneProcessDoes) {
  test::ScratchDir dir;
  const std::string phases =
      "[[phases]]\nkind = \"static\"\nend_time = 1.0\nload_steps = 2\n"
      "[[phases]]\nkind = \"explicit\"\n";
  const std::string path =
      dir.write("column.toml", afemp::test::column_scene("element = \"full\"", phases, 1.01));
  const std::string one = dir.file("one"), two = dir.file("two");
  const auto [a, b] = run_alone_and_on_two_ranks(path, one, two, dir);
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  EXPECT_NE(b.out.find("the static phase ends at t = 1"), std::string::npos) << b.out;

  const core::CsvTable h1 = core::read_csv(one + "/history.csv");
  const core::CsvTable h2 = core::read_csv(two + "/history.csv");
  ASSERT_EQ(h1.header, h2.header);
  ASSERT_EQ(h1.rows.size(), h2.rows.size());
  EXPECT_GT(h1.rows.size(), 10u);
  for (const char* name : {"time", "kinetic", "internal", "external_work", "column.vz"}) {
    const std::size_t c = h1.column(name);
    double scale = 0.0;
    for (const auto& row : h1.rows) scale = std::max(scale, std::abs(row[c]));
    EXPECT_GT(scale, 0.0) << name;
    for (std::size_t r = 0; r < h1.rows.size(); ++r)
      EXPECT_NEAR(h2.rows[r][c], h1.rows[r][c], 1e-10 * scale) << name << ", row " << r;
  }
  const core::CsvTable s1 = core::read_csv(one + "/static_phase.csv");
  const core::CsvTable s2 = core::read_csv(two + "/static_phase.csv");
  ASSERT_EQ(s1.header, s2.header);
  ASSERT_EQ(s1.rows.size(), s2.rows.size());
  EXPECT_GE(s1.rows.size(), 2u);  // a row per Newton iteration, two load steps
  EXPECT_EQ(read_text(two + "/static_phase.csv"), read_text(one + "/static_phase.csv"));

  const std::string bad = dir.write(
      "bad.toml", afemp::test::column_scene("element = \"full\"",
                                            "[[phases]]\nkind = \"static\"\nend_time = 1.0\n"
                                            "max_iterations = 2\ntolerance = 1e-30\n"
                                            "[[phases]]\nkind = \"explicit\"\n",
                                            1.01));
  const std::string bad_one = dir.file("bad_one"), bad_two = dir.file("bad_two");
  const auto [c, d] = run_alone_and_on_two_ranks(bad, bad_one, bad_two, dir);
  EXPECT_EQ(c.exit_code, 3) << c.out << c.err;
  EXPECT_EQ(d.exit_code, c.exit_code) << d.out << d.err;
  const std::string why = "did not converge in 2 iterations";
  EXPECT_NE(c.err.find(why), std::string::npos) << c.err;
  EXPECT_NE(d.err.find("afemp: simulation stopped: step 0 (t = 0): the static phase"),
            std::string::npos)
      << d.err;
  EXPECT_NE(d.err.find("afemp (rank 1 of 2): simulation stopped: step 0 (t = 0): rank 0's "
                       "static phase, field 'solve': rank 0 says why"),
            std::string::npos)
      << d.err;
  EXPECT_EQ(core::read_csv(bad_two + "/static_phase.csv").rows.size(),
            core::read_csv(bad_one + "/static_phase.csv").rows.size());
  // The message names "the run's last frame": the start's frame and the failed solve's (the last
  // converged load step's state), on ranks as in one process, the same times.
  const std::string failed = read_text(bad_one + "/fields.xmf");
  EXPECT_EQ(frame_times(failed).size(), 2u) << failed;
  EXPECT_EQ(frame_times(read_text(bad_two + "/fields.xmf")), frame_times(failed));
  EXPECT_EQ(first_frame_points(bad_two + "/fields.xmf"),
            first_frame_points(bad_one + "/fields.xmf"));

  // An implicit phase that fails after some of its steps converged (yield 100 MPa, one iteration
  // a step: ImplicitPhase.StepThatDoesNotConverge...): the run's last frame is the last converged
  // step's state at its time, which rank 0 sends to every rank; the same frames, the last after t =
  // 0.
  std::string yielding = afemp::test::column_scene(
      "element = \"full\"",
      "[[phases]]\nkind = \"implicit\"\nend_time = 0.05\ntime_step = 0.0005\n"
      "max_iterations = 1\n[[phases]]\nkind = \"explicit\"\n",
      0.06);
  yielding.replace(yielding.find("nu = 0.3\n"), 9,
                   "nu = 0.3\nstrength = { model = \"j2\", yield = 100 }\n");
  const std::string implicit = dir.write("implicit.toml", yielding);
  const std::string im_one = dir.file("im_one"), im_two = dir.file("im_two");
  const auto [e, f] = run_alone_and_on_two_ranks(implicit, im_one, im_two, dir);
  EXPECT_EQ(e.exit_code, 3) << e.out << e.err;
  EXPECT_NE(e.err.find("the run's last frame"), std::string::npos) << e.err;
  EXPECT_EQ(f.exit_code, 3) << f.out << f.err;
  const std::vector<std::string> im_times = frame_times(read_text(im_one + "/fields.xmf"));
  ASSERT_EQ(im_times.size(), 2u);
  EXPECT_GT(std::stod(im_times.back()), 0.0);
  EXPECT_EQ(frame_times(read_text(im_two + "/fields.xmf")), im_times);
  EXPECT_EQ(read_text(im_two + "/implicit_phase.csv"), read_text(im_one + "/implicit_phase.csv"));
}

// Reference: the run in one process. A block of one-point hexahedra at nu = 0.499 with viscous
// hourglass control and the default element step factor 0.9 is past its stability limit (the
// stability suite: +3234 % without the guard) and the energy guard stops it as unstable. On 2
// ranks the guard's energy balance is the whole run's, the same on every rank: both stop with the
// one-process exit status 3 and the field 'energy balance' at the same step, and the ranks write
// the run's last frame together, so the frames are one process's, at the same times, the state
// the run stopped in last.
TEST(Cli, RunOnMpiRanksStoppedByTheEnergyGuardKeepsTheLastFrameAsOneProcessDoes) {
  test::ScratchDir dir;
  const std::string path = dir.write("unstable.toml", R"([run]
end_time = 0.01
output_every = 0.002
[materials.rubber]
density = 1.0e-3
E = 100.0
nu = 0.499
[[bodies]]
name = "block"
discretisation = "hexahedra"
material = "rubber"
shape = { box = { min = [-4, -4, 0], max = [4, 4, 8] } }
mesh = { size = 1.0 }
velocity = [0, 0, -20]
element = "one-point"
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
fixed = ["z"]
)");
  const std::string one = dir.file("one"), two = dir.file("two");
  const auto [a, b] = run_alone_and_on_two_ranks(path, one, two, dir);
  EXPECT_EQ(a.exit_code, 3) << a.out << a.err;
  EXPECT_EQ(b.exit_code, 3) << b.out << b.err;
  std::smatch m1, m2;
  const std::regex stopped("simulation stopped: step ([0-9]+) .*field 'energy balance'");
  ASSERT_TRUE(std::regex_search(a.err, m1, stopped)) << a.err;
  ASSERT_TRUE(std::regex_search(b.err, m2, stopped)) << b.err;
  EXPECT_EQ(m2[1].str(), m1[1].str()) << "the step the guard stopped at";
  const std::string frames = read_text(one + "/fields.xmf");
  const std::vector<std::string> times = frame_times(frames);
  ASSERT_GE(times.size(), 2u) << frames;
  EXPECT_EQ(frame_times(read_text(two + "/fields.xmf")), times);
  EXPECT_EQ(core::read_csv(two + "/history.csv").rows.size(),
            core::read_csv(one + "/history.csv").rows.size());
}

// Reference: the uninterrupted run in one process (100 steps). The bar on 4 ranks stops at step
// 50 with a checkpoint at step 34, written by rank 0 as one process's (every particle, the sums
// of every rank). Continued from it on 2 ranks, and a copy of it in one process, both end with
// the one-process history within 1e-10 of each column's largest magnitude (round-off: the
// partition is made anew, the shared nodes add in another order) and all its frames; the header
// names the 4 ranks that wrote it. Changed in a key a restart may not change, the scene is
// refused on every rank, rank 0 saying so once, and the run's files stay as they were.
TEST(Cli, RunOnFourMpiRanksRestartsOnTwoAndInOneProcessAsTheUninterruptedRun) {
  test::ScratchDir dir;
  const std::string path = dir.write("bar.toml", bar_steps(100));
  const std::string half = dir.write("half.toml", bar_steps(50));
  const std::string one = dir.file("one"), four = dir.file("four"), copy = dir.file("copy");
  const std::string afemp = "\"" + std::string(AFEMP_BINARY) + "\"";
  const test::CommandResult a =
      test::run_captured(afemp + " run \"" + path + "\" --threads 1 -o \"" + one + "\"", dir);
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  const test::CommandResult b = test::run_captured(
      mpiexec(4) + afemp + " run \"" + half + "\" --threads 1 -o \"" + four + "\"", dir);
  ASSERT_EQ(b.exit_code, 0) << b.out << b.err;
  const std::vector<std::string> saved = afemp::list_checkpoints(four);
  ASSERT_EQ(saved.size(), 1u);
  const CheckpointInfo info = afemp::read_checkpoint_info(saved[0]);
  EXPECT_EQ(info.step, 34);
  EXPECT_EQ(info.ranks, 4);
  std::filesystem::copy(four, copy, std::filesystem::copy_options::recursive);

  const std::string changed = dir.write(
      "changed.toml",
      std::regex_replace(bar_steps(100), std::regex("density = 8.93e-3"), "density = 8.9e-3"));
  const std::string before = read_text(four + "/history.csv");
  const test::CommandResult refused = test::run_captured(
      mpiexec(2) + afemp + " run \"" + changed + "\" --threads 1 --restart \"" + four + "\"", dir);
  EXPECT_NE(refused.exit_code, 0) << refused.out << refused.err;
  const std::string why = "the scene changed since the checkpoint";
  EXPECT_NE(refused.err.find(why), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find(why), refused.err.rfind(why)) << "said once: " << refused.err;
  EXPECT_EQ(read_text(four + "/history.csv"), before) << "the run's files untouched";

  const test::CommandResult two = test::run_captured(
      mpiexec(2) + afemp + " run \"" + path + "\" --threads 1 --restart \"" + four + "\"", dir);
  ASSERT_EQ(two.exit_code, 0) << two.out << two.err;
  EXPECT_NE(two.out.find("2 MPI ranks x 1 thread(s)), continuing from"), std::string::npos)
      << two.out;
  EXPECT_NE(two.out.find("written by 4 rank(s)"), std::string::npos) << two.out;
  const test::CommandResult alone = test::run_captured(
      afemp + " run \"" + path + "\" --threads 1 --restart \"" + copy + "\"", dir);
  ASSERT_EQ(alone.exit_code, 0) << alone.out << alone.err;
  EXPECT_NE(alone.err.find("written by 4 MPI ranks"), std::string::npos) << alone.err;

  const std::size_t particles = first_frame_points(one + "/fields.xmf");
  EXPECT_GT(particles, 2000u);
  for (const std::string& run : {four, copy}) {
    expect_history_near(one + "/history.csv", run + "/history.csv", 1e-10);
    EXPECT_EQ(frames_of(run + "/fields.xmf", particles), frames_of(one + "/fields.xmf", particles))
        << run;
  }
}

// Reference: the uninterrupted run in one process. Rank 1 of 2 is killed at step 60 (SIGKILL,
// as the kernel's OOM killer would; AFEMP_FAULT, core/fault_injection.hpp): the launcher stops
// rank 0 too and says which rank died, the run's files end before step 60 with the checkpoint of
// step 34, and `--restart` on 2 ranks ends with the one-process history within 1e-10.
TEST(Cli, ARankThatDiesStopsTheRunAndItsLastCheckpointRestarts) {
  test::ScratchDir dir;
  const std::string path = dir.write("bar.toml", bar_steps(100));
  const std::string one = dir.file("one"), two = dir.file("two");
  const std::string afemp = "\"" + std::string(AFEMP_BINARY) + "\"";
  const test::CommandResult a =
      test::run_captured(afemp + " run \"" + path + "\" --threads 1 -o \"" + one + "\"", dir);
  ASSERT_EQ(a.exit_code, 0) << a.out << a.err;
  const test::CommandResult dies =
      test::run_captured("AFEMP_FAULT=step:60@1 " + mpiexec(2) + "-x AFEMP_FAULT " + afemp +
                             " run \"" + path + "\" --threads 1 -o \"" + two + "\"",
                         dir);
  EXPECT_NE(dies.exit_code, 0) << dies.out << dies.err;
  EXPECT_NE((dies.out + dies.err).find("rank 1"), std::string::npos) << dies.out << dies.err;
  const core::CsvTable cut = core::read_csv(two + "/history.csv");
  ASSERT_FALSE(cut.rows.empty());
  EXPECT_LT(cut.rows.back()[cut.column("step")], 60.5);
  const std::vector<std::string> saved = afemp::list_checkpoints(two);
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_EQ(afemp::read_checkpoint_info(saved[0]).step, 34);
  const test::CommandResult again = test::run_captured(
      mpiexec(2) + afemp + " run \"" + path + "\" --threads 1 --restart \"" + two + "\"", dir);
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  expect_history_near(one + "/history.csv", two + "/history.csv", 1e-10);
}
#endif

// Reference: `afemp check` prints the wall time estimate at the nominal 1.5e6 point-steps per
// thread and second, and warns of a run of days: 512 particles (a 4-cell cube at 2 per cell per
// direction) at dt = 5.1226e-5 ms to t = 40,000 ms make 7.8e8 steps, 4.0e11 point-steps, 3.1 days
// on one thread (the step count itself, under 1e9, is not warned of).
TEST(Cli, CheckEstimatesTheWallTimeAndWarnsOfARunOfDays) {
  test::ScratchDir dir;
  const std::string path = dir.write("days.toml",
                                     "[run]\nend_time = 40000\n"
                                     "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
                                     "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
                                     "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\n"
                                     "particles_per_cell = 2\n"
                                     "shape = { box = { min = [0, 0, 0], max = [4, 4, 4] } }\n");
  const test::CommandResult r = test::run_afemp("check \"" + path + "\" --threads 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wall time estimate: about 3.1 days on 1 thread(s)"), std::string::npos)
      << r.out;
  EXPECT_NE(r.err.find("afemp: warning: the run is estimated to take 3.1 days"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("steps to end_time"), std::string::npos) << r.err;
}

// Reference: SIGINT during `afemp run` ends it cleanly after the step it is in: exit code 130
// (128 + SIGINT), a message naming the signal, the step and the output directory, the summary,
// a history whose last row is a time before the end (the final row written at the stop), with
// the first frame and the final one in the XDMF, and a checkpoint at the step it stopped after
// with the command that continues the run (docs/restart.md). SIGUSR1 before it wrote another
// checkpoint without stopping the run. The scene (a free cube translating, a
// billion steps nominal) cannot end by itself within the test.
TEST(Cli, SigintStopsTheRunCleanlyWithItsFinalRowFrameAndSummary) {
  test::ScratchDir dir;
  const std::string path = dir.write("long.toml",
                                     "[run]\nend_time = 1e6\nhistory_every = 100\n"
                                     "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
                                     "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
                                     "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\n"
                                     "particles_per_cell = 2\nvelocity = [0, 0, 0]\n"
                                     "shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }\n");
  const std::string out = dir.file("out");
  // Started in the background by the shell, interrupted after a second, waited for.
  std::string line = "\"";
  line += AFEMP_BINARY;
  line += "\" run \"";
  line += path;
  line += "\" -o \"";
  line += out;
  line +=
      "\" --threads 1 & pid=$!; sleep 1; kill -USR1 $pid; sleep 0.5; kill -INT $pid; "
      "wait $pid";
  const test::CommandResult r = test::run_shell(line, dir);
  EXPECT_EQ(r.exit_code, 130) << r.out << r.err;
  EXPECT_NE(r.err.find("afemp: stopped by SIGINT after step"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("summary"), std::string::npos) << r.out;
  const core::CsvTable h = core::read_csv(out + "/history.csv");
  ASSERT_GE(h.rows.size(), 2u);
  EXPECT_GT(h.rows.back()[h.column("time")], 0.0);
  EXPECT_LT(h.rows.back()[h.column("time")], 1e6);
  const std::string xmf = test::slurp(out + "/fields.xmf");
  std::size_t frames = 0;
  for (auto p = xmf.find("<Time "); p != std::string::npos; p = xmf.find("<Time ", p + 1)) ++frames;
  EXPECT_EQ(frames, 2u) << xmf.substr(0, 400);
  // Two checkpoints: SIGUSR1's, and the stop's at the last step of the history.
  std::vector<std::string> checkpoints;
  for (const auto& f : std::filesystem::directory_iterator(out + "/checkpoints"))
    checkpoints.push_back(f.path().filename().string());
  std::sort(checkpoints.begin(), checkpoints.end());
  ASSERT_EQ(checkpoints.size(), 2u);
  char last[40];
  std::snprintf(last, sizeof last, "step_%012ld.h5",
                static_cast<long>(h.rows.back()[h.column("step")]));
  EXPECT_EQ(checkpoints[1], last);
  EXPECT_NE(r.err.find("continue with: afemp run " + path + " --restart " + out), std::string::npos)
      << r.err;
}

// [reference] in a scene: a free rigid translation keeps its mean velocity (3, -4, 12) m/s
// exactly (|v| = 13) and its energy, so `afemp run` reports velocity errors of 0 and exits 0;
// a reference of 13.5 m/s is 3.7 % off, outside a 1 % tolerance, and the run exits 4 (a check
// the results miss) with the line saying so.
TEST(Cli, RunComparesTheSceneReferencesAndExitsFourWhenOneIsMissed) {
  test::ScratchDir dir;
  const std::string scene =
      "[run]\nend_time = 1.0\nmax_steps = 10\n"
      "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
      "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\nvelocity = [3, -4, 12]\n"
      "shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }\n"
      "[reference]\nenergy = { tolerance = 1e-6 }\nvelocity = [{ body = \"cube\", component = "
      "\"z\", "
      "value = 12, tolerance = 1e-9 }, { body = \"cube\", value = SPEED, tolerance = 0.01 }]\n";
  auto with_speed = [&](const char* speed) {
    std::string s = scene;
    s.replace(s.find("SPEED"), 5, speed);
    return s;
  };
  const test::CommandResult ok = test::run_afemp("run \"" + dir.write("ok.toml", with_speed("13")) +
                                                     "\" -o \"" + dir.file("ok") + "\" --threads 1",
                                                 dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.out << ok.err;
  EXPECT_NE(ok.out.find("velocity of cube (z): 12 (ref 12, error 0.0000)  (within tolerance)"),
            std::string::npos)
      << ok.out;
  EXPECT_NE(ok.out.find("velocity of cube (magnitude): 13 (ref 13, error 0.0000)"),
            std::string::npos)
      << ok.out;
  EXPECT_NE(ok.out.find("largest |energy-balance error|"), std::string::npos) << ok.out;
  const test::CommandResult missed =
      test::run_afemp("run \"" + dir.write("missed.toml", with_speed("13.5")) + "\" -o \"" +
                          dir.file("missed") + "\" --threads 1",
                      dir);
  EXPECT_EQ(missed.exit_code, 4) << missed.out << missed.err;
  EXPECT_NE(missed.out.find("(ref 13.5, error 0.0370)  (OUTSIDE tolerance)"), std::string::npos)
      << missed.out;
  // A reference to a body the scene does not have names the key and the bodies.
  std::string bad = with_speed("13");
  bad.replace(bad.find("body = \"cube\", value"), 13, "body = \"cub\"");
  const test::CommandResult r =
      test::run_afemp("check \"" + dir.write("bad.toml", bad) + "\"", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("reference.velocity[1].body"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown body \"cub\"; bodies: \"cube\""), std::string::npos) << r.err;
}

// `afemp study`: the study file's runs go through the same checks as `afemp run`'s scenes and
// land in the CSV; a run whose metric misses its tolerance makes the command exit 4.
TEST(Cli, StudyWritesItsTableAndExitsFourWhenARunMissesItsTolerance) {
  test::ScratchDir dir;
  dir.write("cube.toml",
            "[run]\nend_time = 1.0\nmax_steps = 10\n"
            "[grid]\ncell = 1.0\nmin = [-4, -4, -4]\nmax = [8, 8, 8]\n"
            "[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
            "[[bodies]]\nname = \"cube\"\nmaterial = \"steel\"\nvelocity = [3, -4, 12]\n"
            "shape = { box = { min = [0, 0, 0], max = [2, 2, 2] } }\n");
  const std::string study =
      "[study]\nthreads = 1\n[[metrics]]\nkind = \"velocity\"\nbody = \"cube\"\nreference = 13\n"
      "tolerance = 0.01\n[[runs]]\nmethod = \"MPM\"\nscene = \"cube.toml\"\nresolution = [1.0, "
      "0.5]\n"
      "set = { \"grid.cell\" = [1.0, 0.5], \"bodies.cube.velocity\" = [[3, -4, 12], [3, -4, 12.5]] "
      "}\n";
  const test::CommandResult r = test::run_afemp(
      "study \"" + dir.write("study.toml", study) + "\" -o \"" + dir.file("out") + "\"", dir);
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  // The CSV holds text columns (method, label, status): checked as text. Row 1: |v| = 13 to
  // round-off; row 2: |(3, -4, 12.5)| = 13.4629, 3.6 % from 13.
  std::ifstream in(dir.file("out/study.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[0].find(",velocity,velocity.error,velocity.reference,status"), std::string::npos)
      << lines[0];
  // The value before the error (round-off), then the reference and the status.
  const std::size_t reference = lines[1].rfind(",13,ok");
  ASSERT_EQ(reference, lines[1].size() - 6) << lines[1];
  EXPECT_NE(lines[1].rfind(",13,", reference - 1), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(",13.4629,"), std::string::npos) << lines[2];
  EXPECT_NE(lines[2].find(",13,over tolerance: velocity"), std::string::npos) << lines[2];
  EXPECT_NE(r.out.find("[2/2] MPM, resolution 0.5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("over tolerance: velocity"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace afemp::mpm
