// Checkpoints and restart (core/checkpoint.hpp, docs/restart.md). Reference: determinism. A
// run stopped and continued from its checkpoint must end exactly as the uninterrupted run at
// the same thread count: every dataset of every frame equal bit for bit, and the history,
// probe, erosion and conversion files equal byte for byte (every row once, none missing). The
// scene has everything that carries state from step to step: particles, hexahedra (with
// hourglass forces), trusses bonded into the particles (HFEMP), grid contact between the
// projectile and the slab (CFEMP), hexahedra converting into particles (AFEMP) and trusses
// eroding, on both sides of the stop. A run killed (SIGKILL) inside a checkpoint's write or a
// frame's write, or stopped by a full disk, restarts from the last complete checkpoint and
// still ends exactly as the uninterrupted run.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "analysis/reference_checks.hpp"
#include "core/checkpoint.hpp"
#include "core/output/field_writer.hpp"
#include "core/output/history.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "core/state_archive.hpp"
#include "core/time_loop.hpp"
#include "coupling/make_model.hpp"
#include "elastic_bar_scene.hpp"
#include "mpm/mpm_model.hpp"
#include "mpm/test_support.hpp"

namespace afemp::coupling {
namespace {

namespace fs = std::filesystem;
namespace test = mpm::test;

// A small reinforced plate struck by a steel cylinder at 1 km/s: 8192 particles, 112 bonded
// trusses that erode at 0.4 % plastic strain (the first at t = 0.0056), 390 hexahedra that
// convert at 20 % (from t = 0.004 on); 216 steps to t = 0.03.
std::string mixed_scene(const std::string& run_extra = "", const char* yield = "800") {
  return std::string(R"([run]
end_time = 0.03
output_every = 0.005
history_every = 5
)") + run_extra +
         R"(
[grid]
cell = 4.0
min = [-40, -40, -24]
max = [40, 40, 60]

[mpm]
scheme = "MUSL"

[materials.plate]
density = 2.7e-3
E = 70e3
nu = 0.3
strength = { model = "j2", yield = 300 }

[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "j2", yield = )" +
         yield + R"(, tangent_modulus = 2000 }

[[bodies]]
name = "slab"
material = "plate"
shape = { box = { min = [-32, -32, 0], max = [32, 32, 16] } }
particles_per_cell = 2

[[bodies]]
name = "rebar"
discretisation = "trusses"
material = "steel"
shape = { rebar = { min = [-32, -32, 0], max = [32, 32, 16], normal = "z", position = [8], spacing = 16, diameter = 3, cover = 4 } }
mesh = { size = 4 }
bonded_to = "slab"
erosion = { plastic_strain = 0.004 }

[[bodies]]
name = "projectile"
discretisation = "hexahedra"
material = "steel"
shape = { cylinder = { base = [0, 0, 30], axis = [0, 0, -1], radius = 6, length = 12 } }
mesh = { size = 2 }
conversion = { plastic_strain = 0.2 }
velocity = [0, 0, -1000]

[[contact]]
bodies = ["projectile", "slab"]

[[probes]]
name = "tip"
node = { body = "projectile", near = [0, 0, 18] }

[[probes]]
name = "slab_centre"
particle = { body = "slab", near = [0, 0, 8] }
interval = 0.001
)";
}

// The datasets the XDMF index of a run names (fields.h5:/frame_.../...).
std::vector<std::string> indexed_datasets(const std::string& dir) {
  const std::string xmf = test::slurp(dir + "/fields.xmf");
  std::vector<std::string> out;
  const std::string key = "fields.h5:";
  for (auto p = xmf.find(key); p != std::string::npos; p = xmf.find(key, p + 1)) {
    const auto end = xmf.find('<', p);
    std::string path = xmf.substr(p + key.size(), end - p - key.size());
    while (!path.empty() && std::isspace(static_cast<unsigned char>(path.back()))) path.pop_back();
    out.push_back(path);
  }
  return out;
}

// Every frame dataset bit for bit.
void expect_same_frames(const std::string& a, const std::string& b, std::size_t at_least) {
  EXPECT_EQ(test::slurp(a + "/fields.xmf"), test::slurp(b + "/fields.xmf"));
  const std::vector<std::string> datasets = indexed_datasets(a);
  EXPECT_GT(datasets.size(), at_least);
  int differing = 0;
  for (const std::string& d : datasets) {
    const std::vector<double> x = core::read_dataset(a + "/fields.h5", d);
    const std::vector<double> y = core::read_dataset(b + "/fields.h5", d);
    const bool same =
        x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
    if (!same && ++differing <= 5) ADD_FAILURE() << d << " differs";
  }
  EXPECT_EQ(differing, 0);
}

// Every frame dataset bit for bit, and the run's text files byte for byte.
void expect_same_run(const std::string& a, const std::string& b) {
  expect_same_frames(a, b, 100);
  for (const char* f : {"history.csv", "erosion.csv", "conversion.csv", "probes/tip.csv",
                        "probes/slab_centre.csv"}) {
    ASSERT_TRUE(fs::exists(a + "/" + f)) << f;
    EXPECT_EQ(test::slurp(a + "/" + f), test::slurp(b + "/" + f)) << f;
  }
  // Every history row once: the steps increase strictly.
  const core::CsvTable h = core::read_csv(b + "/history.csv");
  for (std::size_t r = 1; r < h.rows.size(); ++r)
    ASSERT_LT(h.rows[r - 1][0], h.rows[r][0]) << "row " << r;
}

struct Threads {
  explicit Threads(int n) : before(core::thread_count()) { core::set_thread_count(n); }
  ~Threads() { core::set_thread_count(before); }
  int before;
};

core::RunSummary run_scene(const core::Scene& scene, const std::string& dir, long stop_after = 0,
                           const std::string& restart_from = "") {
  const std::unique_ptr<core::Model> model = make_model(scene);
  core::RunOptions options;
  options.output_directory = dir;
  options.restart_from = restart_from;
  long calls = 0;
  if (stop_after > 0) options.stop_requested = [&] { return ++calls > stop_after; };
  return analysis::run(*model, scene, options);
}

TEST(Restart, ARunStoppedAndRestartedEndsBitIdenticalToAnUninterruptedOne) {
  const Threads threads(2);
  test::ScratchDir dir;
  const core::Scene scene = core::parse_scene(mixed_scene(), "mixed.toml");
  const std::string full = dir.file("full"), parts = dir.file("parts");
  const core::RunSummary whole = run_scene(scene, full);
  ASSERT_EQ(whole.steps, 216);

  // Stopped after 100 steps (t = 0.0139): a checkpoint, then the final row and frame.
  const core::RunSummary first = run_scene(scene, parts, 100);
  ASSERT_TRUE(first.interrupted);
  EXPECT_EQ(first.steps, 100);
  ASSERT_FALSE(first.checkpoint.empty()) << first.checkpoint_error;
  EXPECT_EQ(first.checkpoint, core::checkpoint_path(parts, 100));
  // Erosion and conversion happened before the stop and happen after it.
  for (const char* file : {"/erosion.csv", "/conversion.csv"}) {
    // The first column is the time; rows are in time order.
    std::istringstream rows(test::slurp(full + file));
    std::string line;
    std::vector<double> times;
    std::getline(rows, line);  // the header
    while (std::getline(rows, line)) times.push_back(std::stod(line.substr(0, line.find(','))));
    ASSERT_FALSE(times.empty()) << file;
    EXPECT_LT(times.front(), first.time) << file;
    EXPECT_GT(times.back(), first.time) << file;
  }

  const core::RunSummary second = run_scene(scene, parts, 0, core::newest_checkpoint(parts));
  EXPECT_FALSE(second.interrupted);
  EXPECT_EQ(second.restarted_at, 100);
  EXPECT_EQ(second.steps, whole.steps);
  EXPECT_EQ(second.field_frames, whole.field_frames);
  EXPECT_EQ(second.final.kinetic, whole.final.kinetic);
  EXPECT_EQ(second.final.eroded, whole.final.eroded);
  EXPECT_EQ(second.final.converted, whole.final.converted);
  EXPECT_EQ(second.max_energy_error, whole.max_energy_error);
  ASSERT_EQ(second.probes.size(), whole.probes.size());
  for (std::size_t k = 0; k < whole.probes.size(); ++k)
    EXPECT_EQ(second.probes[k].time.size(), whole.probes[k].time.size()) << whole.probes[k].name;
  expect_same_run(full, parts);
}

// The elastic copper bar on a wall face with the [mpm] settings `method`, stopped after 40 of
// 80 steps and restarted: every frame bit for bit, and the same final kinetic energy.
void expect_restart_bit_identical(const std::string& method, const std::string& name) {
  const Threads threads(2);
  test::ScratchDir dir;
  // The V1 bar, to 12 us at a fixed step (80 steps).
  std::string text = "[mpm]\nscheme = \"MUSL\"\n" + method + ::afemp::test::elastic_bar_scene;
  // The total-Lagrangian form takes no wall face (a place in space): the bar starts clamped.
  if (method.find("total-lagrangian") != std::string::npos)
    text.replace(text.find("zmin = \"wall\""), 13, "zmin = \"fixed\"");
  // The mixed pressure replaces a hyperelastic solid's K (J - 1).
  if (method.find("mixed") != std::string::npos)
    text.replace(text.find("nu = 0.3\n"), 9, "nu = 0.3\nstrength = { model = \"neo-hookean\" }\n");
  const std::string end = "end_time = 0.02\n";
  ASSERT_NE(text.find(end), std::string::npos);
  text.replace(text.find(end), end.size(),
               "end_time = 0.012\noutput_every = 0.004\ntime_step = 1.5e-4\n");
  const core::Scene scene = core::parse_scene(text, name);
  const std::string full = dir.file("full"), parts = dir.file("parts");
  const core::RunSummary whole = run_scene(scene, full);
  ASSERT_EQ(whole.steps, 80);
  const core::RunSummary first = run_scene(scene, parts, 40);
  ASSERT_TRUE(first.interrupted);
  ASSERT_FALSE(first.checkpoint.empty()) << first.checkpoint_error;
  const core::RunSummary second = run_scene(scene, parts, 0, core::newest_checkpoint(parts));
  EXPECT_EQ(second.restarted_at, 40);
  EXPECT_EQ(second.steps, whole.steps);
  EXPECT_EQ(second.final.kinetic, whole.final.kinetic);
  expect_same_frames(full, parts, 10);
}

// The cubic B-spline with the affine transfer: the particles' affine velocities and the half
// widths its kinetic energy reads come back with the rest; the bar strikes the spline's
// modified face cells.
TEST(Restart, ACubicBsplineApicRunRestartsBitIdentical) {
  expect_restart_bit_identical("shape_function = \"bspline3\"\ntransfer = \"apic\"\n",
                               "bspline.toml");
}

// The total-Lagrangian form: the reference positions and deformation gradients come back with
// the rest.
TEST(Restart, TotalLagrangianRunRestartsBitIdentical) {
  expect_restart_bit_identical(
      "formulation = \"total-lagrangian\"\nshape_function = \"bspline2\"\n", "tl.toml");
}

// The mixed displacement-pressure form: its pressure is projected afresh each step from F, so
// nothing beyond the total-Lagrangian state is saved, and the restart is still exact.
TEST(Restart, AMixedPressureRunRestartsBitIdentical) {
  expect_restart_bit_identical(
      "formulation = \"total-lagrangian\"\nshape_function = \"bspline2\"\npressure = \"mixed\"\n",
      "mixed.toml");
}

// CPDI: the parallelepipeds' edge vectors and the tracked corners come back with the rest.
TEST(Restart, CpdiRunsRestartBitIdentical) {
  expect_restart_bit_identical("shape_function = \"cpdi1\"\n", "cpdi1.toml");
  expect_restart_bit_identical("shape_function = \"cpdi2\"\n", "cpdi2.toml");
}

// A TNT column stopped half burnt (step 100, t = 0.0019 ms, the front at about 13 mm of 30) and
// restarted: the burn fractions and lighting times come back with the rest, and the run ends
// with the uninterrupted run's particles bit for bit (positions, stresses, energies, burn).
TEST(Restart, ADetonationStoppedHalfBurntEndsBitIdentical) {
  test::ScratchDir dir;
  const core::Scene scene = core::parse_scene(R"([run]
end_time = 0.004
[grid]
cell = 0.5
min = [0, 0, -2]
max = [1, 1, 40]
boundary = { xmin = "symmetric", xmax = "symmetric", ymin = "symmetric", ymax = "symmetric", zmin = "outflow", zmax = "outflow" }
[materials.tnt]
density = 1.63e-3
strength = { model = "fluid" }
eos = { model = "jwl", A = 3.712e5, B = 3.231e3, R1 = 4.15, R2 = 0.95, omega = 0.30, E0 = 7.0e3 }
burn = { D = 6930, pcj = 2.1e4 }
[[bodies]]
name = "charge"
material = "tnt"
shape = { box = { min = [0, 0, 0], max = [1, 1, 30] } }
[[detonations]]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
)",
                                              "column.toml");
  const auto final_particles = [&](const std::string& out, long stop_after,
                                   const std::string& restart) {
    const std::unique_ptr<core::Model> model = make_model(scene);
    core::RunOptions options;
    options.output_directory = out;
    options.write_fields = false;
    options.restart_from = restart;
    long calls = 0;
    if (stop_after > 0) options.stop_requested = [&] { return ++calls > stop_after; };
    analysis::run(*model, scene, options);
    return dynamic_cast<const mpm::MpmModel&>(*model).solver().particles();
  };
  const mpm::Particles whole = final_particles(dir.file("whole"), 0, "");
  // At the stop the column is partly burnt: some particles unlit, some burning, some done.
  const mpm::Particles at_stop = final_particles(dir.file("parts"), 100, "");
  int unlit = 0, burning = 0;
  for (double f : at_stop.burn) {
    unlit += f == 0.0;
    burning += f > 0.0 && f < 1.0;
  }
  EXPECT_GT(unlit, 0);
  EXPECT_GT(burning, 0);
  const mpm::Particles parts =
      final_particles(dir.file("parts"), 0, core::newest_checkpoint(dir.file("parts")));
  ASSERT_FALSE(whole.burn.empty());
  ASSERT_EQ(whole.size(), parts.size());
  const auto same = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
  };
  EXPECT_TRUE(same(whole.position, parts.position));
  EXPECT_TRUE(same(whole.stress, parts.stress));
  EXPECT_TRUE(same(whole.energy, parts.energy));
  EXPECT_TRUE(same(whole.burn, parts.burn));
  EXPECT_TRUE(same(whole.light_time, parts.light_time));
  EXPECT_EQ(test::slurp(dir.file("whole") + "/history.csv"),
            test::slurp(dir.file("parts") + "/history.csv"));
}

