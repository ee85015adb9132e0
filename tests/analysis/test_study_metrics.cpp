// The study metrics read from probes and from a target's points (docs/study-format.md):
//  - wave_front and frequency on the fixed-free elastic bar of hexahedra (nu = 0): the front
//    runs at c = sqrt(E / rho) (5047.5 m/s) and the first axial frequency is c / (4 L); the
//    study's values and errors against those references within 2 %;
//  - crater and hole on targets of particles made from point lists with a spherical-cap crater
//    (depth 1.5, rim radius 3) and a round hole (radius 2) cut into them, at rest for a few
//    steps: the metrics give the cut geometry within one particle spacing;
//  - force on a steel cube squeezed in a static phase on a frictionless wall: the wall's force
//    is the uniaxial-stress closed form at small strain to 1e-9, for squeezes and load steps
//    set by index ("constraints.2.velocity", "phases.0.load_steps");
//  - a band's error is 0 inside it and the distance to the nearer bound relative to that bound
//    outside; each run is measured against its own reference where its [[runs]] table gives
//    one, the CSV says which, and the value plot draws the references beside the runs;
//  - the mistakes a study file can make with them name the file, line, key and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "analysis/study.hpp"
#include "analysis/study_file.hpp"
#include "fixed_free_bar_scene.hpp"
#include "scratch_dir.hpp"

namespace afemp::analysis {
namespace {

const double c = std::sqrt(200e3 / 7.85e-3), length = 50.0;

const std::string bar_scene = test::fixed_free_bar_scene() + R"(
[[probes]]
name = "z10"
node = { body = "bar", near = [1, 1, 10] }
[[probes]]
name = "z25"
node = { body = "bar", near = [1, 1, 25] }
[[probes]]
name = "z40"
node = { body = "bar", near = [1, 1, 40] }
[[probes]]
name = "tip"
node = { body = "bar", near = [1, 1, 50] }
[[probes]]
name = "bar_v"
mean_velocity = "bar"
)";

// The front's first passage: the histories up to 55 mm of travel, before the reflection
// from the free end reaches z = 40.
const std::string bar_study = R"(
[study]
title = "Fixed-free bar"
threads = 1
plot = "front"

[[metrics]]
kind = "wave_front"
name = "front"
probes = ["z10", "z25", "z40"]
quantity = "vz"
until = 0.0109
reference = 5047.54
tolerance = 0.02

[[metrics]]
kind = "frequency"
name = "axial"
probe = "tip"
quantity = "vz"
reference = 25.2377
tolerance = 0.02

[[runs]]
method = "FE"
scene = "bar.toml"
)";

