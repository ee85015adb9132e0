// Trusses tied into hexahedra (bonded_to naming a body of hexahedra: rebar in solid elements,
// fem/embedded_nodes.hpp). References: the composite bar's closed forms (equal strains in the
// steel and the concrete), the prestress's elastic-shortening loss, and momentum conservation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "afemp/simulation.hpp"
#include "core/scene.hpp"
#include "phase_test_support.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp {
namespace {

// Concrete (nu = 0: the column and the prism stay in uniaxial stress) and steel.
constexpr double kRhoC = 2.4e-3, kEc = 3.0e4, kRhoS = 7.85e-3, kEs = 2.0e5;

const std::string kMaterials =
    "[materials.concrete]\ndensity = 2.4e-3\nE = 3.0e4\nnu = 0.0\n"
    "[materials.steel]\ndensity = 7.85e-3\nE = 2.0e5\nnu = 0.3\n";

// A bar of concrete hexahedra, 10 x 10 x 100 (2 x 2 x 20, fully integrated), with a steel
// tendon of `area` tied along its axis from z0 to z1.
std::string bar(double area, double z0, double z1, const std::string& tendon_extra) {
  char tendon[320];
  std::snprintf(tendon, sizeof tendon,
                "[[bodies]]\nname = \"tendon\"\ndiscretisation = \"trusses\"\nmaterial = "
                "\"steel\"\nshape = { line = { from = [5, 5, %.17g], to = [5, 5, %.17g] } }\n"
                "area = %.17g\nmesh = { segments = 40 }\nbonded_to = \"bar\"\n",
                z0, z1, area);
  return kMaterials +
         "[[bodies]]\nname = \"bar\"\ndiscretisation = \"hexahedra\"\nmaterial = \"concrete\"\n"
         "element = \"full\"\nshape = { box = { min = [0, 0, 0], max = [10, 10, 100] } }\n"
         "mesh = { divisions = [2, 2, 20] }\n" +
         tendon + tendon_extra;
}

double top_displacement(Simulation& sim) {
  const NodeFields n = sim.nodes();
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < n.size(); ++i)
    if (n.body[i] == 0 && n.position[i].z > 99.0) sum += n.position[i].z - 100.0, ++count;
  return sum / count;
}

// The tendon's mean stress in the bar's middle half.
double middle_tendon_stress(Simulation& sim) {
  return test::mean_truss_stress(sim, 25.0, 75.0);
}

// A column held at its base under gravity, relaxed (DRTOL 1e-5: a residue of about 0.3 % of
// the static displacement): its top settles by the composite column's
// (rho_c A_c + rho_s A_s) g H^2 / (2 (E_c A_c + E_s A_s)), the tendon's weight carried and its
// stiffness added (13 % less than the plain column's), within 1 %.
TEST(TiedRebar, ColumnUnderGravitySettlesAsTheCompositeSection) {
  const double As = 5.0, Ac = 100.0, g = 100.0, H = 100.0;
  const std::string text =
      "[run]\nend_time = 2.01\ngravity = [0, 0, -100]\nhistory_every = 100\n" +
      bar(As, 0.0, 100.0, "") +
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "body = \"bar\"\nfixed = [\"x\", \"y\", \"z\"]\n"
      "[[phases]]\nkind = \"relaxation\"\nend_time = 2\ntolerance = 1e-5\n"
      "[[phases]]\nkind = \"explicit\"\n";
  Simulation sim(core::parse_scene(text, "column.toml"));
  sim.run_to(2.0);
  const double exact = -(kRhoC * Ac + kRhoS * As) * g * H * H / (2.0 * (kEc * Ac + kEs * As));
  const double plain = -kRhoC * g * H * H / (2.0 * kEc);
  const double u = top_displacement(sim);
  std::printf("tied column: top %.6g (composite %.6g, %+.2f %%; plain column %.6g), %ld steps\n", u,
              exact, 100.0 * (u / exact - 1.0), plain, sim.step_count());
  EXPECT_NEAR(u / exact, 1.0, 0.01);
  // The tendon's top node sits on the column's top face, at its middle node, and moves with it.
  const NodeFields n = sim.nodes();
  int matched = 0;
  for (std::size_t i = 0; i < n.size(); ++i)
    for (std::size_t j = 0; j < n.size(); ++j)
      if (n.body[i] == 1 && n.body[j] == 0 && n.position[i].z > 99.0 && n.position[j].z > 99.0 &&
          std::abs(n.position[i].x - n.position[j].x) < 1e-9 &&
          std::abs(n.position[i].y - n.position[j].y) < 1e-9) {
        EXPECT_NEAR(n.position[i].z, n.position[j].z, 1e-12 * 100.0);
        ++matched;
      }
  EXPECT_EQ(matched, 1);
}