// Reference: docs/restart.md. Physics may not change between the runs; the end time may.
TEST(Restart, ASceneEditedBetweenTheRunsIsRefusedWithTheKeysThatDiffer) {
  test::ScratchDir dir;
  const std::string out = dir.file("out");
  const core::Scene scene = core::parse_scene(mixed_scene(), dir.file("mixed.toml"));
  ASSERT_TRUE(run_scene(scene, out, 40).interrupted);
  const std::string checkpoint = core::newest_checkpoint(out);
  const std::string history_before = test::slurp(out + "/history.csv");

  const core::Scene edited = core::parse_scene(mixed_scene("", "850"), dir.file("mixed.toml"));
  const std::vector<std::string> changes =
      core::scene_changes(core::read_checkpoint_header(checkpoint), edited);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0], "materials.steel.strength.yield: 800 in the checkpoint, 850 now (" +
                            dir.file("mixed.toml") + " line 24)");
  try {
    run_scene(edited, out, 0, checkpoint);
    ADD_FAILURE() << "the edited scene was taken";
  } catch (const core::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("restart refused"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("materials.steel.strength.yield"), std::string::npos);
  }
  EXPECT_EQ(test::slurp(out + "/history.csv"), history_before)
      << "a refused restart writes nothing";

  // Another end time (and other output settings) is allowed; the run goes on to it.
  const core::Scene other_end =
      core::parse_scene(std::string(mixed_scene())
                            .replace(mixed_scene().find("end_time = 0.03"), 15, "end_time = 0.02"),
                        dir.file("mixed.toml"));
  EXPECT_TRUE(core::scene_changes(core::read_checkpoint_header(checkpoint), other_end).empty());
  const core::RunSummary s = run_scene(other_end, out, 0, checkpoint);
  EXPECT_NEAR(s.time, 0.02, 1e-12);
}