std::string study_error(const std::string& study, const std::string& scene = bar_scene) {
  test::ScratchDir dir;
  dir.write("bar.toml", scene);
  try {
    analysis::read_study(dir.write("study.toml", study));
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << study;
  return "";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(StudyMetrics, WaveFrontAndFrequencyOfTheFixedFreeBar) {
  test::ScratchDir dir;
  dir.write("bar.toml", bar_scene);
  const analysis::StudyPlan plan = analysis::read_study(dir.write("study.toml", bar_study));
  const StudyResult result = run_study(plan);
  ASSERT_EQ(result.value_columns, (std::vector<std::string>{"front", "axial"}));
  ASSERT_EQ(result.error_columns, (std::vector<std::string>{"front.error", "axial.error"}));
  const StudyRow& row = result.rows.at(0);
  std::printf("front %.1f m/s (c %.1f, error %.4f), axial %.3f /ms (c / 4L %.3f, error %.4f)\n",
              row.values[0], c, row.errors[0], row.values[1], c / (4 * length), row.errors[1]);
  EXPECT_TRUE(row.ok()) << describe_row(result, row);
  EXPECT_NEAR(row.values[0], c, 0.02 * c);
  EXPECT_NEAR(row.values[1], c / (4.0 * length), 0.02 * c / (4.0 * length));
  EXPECT_DOUBLE_EQ(row.errors[0], std::abs(row.values[0] - 5047.54) / 5047.54);
  EXPECT_DOUBLE_EQ(row.errors[1], std::abs(row.values[1] - 25.2377) / 25.2377);
  // The whole history: the reflection doubles the change at z = 40 before it does at z = 10,
  // so the half-peak arrival there is the first front's top and the speed reads low.
  test::ScratchDir dir2;
  dir2.write("bar.toml", bar_scene);
  const analysis::StudyPlan whole =
      analysis::read_study(dir2.write("study.toml", replaced(bar_study, "until = 0.0109\n", "")));
  const StudyResult whole_result = run_study(whole);
  const StudyRow& w = whole_result.rows.at(0);
  std::printf("front without until: %.1f m/s\n", w.values[0]);
  EXPECT_GT(w.errors[0], 0.05);
  EXPECT_FALSE(w.ok());
}

// Lattice points (spacing d, volume d^3) of a plate [-5, 5]^2 x [-2, 0] about (cx, 0, 0),
// less those inside `cut`.
template <class Cut>
std::string plate_points(double cx, double d, Cut cut) {
  std::ostringstream os;
  for (double x = -5 + d / 2; x < 5; x += d)
    for (double y = -5 + d / 2; y < 5; y += d)
      for (double z = -2 + d / 2; z < 0; z += d)
        if (!cut(x, y, z)) os << cx + x << ' ' << y << ' ' << z << ' ' << d * d * d << '\n';
  return os.str();
}

constexpr double d = 0.25, depth = 1.5, rim = 3.0, hole = 2.0;

// targets.toml: a block with the crater cut (body "block", about the z axis) and a plate with
// the hole cut (body "plate", about x = 20), at rest for three steps.
void write_cut_targets(test::ScratchDir& dir) {
  const double sphere = (rim * rim + depth * depth) / (2 * depth);
  // The crater: points above the sphere through the rim circle and (0, 0, -depth) are cut.
  dir.write("crater.xyz", plate_points(0.0, d, [&](double x, double y, double z) {
              return std::hypot(x, y, z - (sphere - depth)) < sphere;
            }));
  dir.write("hole.xyz", plate_points(20.0, d, [&](double x, double y, double) {
              return std::hypot(x, y) < hole;
            }));
  dir.write("targets.toml", R"(
[run]
end_time = 1
max_steps = 3
[grid]
cell = 0.5
min = [-6, -6, -3]
max = [26, 6, 1]
[materials.al]
density = 2.7e-3
E = 70e3
nu = 0.3
[[bodies]]
name = "block"
material = "al"
shape = { points = { file = "crater.xyz" } }
[[bodies]]
name = "plate"
material = "al"
shape = { points = { file = "hole.xyz" } }
)");
}

TEST(StudyMetrics, CraterAndHoleOfCutTargets) {
  test::ScratchDir dir;
  write_cut_targets(dir);
  const analysis::StudyPlan plan = analysis::read_study(dir.write("study.toml", R"(
[study]
threads = 1
[[metrics]]
kind = "crater"
body = "block"
point = [0, 0, 0]
normal = [0, 0, 1]
ring = 0.25
threshold = 0.1
reference = { depth = 1.5, diameter = 6.0 }
tolerance = 0.1
[[metrics]]
kind = "hole"
body = "plate"
point = [20, 0, -1]
normal = [0, 0, 1]
band = 0.5
reference = 4.0
tolerance = 0.1
[[runs]]
method = "MPM"
scene = "targets.toml"
)"));
  const StudyResult result = run_study(plan);
  ASSERT_EQ(result.value_columns,
            (std::vector<std::string>{"crater.depth", "crater.diameter", "hole"}));
  ASSERT_EQ(result.error_columns, (std::vector<std::string>{"crater.error", "hole.error"}));
  const StudyRow& row = result.rows.at(0);
  std::printf(
      "crater depth %.3f (cut %.2f), diameter %.3f (cut %.2f); hole %.3f (cut %.2f); "
      "errors %.4f %.4f\n",
      row.values[0], depth, row.values[1], 2 * rim, row.values[2], 2 * hole, row.errors[0],
      row.errors[1]);
  EXPECT_EQ(row.steps, 3);
  // Particles sit half a spacing inside the material: the surface level is measured on them
  // too, so the depth is the cut's within a spacing; the diameter within a ring each side.
  EXPECT_NEAR(row.values[0], depth, d);
  EXPECT_NEAR(row.values[1], 2 * rim, 2 * d);
  // The hole: twice the nearest particle's distance, within a spacing of the cut.
  EXPECT_NEAR(row.values[2], 2 * hole, 2 * d);
  EXPECT_GE(row.values[2], 2 * hole);
  EXPECT_DOUBLE_EQ(row.errors[0], 0.5 * (std::abs(row.values[0] - 1.5) / 1.5 +
                                         std::abs(row.values[1] - 6.0) / 6.0));
  EXPECT_TRUE(row.ok()) << describe_row(result, row);
}

// A steel cube [0, 1]^3 of 2 x 2 x 2 B-bar hexahedra on a frictionless wall at z = 0, on the
// symmetry planes x = 0 and y = 0, its top pressed down by u = 1e-3 (the velocity's curve
// integrates to 1 over the static phase and is 0 after it), then 1 us of explicit phase at rest
// in which the wall reports the force.
const std::string squeezed_cube = R"(
[run]
end_time = 1.001
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
[[bodies]]
name = "cube"
discretisation = "hexahedra"
element = "full"
material = "steel"
shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }
mesh = { divisions = [2, 2, 2] }
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }
fixed = ["x"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }
fixed = ["y"]
[[constraints]]
nodes = { plane = { point = [0, 0, 1], normal = [0, 0, 1] } }
velocity = [0, 0, -1e-3]
components = ["z"]
curve = [[0, 2], [1, 0]]
[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
[[phases]]
kind = "static"
end_time = 1
[[phases]]
kind = "explicit"
[[probes]]
name = "base"
force = "wall1"
[[probes]]
name = "corner"
node = { body = "cube", near = [1, 1, 1] }
)";

// Uniaxial stress at small strain eps = u / H: sigma_zz = E eps, the free sides move out by
// nu eps, so the explicit phase reads the force sigma_zz A (1 + nu eps)^2 through the wall.
double cube_force(double u) {
  const double eps = u / 1.0;
  return 200e3 * eps * 1.0 * (1.0 + 0.3 * eps) * (1.0 + 0.3 * eps);
}

const std::string cube_study = R"(
[study]
threads = 1
[[metrics]]
kind = "force"
name = "base"
probe = "base"
quantity = "fz"
tolerance = 1e-9
[[runs]]
method = "static"
scene = "cube.toml"
resolution = [1, 4]
set = { "phases.0.load_steps" = [1, 4], "constraints.2.velocity" = [[0, 0, -1e-3], [0, 0, -2e-3]] }
reference = { base = [REF1, REF2] }
)";