// A tendon prestressed to sigma_p tied along a free prism: relaxed, it shortens with the
// concrete until sigma_t A_t + sigma_c A_c = 0 at equal strains,
// sigma_t = sigma_p / (1 + E_s A_s / E_c A_c) (the elastic-shortening loss; here 0.8 sigma_p),
// within 2 % in the middle half; the concrete there carries -sigma_t A_t / A_c.
TEST(TiedRebar, PrestressedTendonRelaxesToTheElasticShorteningLoss) {
  const double As = 3.75, Ac = 100.0, sigma_p = 600.0;
  const std::string text = "[run]\nend_time = 3.01\nhistory_every = 100\n" +
                           bar(As, 1.0, 99.0, "prestress = 600\n") +
                           "[[phases]]\nkind = \"relaxation\"\nend_time = 3\ntolerance = 1e-5\n"
                           "[[phases]]\nkind = \"explicit\"\n";
  Simulation sim(core::parse_scene(text, "prism.toml"));
  sim.run_to(3.0);
  const double expected = sigma_p / (1.0 + kEs * As / (kEc * Ac));
  const double tendon = middle_tendon_stress(sim);
  const NodeFields n = sim.nodes();
  const ElementFields h = sim.hexahedra();
  double concrete = 0.0;
  int points = 0;
  for (std::size_t e = 0; e < h.size(); ++e) {
    double z = 0.0;
    for (int a = 0; a < 8; ++a)
      z += 0.125 * n.position[static_cast<std::size_t>(h.connectivity[8 * e + a])].z;
    if (z < 25.0 || z > 75.0) continue;
    for (std::size_t p = h.first_point[e]; p < h.first_point[e + 1]; ++p)
      concrete += h.stress[p].zz, ++points;
  }
  concrete /= points;
  std::printf(
      "tied tendon relaxed: %.5g MPa (closed form %.5g, %+.2f %%), concrete %.5g MPa "
      "(%.5g), %ld steps\n",
      tendon, expected, 100.0 * (tendon / expected - 1.0), concrete, -expected * As / Ac,
      sim.step_count());
  EXPECT_NEAR(tendon / expected, 1.0, 0.02);
  EXPECT_NEAR(concrete / (-expected * As / Ac), 1.0, 0.02);
}

// A composite bar in free flight, its tendon prestressed (the internal forces do no net work on
// the whole): the momentum stays (m_c + m_s) v to round-off, and the body sums book the
// tendon's own mass and momentum.
TEST(TiedRebar, MomentumIsKeptAndEachBodyBooksItsOwnMass) {
  const std::string text = "[run]\nend_time = 0.05\n" + bar(3.75, 1.0, 99.0, "prestress = 600\n");
  std::string moving = text;
  moving.replace(moving.find("element = \"full\""), 0, "velocity = [0, 0, 20]\n");
  Simulation sim(core::parse_scene(moving, "flight.toml"));
  const double mc = kRhoC * 10.0 * 10.0 * 100.0, ms = kRhoS * 3.75 * 98.0;
  const Energies e0 = sim.energies();
  EXPECT_NEAR(e0.bodies[0].mass / mc, 1.0, 1e-12);
  EXPECT_NEAR(e0.bodies[1].mass / ms, 1.0, 1e-12);
  EXPECT_NEAR(e0.bodies[1].momentum.z / (ms * 20.0), 1.0, 1e-12);
  sim.run();
  const Energies e = sim.energies();
  const double p = e.bodies[0].momentum.z + e.bodies[1].momentum.z;
  EXPECT_GT(sim.step_count(), 100);
  EXPECT_NEAR(p / ((mc + ms) * 20.0), 1.0, 1e-12);
  EXPECT_NEAR(e.bodies[0].momentum.x + e.bodies[1].momentum.x, 0.0, 1e-12 * p);
  EXPECT_NEAR(e.bodies[0].mass + e.bodies[1].mass, mc + ms, 1e-12 * (mc + ms));
}

// The bar's supports for a static phase: symmetry planes x = 0, y = 0 and the base z = 0 (the
// bar alone: the tendon's base node lies on z = 0 and moves with the bar).
const std::string kPlanes =
    "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }\n"
    "body = \"bar\"\nfixed = [\"x\"]\n"
    "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }\n"
    "body = \"bar\"\nfixed = [\"y\"]\n"
    "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
    "body = \"bar\"\nfixed = [\"z\"]\n";