// Reference: the previous checkpoint is untouched when a checkpoint cannot be written (here
// its temporary file's name is taken by a directory).
TEST(Restart, ACheckpointThatCannotBeWrittenLeavesThePreviousOne) {
  test::ScratchDir dir;
  const std::string out = dir.file("out");
  const core::Scene scene = core::parse_scene(mixed_scene(), "mixed.toml");
  const std::unique_ptr<core::Model> model = make_model(scene);
  core::RunOptions options;
  options.output_directory = out;
  core::TimeLoop loop(*model, scene, options);
  for (int k = 0; k < 10; ++k) loop.step(scene.run.end_time);
  const std::string first = loop.checkpoint("test");
  const std::string first_bytes = test::slurp(first);
  for (int k = 0; k < 10; ++k) loop.step(scene.run.end_time);
  fs::create_directories(core::checkpoint_path(out, 20) + ".tmp/blocked");
  try {
    loop.checkpoint("test");
    ADD_FAILURE() << "the checkpoint was written";
  } catch (const core::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("step_000000000020.h5.tmp"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("the previous checkpoints are kept"), std::string::npos);
  }
  EXPECT_EQ(core::list_checkpoints(out), std::vector<std::string>{first});
  EXPECT_EQ(test::slurp(first), first_bytes);
  EXPECT_EQ(core::read_checkpoint_header(first).step, 10);
}