std::string cube_study_text() {
  char ref[2][32];
  std::snprintf(ref[0], sizeof ref[0], "%.17g", cube_force(1e-3));
  std::snprintf(ref[1], sizeof ref[1], "%.17g", cube_force(2e-3));
  return replaced(replaced(cube_study, "REF1", ref[0]), "REF2", ref[1]);
}

TEST(StudyMetrics, ForceOfTheWallUnderACubeSqueezedInAStaticPhase) {
  test::ScratchDir dir;
  dir.write("cube.toml", squeezed_cube);
  const analysis::StudyPlan plan = analysis::read_study(dir.write("study.toml", cube_study_text()));
  const StudyResult result = run_study(plan);
  ASSERT_EQ(result.value_columns, std::vector<std::string>{"base"});
  ASSERT_EQ(result.rows.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const StudyRow& row = result.rows[k];
    const double exact = cube_force(k == 0 ? 1e-3 : 2e-3);
    std::printf("u %g: force %.12g N (closed form %.12g, error %.2e)\n", k == 0 ? 1e-3 : 2e-3,
                row.values[0], exact, row.errors[0]);
    EXPECT_TRUE(row.ok()) << describe_row(result, row);
    EXPECT_NEAR(row.values[0], exact, 1e-9 * exact);
  }
}