// Patch test in a static phase: the bar stretched by 0.01 over its 100 mm (uniform strain
// 1e-4) carries E_c eps in every point and the tied tendon E_s eps, to round-off (the tied
// nodes take the linear field exactly); the composite column under gravity settles as above.
TEST(TiedRebar, StaticPhaseTakesTheTiedTendon) {
  const std::string pull =
      "[run]\nend_time = 1.01\n" + bar(5.0, 0.0, 100.0, "") + kPlanes +
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 100], normal = [0, 0, 1] } }\n"
      "body = \"bar\"\nvelocity = [0, 0, 0.01]\ncomponents = [\"z\"]\n"
      "[[phases]]\nkind = \"static\"\nend_time = 1.0\nload_steps = 2\n"
      "[[phases]]\nkind = \"explicit\"\n";
  Simulation sim(core::parse_scene(pull, "pull.toml"));
  sim.run_to(1.0);
  const double eps = 0.01 / 100.0;
  const ElementFields h = sim.hexahedra();
  for (std::size_t p = 0; p < h.stress.size(); ++p)
    ASSERT_NEAR(h.stress[p].zz / (kEc * eps), 1.0, 1e-8) << p;
  const ElementFields t = sim.trusses();
  for (std::size_t e = 0; e < t.size(); ++e)
    ASSERT_NEAR(t.stress[t.first_point[e]].xx / (kEs * eps), 1.0, 1e-8) << e;

  const std::string weight =
      "[run]\nend_time = 1.01\ngravity = [0, 0, -100]\n" + bar(5.0, 0.0, 100.0, "") + kPlanes +
      "[[phases]]\nkind = \"static\"\nend_time = 1.0\n[[phases]]\nkind = \"explicit\"\n";
  Simulation column(core::parse_scene(weight, "weight.toml"));
  column.run_to(1.0);
  const double exact =
      -(kRhoC * 100.0 + kRhoS * 5.0) * 100.0 * 1e4 / (2.0 * (kEc * 100.0 + kEs * 5.0));
  const double u = top_displacement(column);
  std::printf("tied column, static phase: top %.6g (composite %.6g, %+.3f %%)\n", u, exact,
              100.0 * (u / exact - 1.0));
  EXPECT_NEAR(u / exact, 1.0, 0.005);
}

// The prestressed tendon of the relaxation test brought into equilibrium by a static phase
// after a first explicit step (the phase turns the state's imbalance on over its load steps):
// sigma_p / (1 + E_s A_s / E_c A_c) in the middle half, within 0.5 %.
TEST(TiedRebar, StaticPhaseBalancesAPrestressedTendon) {
  const std::string text = "[run]\nend_time = 1.01\n" + bar(3.75, 1.0, 99.0, "prestress = 600\n") +
                           kPlanes +
                           "[[phases]]\nkind = \"explicit\"\nend_time = 1e-4\n"
                           "[[phases]]\nkind = \"static\"\nend_time = 1.0\nload_steps = 2\n"
                           "[[phases]]\nkind = \"explicit\"\n";
  Simulation sim(core::parse_scene(text, "prestress.toml"));
  sim.run_to(1.0);
  const double expected = 600.0 / (1.0 + kEs * 3.75 / (kEc * 100.0));
  const double tendon = middle_tendon_stress(sim);
  std::printf("tied tendon, static phase: %.5g MPa (closed form %.5g, %+.3f %%)\n", tendon,
              expected, 100.0 * (tendon / expected - 1.0));
  EXPECT_NEAR(tendon / expected, 1.0, 0.005);
}

// An implicit phase (trapezoidal rule, 100 steps) of the composite column under gravity applied
// at once, to t = 2 H / c with c = sqrt((E_c A_c + E_s A_s) / (rho_c A_c + rho_s A_s)): every
// mode of the fixed-free bar is then at its far turn, and its top is at twice the static
// displacement, within 2 % (the uniform bar's mark in tests/fem/test_implicit_phase.cpp is 1 %).
TEST(TiedRebar, ImplicitPhaseSwingsTheCompositeColumnToTwiceItsStaticDisplacement) {
  const double ea = kEc * 100.0 + kEs * 5.0, ma = kRhoC * 100.0 + kRhoS * 5.0;
  const double t_end = 2.0 * 100.0 / std::sqrt(ea / ma);
  char phases[256];
  std::snprintf(phases, sizeof phases,
                "[[phases]]\nkind = \"implicit\"\nend_time = %.17g\ntime_step = %.17g\n"
                "[[phases]]\nkind = \"explicit\"\n",
                t_end, t_end / 100.0);
  char run[96];
  std::snprintf(run, sizeof run, "[run]\nend_time = %.17g\ngravity = [0, 0, -100]\n", 1.01 * t_end);
  Simulation sim(
      core::parse_scene(run + bar(5.0, 0.0, 100.0, "") + kPlanes + phases, "swing.toml"));
  sim.run_to(t_end);
  const double u_static = -ma * 100.0 * 1e4 / (2.0 * ea);
  const double u = top_displacement(sim);
  std::printf("tied column, implicit phase: top %.6g at 2H/c (2 u_static %.6g, %+.2f %%)\n", u,
              2.0 * u_static, 100.0 * (u / (2.0 * u_static) - 1.0));
  EXPECT_NEAR(u / (2.0 * u_static), 1.0, 0.02);
}