// The command line: a run with checkpoints every 0.012 (at steps 87 and 173) and frames every
// 0.005, killed or stopped as named, then `afemp run SCENE --restart DIR`, compared with the
// uninterrupted run.
class RestartCli : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = dir_.write("mixed.toml", mixed_scene("checkpoint_every = 0.012\n"));
    full_ = dir_.file("full");
    const test::CommandResult r = afemp("run \"" + scene_ + "\" -o \"" + full_ + "\"");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  test::CommandResult afemp(const std::string& args, const std::string& env = "") {
    return test::run_shell(env + " \"" + std::string(AFEMP_BINARY) + "\" " + args + " --threads 1",
                           dir_);
  }
  test::ScratchDir dir_;
  std::string scene_, full_;
};

TEST_F(RestartCli, KilledWhileWritingACheckpointItRestartsFromThePreviousOne) {
  const std::string out = dir_.file("killed");
  const test::CommandResult killed =
      afemp("run \"" + scene_ + "\" -o \"" + out + "\"", "AFEMP_FAULT=checkpoint:2");
  EXPECT_EQ(killed.exit_code, 128 + 9) << "SIGKILL: " << killed.err;
  EXPECT_EQ(core::list_checkpoints(out), std::vector<std::string>{core::checkpoint_path(out, 87)});
  const auto half_written = [&] {
    int n = 0;
    for (const auto& f : fs::directory_iterator(core::checkpoint_directory(out)))
      n += f.path().extension() == ".tmp";
    return n;
  };
  EXPECT_EQ(half_written(), 1) << "killed mid-write";
  const test::CommandResult again = afemp("run \"" + scene_ + "\" --restart \"" + out + "\"");
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("continuing from " + core::checkpoint_path(out, 87)), std::string::npos)
      << again.out;
  EXPECT_EQ(half_written(), 0) << "the restart removes it";
  expect_same_run(full_, out);
}