TEST(StudyMetrics, MistakesNameTheFileLineKeyAndWhatIsAllowed) {
  std::string e =
      study_error(replaced(bar_study, "quantity = \"vz\"\nuntil", "quantity = \"speed\"\nuntil"));
  EXPECT_NE(
      e.find("study.toml:7: key 'metrics.quantity': probe \"z10\" is a node probe; its columns "
             "are \"x\", \"y\", \"z\", \"vx\", \"vy\", \"vz\""),
      std::string::npos)
      << e;
  e = study_error(replaced(bar_study, "probe = \"tip\"", "probe = \"end\""));
  EXPECT_NE(e.find("key 'metrics.probe': metric \"axial\" reads probe \"end\", which run \"FE\""),
            std::string::npos)
      << e;
  e = study_error(
      replaced(bar_study, "probes = [\"z10\", \"z25\", \"z40\"]", "probes = [\"z10\"]"));
  EXPECT_NE(e.find("key 'metrics[0].probes': name two or more probes"), std::string::npos) << e;
  e = study_error(
      replaced(bar_study, "probes = [\"z10\", \"z25\", \"z40\"]", "probes = [\"z10\", \"bar_v\"]"));
  EXPECT_NE(e.find("probe \"bar_v\" is a mean_velocity probe"), std::string::npos) << e;
  e = study_error(replaced(bar_study, "probe = \"tip\"", "probe = \"tip\"\nband = 1"));
  EXPECT_NE(e.find("key 'metrics[1].band': applies to kind \"hole\" only, not \"frequency\""),
            std::string::npos)
      << e;
  e = study_error(replaced(bar_study, "until = 0.0109", "until = -1"));
  EXPECT_NE(e.find("key 'metrics[0].until'"), std::string::npos) << e;
  const std::string crater =
      "[study]\n[[metrics]]\nkind = \"crater\"\nbody = \"bar\"\npoint = [0, 0, 50]\n"
      "normal = [0, 0, 1]\nring = 0.5\nthreshold = 0.1\ntolerance = 0.1\n"
      "[[runs]]\nmethod = \"FE\"\nscene = \"bar.toml\"\n";
  e = study_error(crater);
  EXPECT_NE(e.find("study.toml:9: key 'metrics[0].tolerance': a tolerance needs a reference"),
            std::string::npos)
      << e;
  e = study_error(replaced(crater, "ring = 0.5\n", ""));
  EXPECT_NE(e.find("key 'metrics[0].ring': required key is missing"), std::string::npos) << e;
  e = study_error(replaced(crater, "normal = [0, 0, 1]", "normal = [0, 0, 0]"));
  EXPECT_NE(e.find("key 'metrics[0].normal': the normal must be a non-zero vector"),
            std::string::npos)
      << e;
  e = study_error(
      replaced(replaced(crater, "tolerance = 0.1\n", ""), "body = \"bar\"", "body = \"slab\""));
  EXPECT_NE(e.find("measures body \"slab\""), std::string::npos) << e;
  // A force metric reads a force probe's column; unnamed tables are picked by an index in range.
  auto cube_error = [](const std::string& from, const std::string& to) {
    return study_error(replaced(replaced(cube_study_text(), from, to), "cube.toml", "bar.toml"),
                       squeezed_cube);
  };
  e = cube_error("probe = \"base\"", "probe = \"corner\"");
  EXPECT_NE(e.find("key 'metrics.probe': a force metric reads a force probe (force = \"wall1\", "
                   "a contact's name, ...); probe \"corner\" is a node probe"),
            std::string::npos)
      << e;
  e = cube_error("quantity = \"fz\"", "quantity = \"vz\"");
  EXPECT_NE(e.find("probe \"base\" is a force probe; its columns are \"fx\", \"fy\", \"fz\""),
            std::string::npos)
      << e;
  e = cube_error("constraints.2.velocity", "constraints.3.velocity");
  EXPECT_NE(e.find("has no 'constraints' numbered 3; its tables have no names: pick one by its "
                   "index, 0 to 2"),
            std::string::npos)
      << e;
}

TEST(StudyMetrics, BandErrorIsTheDistanceToTheNearerBoundRelativeToIt) {
  const ScalarReference band{4.0, 5.0, true}, negative{-5.0, -4.0, true},
      value{300.0, 300.0, false};
  EXPECT_DOUBLE_EQ(reference_error(3.0, band), 0.25);  // (4 - 3) / 4
  EXPECT_EQ(reference_error(4.0, band), 0.0);
  EXPECT_EQ(reference_error(4.5, band), 0.0);
  EXPECT_EQ(reference_error(5.0, band), 0.0);
  EXPECT_DOUBLE_EQ(reference_error(6.0, band), 0.2);        // (6 - 5) / 5
  EXPECT_DOUBLE_EQ(reference_error(-6.0, negative), 0.2);   // (-5 - -6) / |-5|
  EXPECT_DOUBLE_EQ(reference_error(-3.0, negative), 0.25);  // (-3 - -4) / |-4|
  EXPECT_EQ(reference_error(-4.5, negative), 0.0);
  // One value: |v - v_ref| / |v_ref| either side.
  EXPECT_DOUBLE_EQ(reference_error(330.0, value), 0.1);
  EXPECT_DOUBLE_EQ(reference_error(270.0, value), 0.1);
  EXPECT_TRUE(std::isnan(reference_error(std::nan(""), band)));
}