// A restart from a checkpoint of a run with a tied, prestressed tendon ends as the run that went
// through, history bit for bit (the tied nodes' own masses are made again from the live
// elements on loading).
TEST(TiedRebar, RestartEndsAsTheWholeRun) {
  const test::ScratchDir scratch;
  const std::filesystem::path whole = scratch.path() / "whole",
                              restarted = scratch.path() / "restarted";
  std::string text = "[run]\nend_time = 0.03\nhistory_every = 5\ncheckpoint_every = 0.02\n" +
                     bar(3.75, 1.0, 99.0, "prestress = 600\n");
  text.replace(text.find("element = \"full\""), 0, "velocity = [0, 0, 20]\n");
  const core::Scene scene = core::parse_scene(text, "restart.toml");
  SimulationOptions a;
  a.output_directory = whole.string();
  Simulation first(scene, a);
  first.run();
  std::filesystem::copy(
      whole, restarted,
      std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
  SimulationOptions b;
  b.output_directory = restarted.string();
  b.restart_from = newest_checkpoint(restarted.string());
  ASSERT_FALSE(b.restart_from.empty());
  Simulation second(scene, b);
  EXPECT_LT(second.time(), 0.025);  // restarted at the checkpoint at 0.02, not at the end
  second.run();
  auto read = [](const std::filesystem::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  EXPECT_EQ(read(whole / "history.csv"), read(restarted / "history.csv"));
  EXPECT_GT(read(whole / "history.csv").size(), 1000u);
}

TEST(TiedRebar, BadInputNamesTheBodyAndWhatIsAllowed) {
  using test::error_of;
  const std::string run = "[run]\nend_time = 0.01\n";
  // A node outside the host.
  try {
    Simulation sim(core::parse_scene(run + bar(1.0, 1.0, 120.0, ""), "out.toml"));
    ADD_FAILURE() << "a tendon reaching past its host ran";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("lies outside the hexahedra of \"bar\""), std::string::npos) << what;
    // z_k = 1 + 2.975 k: node 34 is the first past the top face.
    EXPECT_NE(what.find("node 34 of body \"tendon\" at (5, 5, 102.15)"), std::string::npos) << what;
  }
  // Hexahedra do not tie into hexahedra; a tied body takes no velocity, constraint or wall.
  std::string hex =
      run + bar(1.0, 1.0, 99.0, "") +
      "[[bodies]]\nname = \"block\"\ndiscretisation = \"hexahedra\"\nmaterial = "
      "\"steel\"\nshape = { box = { min = [2, 2, 2], max = [4, 4, 4] } }\nmesh = { size = 1 }\n"
      "bonded_to = \"bar\"\n";
  EXPECT_NE(error_of(hex).find("only trusses are tied into hexahedra"), std::string::npos)
      << error_of(hex);
  std::string fast = run + bar(1.0, 1.0, 99.0, "velocity = [0, 0, 5]\n");
  EXPECT_NE(test::checked_error_of(fast).find(
                "moves with its host from the start; give the velocity to \"bar\""),
            std::string::npos);
  std::string held = run + bar(1.0, 1.0, 99.0, "") +
                     "[[constraints]]\nnodes = { plane = { point = [0, 0, 1], normal = [0, 0, 1] "
                     "} }\nbody = \"tendon\"\nfixed = [\"z\"]\n";
  EXPECT_NE(error_of(held).find("is tied into hexahedra and moves with them"), std::string::npos);
  std::string walled = run + bar(1.0, 1.0, 99.0, "") +
                       "[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nbodies = [\"tendon\"]\n";
  EXPECT_NE(error_of(walled).find("walls act on free mesh bodies (name its host)"),
            std::string::npos);
  // A static phase that lists the tied body without its host.
  const std::string alone = run + bar(1.0, 1.0, 99.0, "") +
                            "[[phases]]\nkind = \"static\"\nend_time = 0.005\nbodies = "
                            "[\"tendon\"]\n[[phases]]\nkind = \"explicit\"\n";
  const std::string why = test::checked_error_of(alone);
  EXPECT_NE(why.find("phases[0].bodies"), std::string::npos) << why;
  EXPECT_NE(why.find("body \"tendon\" is tied into \"bar\", which a static phase does not "
                     "solve: list that body"),
            std::string::npos)
      << why;
}

}  // namespace
}  // namespace afemp