TEST_F(RestartCli, KilledWhileWritingAFrameEveryEarlierFrameLoadsAndTheRestartEndsTheSame) {
  const std::string out = dir_.file("killed");
  // The fifth frame (t = 0.02) is being written: frames 0-3 are complete, the checkpoint at
  // step 87 (t = 0.012) is the newest.
  const test::CommandResult killed =
      afemp("run \"" + scene_ + "\" -o \"" + out + "\"", "AFEMP_FAULT=frame:5");
  EXPECT_EQ(killed.exit_code, 128 + 9) << killed.err;
  const std::vector<std::string> listed = indexed_datasets(out);
  std::set<std::string> frames;
  for (const std::string& d : listed) {
    frames.insert(d.substr(0, d.find('/', 1)));
    EXPECT_NO_THROW(core::read_dataset(out + "/fields.h5", d)) << d;
  }
  EXPECT_EQ(frames.size(), 4u);
  EXPECT_EQ(core::newest_checkpoint(out), core::checkpoint_path(out, 87));
  const test::CommandResult again = afemp("run \"" + scene_ + "\" --restart \"" + out + "\"");
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("continuing from " + core::checkpoint_path(out, 87)), std::string::npos)
      << again.out;
  expect_same_run(full_, out);
}

// A full disk, made by a file-size limit (ulimit -f, in the 512-byte blocks of POSIX sh; SIGXFSZ
// ignored as a full disk sends none): fields.h5 cannot grow past 6.1 MB, which the fourth
// frame (t = 0.015) needs, after the checkpoint at step 87. The run stops with exit code 5 naming
// the file and the reason, keeps the checkpoint, and the restart with room again ends as the full
// run.
TEST_F(RestartCli, AFullDiskStopsTheRunWithAClearMessageAndTheCheckpointStaysUsable) {
  const std::string out = dir_.file("full_disk");
  const test::CommandResult stopped =
      test::run_captured("trap '' XFSZ; ulimit -f 12000; \"" + std::string(AFEMP_BINARY) +
                             "\" run \"" + scene_ + "\" -o \"" + out + "\" --threads 1",
                         dir_);
  EXPECT_EQ(stopped.exit_code, 5) << stopped.out << stopped.err;
  EXPECT_NE(stopped.err.find("afemp: run stopped: "), std::string::npos) << stopped.err;
  // The file and the system's reason (the fourth frame fails in a dataset's write or in the
  // flush, depending on the frame's size).
  EXPECT_NE(stopped.err.find("fields.h5"), std::string::npos) << stopped.err;
  EXPECT_NE(stopped.err.find(": File too large"), std::string::npos) << stopped.err;
  EXPECT_NE(stopped.err.find("the newest checkpoint is " + core::checkpoint_path(out, 87)),
            std::string::npos)
      << stopped.err;
  const test::CommandResult again = afemp("run \"" + scene_ + "\" --restart \"" + out + "\"");
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("continuing from " + core::checkpoint_path(out, 87)), std::string::npos)
      << again.out;
  expect_same_run(full_, out);
}