// The hole of the cut plate, 2 sqrt(274) / 8 = 4.14 (the nearest lattice points to the axis
// outside radius 2 sit at (7, 15) / 8), measured against a band below it, one value, the
// study-wide band about it, and a band above it: the run's own reference reaches its row, and
// the crater, which has references in two runs only, is reported only in the others.
TEST(StudyMetrics, PerRunReferencesAndBandsReachTheirRowsAndTheValuePlot) {
  test::ScratchDir dir;
  write_cut_targets(dir);
  const analysis::StudyPlan plan = analysis::read_study(dir.write("study.toml", R"toml(
[study]
title = "Cut plate"
threads = 1
plot_value = "hole"
x_label = "impact speed (km/s)"
[[metrics]]
kind = "crater"
body = "block"
point = [0, 0, 0]
normal = [0, 0, 1]
ring = 0.25
threshold = 0.1
tolerance = 0.5
[[metrics]]
kind = "hole"
body = "plate"
point = [20, 0, -1]
normal = [0, 0, 1]
band = 0.5
reference = [3.5, 4.6]
tolerance = 0.1
[[runs]]
method = "MPM"
scene = "targets.toml"
resolution = [5, 7]
reference = { crater = [{ depth = 1.5, diameter = 6.0 }, { depth = 2.0, diameter = 5.0 }], hole = [[4.5, 5.0], 3.0] }
[[runs]]
method = "MPM"
scene = "targets.toml"
resolution = 6
[[runs]]
method = "MPM again"
scene = "targets.toml"
resolution = 6
reference = { hole = [3.0, 3.5] }
)toml"));
  const StudyResult result = run_study(plan);
  ASSERT_EQ(result.error_columns, (std::vector<std::string>{"crater.error", "hole.error"}));
  ASSERT_EQ(result.reference_columns,
            (std::vector<std::string>{"crater.reference_depth", "crater.reference_diameter",
                                      "hole.reference_low", "hole.reference_high"}));
  ASSERT_EQ(result.rows.size(), 4u);
  const double depth_0 = result.rows[0].values[0], diameter_0 = result.rows[0].values[1];
  const double depth_1 = result.rows[1].values[0], diameter_1 = result.rows[1].values[1];
  const double v = result.rows[0].values[2];
  std::printf("hole %.4f (lattice 2 sqrt(274) / 8 = %.4f)\n", v, std::sqrt(274.0) / 4.0);
  EXPECT_NEAR(v, std::sqrt(274.0) / 4.0, 1e-9);
  for (const StudyRow& row : result.rows) {
    EXPECT_EQ(row.values[2], v);  // the same target in every run
    EXPECT_EQ(row.values[0], depth_0);
  }
  const double nan = std::nan("");
  auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
    return true;
  };
  // Row 1: the sweep's first references; the hole below the band [4.5, 5].
  EXPECT_TRUE(same(result.rows[0].references, {1.5, 6.0, 4.5, 5.0}));
  EXPECT_DOUBLE_EQ(result.rows[0].errors[0],
                   0.5 * (std::abs(depth_0 - 1.5) / 1.5 + std::abs(diameter_0 - 6.0) / 6.0));
  EXPECT_DOUBLE_EQ(result.rows[0].errors[1], (4.5 - v) / 4.5);
  EXPECT_TRUE(result.rows[0].ok()) << describe_row(result, result.rows[0]);
  // Row 2: the second; the hole against the one value 3.
  EXPECT_TRUE(same(result.rows[1].references, {2.0, 5.0, 3.0, 3.0}));
  EXPECT_DOUBLE_EQ(result.rows[1].errors[0],
                   0.5 * (std::abs(depth_1 - 2.0) / 2.0 + std::abs(diameter_1 - 5.0) / 5.0));
  EXPECT_DOUBLE_EQ(result.rows[1].errors[1], (v - 3.0) / 3.0);
  EXPECT_EQ(result.rows[1].over_tolerance, std::vector<std::string>{"hole"});
  // Row 3: no crater reference (value only, no tolerance check), the study-wide band about it.
  EXPECT_TRUE(same(result.rows[2].references, {nan, nan, 3.5, 4.6}));
  EXPECT_TRUE(std::isnan(result.rows[2].errors[0]));
  EXPECT_EQ(result.rows[2].errors[1], 0.0);
  EXPECT_TRUE(result.rows[2].ok()) << describe_row(result, result.rows[2]);
  // Row 4: a band [3, 3.5] below the hole.
  EXPECT_TRUE(same(result.rows[3].references, {nan, nan, 3.0, 3.5}));
  EXPECT_DOUBLE_EQ(result.rows[3].errors[1], (v - 3.5) / 3.5);
  EXPECT_EQ(result.rows[3].over_tolerance, std::vector<std::string>{"hole"});

  write_study(plan, result, dir.str() + "/out");
  std::ifstream in(dir.file("out/study.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_NE(lines[0].find(",crater.depth,crater.diameter,hole,crater.error,hole.error,"
                          "crater.reference_depth,crater.reference_diameter,hole.reference_low,"
                          "hole.reference_high,status"),
            std::string::npos)
      << lines[0];
  EXPECT_NE(lines[1].find(",1.5,6,4.5,5,ok"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(",2,5,3,3,over tolerance: hole"), std::string::npos) << lines[2];
  EXPECT_NE(lines[3].find(",,,3.5,4.6,ok"), std::string::npos) << lines[3];
  EXPECT_NE(lines[4].find(",,,3,3.5,over tolerance: hole"), std::string::npos) << lines[4];
  std::ifstream md_in(dir.file("out/study.md"));
  const std::string md((std::istreambuf_iterator<char>(md_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("![hole against impact speed (km/s)](value_vs_resolution.svg)"),
            std::string::npos)
      << md;
  // The plot: x 5..7 and y 3..5 in steps of 0.5 (the plot area spans x 80..530, y 50..420).
  // The methods' lines, then the references: the bands' bounds at 5 and 6 (two at 6, one per
  // run, in the runs' order), the one value at 7 (a marker: one point, no line).
  std::ifstream svg_in(dir.file("out/value_vs_resolution.svg"));
  const std::string svg((std::istreambuf_iterator<char>(svg_in)), std::istreambuf_iterator<char>());
  std::size_t series = 0;
  for (auto p = svg.find("<g class=\"series\""); p != std::string::npos;
       p = svg.find("<g class=\"series\"", p + 1))
    ++series;
  EXPECT_EQ(series, 5u);
  const auto mpm = svg.find("data-name=\"MPM\""), again = svg.find("data-name=\"MPM again\""),
             low = svg.find("data-name=\"reference low\""),
             high = svg.find("data-name=\"reference high\""),
             one = svg.find("data-name=\"reference\"");
  ASSERT_NE(one, std::string::npos) << svg;
  EXPECT_TRUE(mpm < again && again < low && low < high && high < one) << svg;
  char points[160];
  const double y = 50 + 370 * (1 - (v - 3.0) / (5.0 - 3.0));
  std::snprintf(points, sizeof points, "<polyline points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f \"", 80.0,
                y, 80 + 450 * ((6.0 - 5.0) / (7.0 - 5.0)), y, 530.0, y);
  EXPECT_NE(svg.find(points, mpm), std::string::npos) << points << "\n" << svg;
  std::snprintf(points, sizeof points, "<polyline points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f \"", 80.0,
                50 + 370 * (1 - 1.5 / 2), 305.0, 50 + 370 * (1 - 0.5 / 2), 305.0,
                50 + 370 * (1 - 0.0 / 2));
  EXPECT_NE(svg.find(points, low), std::string::npos) << points << "\n" << svg;
  EXPECT_NE(svg.find("<circle cx=\"530.00\" cy=\"420.00\"", one), std::string::npos) << svg;
  EXPECT_NE(svg.find(">impact speed (km/s)</text>"), std::string::npos);
}

}  // namespace
}  // namespace afemp::analysis