// A disk that is really full: an 11 MiB tmpfs mounted in a user and mount namespace of its
// own (unshare; skipped where the system allows no such namespace). Five frames (7.9 MB) and the
// first checkpoint (2.0 MB) fit; the second checkpoint does not. The run stops with exit code 5,
// "No space left on device", the free space, and the first checkpoint, which is kept whole; the
// run directory, copied out of the tmpfs, restarts and ends as the uninterrupted run.
TEST_F(RestartCli, ADiskThatFillsUpDuringACheckpointKeepsThePreviousOne) {
  const std::string mount = dir_.file("tmpfs"), copy = dir_.file("copied");
  fs::create_directories(mount);
  const test::CommandResult probe = test::run_captured(
      "unshare --user --map-root-user --mount sh -c 'mount -t tmpfs -o size=11m tmpfs \"" + mount +
          "\"' 2>&1",
      dir_);
  if (probe.exit_code != 0)
    GTEST_SKIP() << "no user and mount namespace for a tmpfs here: " << probe.out << probe.err;
  const test::CommandResult stopped = test::run_captured(
      "unshare --user --map-root-user --mount sh -c 'mount -t tmpfs -o size=11m tmpfs \"" + mount +
          "\" && \"" + std::string(AFEMP_BINARY) + "\" run \"" + scene_ + "\" -o \"" + mount +
          "/run\" --threads 1; code=$?; cp -r \"" + mount + "/run\" \"" + copy + "\"; exit $code'",
      dir_);
  EXPECT_EQ(stopped.exit_code, 5) << stopped.out << stopped.err;
  EXPECT_NE(stopped.err.find("checkpoints/step_000000000173.h5.tmp: "), std::string::npos)
      << stopped.err;
  EXPECT_NE(stopped.err.find("No space left on device (the disk holding " + mount + "/run has "),
            std::string::npos)
      << stopped.err;
  EXPECT_NE(stopped.err.find("bytes free: it is full); the previous checkpoints are kept"),
            std::string::npos)
      << stopped.err;
  EXPECT_EQ(core::list_checkpoints(copy),
            std::vector<std::string>{core::checkpoint_path(copy, 87)});
  const test::CommandResult again = afemp("run \"" + scene_ + "\" --restart \"" + copy + "\"");
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("continuing from " + core::checkpoint_path(copy, 87)), std::string::npos)
      << again.out;
  expect_same_run(full_, copy);
}

}  // namespace
}  // namespace afemp::coupling
