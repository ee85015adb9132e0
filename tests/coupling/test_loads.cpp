// [[loads]]: surface tractions on hexahedra (fem/surface_loads.cpp) and forces shared by
// particles (mpm/particle_loads.cpp). References: the consistent load vector of a uniform
// traction on a bilinear face (its resultant t A and its first moment t A x_c, the centroid's),
// Newton's second law for a free body (momentum F t), the energy balance with the loads' work
// booked as external work, and the elongation sigma L / E of a bar pulled at its end (nu = 0).
#include <gtest/gtest.h>

#include <afemp/afemp.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp {
namespace {

const std::string kMaterial =
    "[materials.gel]\ndensity = 1.0\nE = 1000.0\nnu = 0.3\n"
    "[materials.bar]\ndensity = 1.0\nE = 1000.0\nnu = 0.0\n";

// A block 2 x 1 x 1 m of hexahedra (4 x 2 x 2) or of particles (cells of 0.25 m, 2 per cell
// per direction), free, with `load` (a [[loads]] table's keys) to `end` s.
std::string free_block(bool particles, const std::string& load, double end) {
  char run[96];
  std::snprintf(run, sizeof run, "[run]\nend_time = %.17g\n", end);
  std::string s = std::string(run) + kMaterial;
  if (particles)
    s += "[grid]\ncell = 0.25\nmin = [-1, -1, -1]\nmax = [3, 3, 3]\n"
         "[[bodies]]\nname = \"block\"\nmaterial = \"gel\"\n"
         "shape = { box = { min = [0, 0, 0], max = [2, 1, 1] } }\n";
  else
    s += "[[bodies]]\nname = \"block\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
         "shape = { box = { min = [0, 0, 0], max = [2, 1, 1] } }\n"
         "mesh = { divisions = [4, 2, 2] }\n";
  return s + "[[loads]]\nbody = \"block\"\n" + load;
}

struct Pushed {
  Vec3 momentum;
  double balance = 0.0;  // (E - E0 - W_ext) / W_ext
  double work = 0.0;
  double last_step = 0.0;
};

Pushed push(const std::string& text) {
  Simulation sim(core::parse_scene(text, "block.toml"));
  const double e0 = sim.energies().total();
  double last = 0.0;
  while (!sim.finished()) {
    const double before = sim.time();
    sim.step();
    last = sim.time() - before;  // the last one cut to land on the end time
  }
  const Energies e = sim.energies();
  Pushed p;
  p.momentum = e.bodies[0].momentum;
  p.work = e.external_work;
  p.balance = (e.total() - e0 - e.external_work) / e.external_work;
  p.last_step = last;
  return p;
}

// Reference: a free body under a constant force F has momentum F t (Newton's second law); the
// explicit FE update's momentum is that of v^{n-1/2}, so F (t - dt / 2) after a last step dt,
// and the grid's is F t. The hexahedra's face x = 2 takes a shear traction 10 Pa (area 1 m^2:
// 10 N); the particles of the layer x > 1.87 m share a force of 10 N.
TEST(Loads, AFreeBlockTakesTheImpulseOfItsLoad) {
  const double end = 0.5;
  const Pushed hex = push(free_block(
      false,
      "nodes = { plane = { point = [2, 0, 0], normal = [1, 0, 0] } }\ntraction = [0, 10, 0]\n",
      end));
  const Pushed grains = push(free_block(
      true, "particles = { box = { min = [1.87, -1, -1], max = [3, 3, 3] } }\nforce = [0, 10, 0]\n",
      end));
  std::printf("hexahedra: p_y %.12g (F (t - dt/2) = %.12g); particles: p_y %.12g (F t = %.12g)\n",
              hex.momentum.y, 10.0 * (end - 0.5 * hex.last_step), grains.momentum.y, 10.0 * end);
  EXPECT_NEAR(hex.momentum.y, 10.0 * (end - 0.5 * hex.last_step), 1e-9);
  EXPECT_NEAR(grains.momentum.y, 10.0 * end, 1e-9);
  EXPECT_NEAR(hex.momentum.x, 0.0, 1e-12);
  EXPECT_NEAR(grains.momentum.x, 0.0, 1e-12);
}

// Reference: a force M g shared by every particle of a body by mass is the body force m g, so
// the run matches the same block under gravity g: momentum and external work to 1e-12, and the
// energy balance closes to round-off as it does under gravity (the block falls unstrained).
TEST(Loads, ALoadOnEveryParticleIsABodyForce) {
  const double end = 0.5;
  const Pushed loaded = push(free_block(
      true, "particles = { box = { min = [-1, -1, -1], max = [3, 3, 3] } }\nforce = [0, 0, -10]\n",
      end));
  std::string gravity = free_block(true, "", end);
  gravity = gravity.substr(0, gravity.find("[[loads]]"));
  gravity.insert(gravity.find("[materials"), "gravity = [0, 0, -5]\n");  // M = 2 kg
  Simulation sim(core::parse_scene(gravity, "falling.toml"));
  sim.run();
  const Energies e = sim.energies();
  std::printf("load: p_z %.15g, work %.15g, balance %.2e; gravity: p_z %.15g, work %.15g\n",
              loaded.momentum.z, loaded.work, loaded.balance, e.bodies[0].momentum.z,
              e.external_work);
  EXPECT_NEAR(loaded.momentum.z, e.bodies[0].momentum.z, 1e-12 * 5.0);
  EXPECT_NEAR(loaded.work, e.external_work, 1e-12 * e.external_work);
  EXPECT_LT(std::abs(loaded.balance), 1e-12);
}

// Reference: a bar 4 x 1 x 1 m (nu = 0) held at x = 0 and pulled at x = 4 by a traction raised
// from 0 to 5 Pa over 5 s (1 - cos, ten times its longest period 4 L / c = 0.506 s), then held,
// oscillates little (about 1 %) about the stretch sigma L / E = 0.02 m. Pass: the work booked as
// external work balances the energy to 1e-4 of it, and the end's stretch averaged over four
// periods after the ramp is within 0.5 % of 0.02 m.
TEST(Loads, ASlowlyPulledBarStoresTheLoadsWork) {
  const std::string text =
      "[run]\nend_time = 7.024\n" + kMaterial +
      "[[bodies]]\nname = \"bar\"\nmaterial = \"bar\"\ndiscretisation = \"hexahedra\"\n"
      "element = \"full\"\nshape = { box = { min = [0, 0, 0], max = [4, 1, 1] } }\n"
      "mesh = { divisions = [8, 2, 2] }\n"
      "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }\n"
      "fixed = [\"all\"]\n"
      "[[loads]]\nbody = \"bar\"\nnodes = { plane = { point = [4, 0, 0], normal = [1, 0, 0] } }\n"
      "traction = [5, 0, 0]\ncurve = [[0, 0], [0.5, 0.0244717], [1, 0.0954915], [1.5, 0.206107], "
      "[2, 0.345492], [2.5, 0.5], [3, 0.654508], [3.5, 0.793893], [4, 0.904508], [4.5, 0.975528], "
      "[5, 1]]\n";
  Simulation sim(core::parse_scene(text, "bar.toml"));
  const double e0 = sim.energies().total();
  double stretch = 0.0;  // the end's displacement averaged over [5, 7.024] s, four periods
  while (!sim.finished()) {
    const double before = sim.time();
    sim.step();
    if (before < 5.0) continue;
    const NodeFields n = sim.nodes();
    double u = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < n.size(); ++i)
      if (n.position[i].x > 3.9) u += n.position[i].x - 4.0, ++count;
    stretch += (sim.time() - before) * u / count / 2.024;
  }
  const Energies e = sim.energies();
  const double balance = (e.total() - e0 - e.external_work) / e.external_work;
  std::printf(
      "work %.6g J, internal %.6g J, kinetic %.3g J, balance %.2e; mean stretch over four "
      "periods %.7g m (sigma L / E = 0.02)\n",
      e.external_work, e.internal, e.kinetic, balance, stretch);
  EXPECT_LT(std::abs(balance), 1e-4);
  EXPECT_NEAR(stretch, 0.02, 0.005 * 0.02);
}

// Reference: a load's curve scales it at each step's start time: a force held at 1 to t = 0.02
// and 0 after gives the momentum of the first 0.02 s, F * 0.02, once the load is off (to a
// step's impulse F dt: the factor is taken at a step's start).
TEST(Loads, ACurveTurnsTheLoadOff) {
  const Pushed grains = push(free_block(
      true,
      "particles = { box = { min = [1.87, -1, -1], max = [3, 3, 3] } }\nforce = [0, 0, 10]\n"
      "curve = [[0, 1], [0.02, 1], [0.0200001, 0]]\n",
      0.05));
  std::printf("particles: p_z %.9g against F * 0.02 = 0.2 (step %.3g)\n", grains.momentum.z,
              grains.last_step);
  EXPECT_NEAR(grains.momentum.z, 0.2, 10.0 * grains.last_step);
}

// Reference: the consistent nodal forces of a uniform traction t on a flat bilinear face sum to
// t A and put the resultant at the face's centroid (Zienkiewicz, Taylor & Zhu 2013, §8.5), to
// round-off. The face is a trapezoid, bases 4 m (y = 0) and 2 m (y = 2 m), area 6 m^2,
// centroid y_c = h (b1 + 2 b2) / 3 (b1 + b2) = 8/9 m, where giving each node a quarter of the
// area would put it at the corners' mean, 1 m. A total force F spreads as the traction F / A.
TEST(Loads, AFacesNodalForcesHaveTheTractionsResultantAndCentroid) {
  test::ScratchDir dir;
  const std::string mesh = (dir.path() / "trapezoid.inp").string();
  std::ofstream(mesh) << "*NODE\n1, 0, 0, 0\n2, 4, 0, 0\n3, 3, 2, 0\n4, 1, 2, 0\n"
                         "5, 0, 0, 1\n6, 4, 0, 1\n7, 3, 2, 1\n8, 1, 2, 1\n"
                         "*ELEMENT, TYPE=C3D8R, ELSET=block\n1, 1, 2, 3, 4, 5, 6, 7, 8\n";
  for (const bool total : {false, true}) {
    const std::string text =
        "[run]\nend_time = 1\n" + kMaterial +
        "[[bodies]]\nname = \"prism\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
        "shape = { mesh = { file = \"" +
        mesh +
        "\" } }\n[[loads]]\nbody = \"prism\"\n"
        "nodes = { plane = { point = [0, 0, 1], normal = [0, 0, 1] } }\n" +
        (total ? "force = [0, 0, -18]\n" : "traction = [0, 0, -3]\n");
    const core::Scene scene = core::parse_scene(text, "prism.toml");
    const fem::FeSolver solver(scene);
    const std::vector<Vec3> f = solver.scene_loads_at(0.0);
    Vec3 sum, moment;
    for (std::size_t n = 0; n < f.size(); ++n) {
      sum += f[n];
      moment += f[n].z * solver.nodes().initial_position[n];
    }
    std::printf("%s: resultant %.15g N, its centroid (%.15g, %.15g)\n",
                total ? "force" : "traction", sum.z, moment.x / sum.z, moment.y / sum.z);
    EXPECT_NEAR(sum.z, -18.0, 1e-12);
    EXPECT_NEAR(moment.x / sum.z, 2.0, 1e-12);
    EXPECT_NEAR(moment.y / sum.z, 8.0 / 9.0, 1e-12);
    EXPECT_NEAR(std::abs(sum.x) + std::abs(sum.y), 0.0, 1e-15);
  }
}

// Reference: a bar 4 x 1 x 1 m (nu = 0) held at x = 0 and pulled by sigma at x = 4 stretches
// uniformly by sigma L / E: 5 Pa * 4 m / 1000 Pa = 0.02 m (a static phase; its loads are those
// at the phase's end: a curve at half there gives half). Pass: to 1e-3 of it (the phase solves
// large displacements: the end face's traction stays the initial area's, the stretch 0.5 %).
TEST(Loads, ABarPulledAtItsEndStretchesBySigmaLOverE) {
  for (const double factor : {1.0, 0.5}) {
    char curve[64];
    std::snprintf(curve, sizeof curve, "curve = [[0, 0], [1, %g]]\n", factor);
    const std::string text =
        "[run]\nend_time = 1\n" + kMaterial +
        "[[bodies]]\nname = \"bar\"\nmaterial = \"bar\"\ndiscretisation = \"hexahedra\"\n"
        "element = \"full\"\nshape = { box = { min = [0, 0, 0], max = [4, 1, 1] } }\n"
        "mesh = { divisions = [4, 1, 1] }\n"
        "[[constraints]]\nnodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }\n"
        "fixed = [\"all\"]\n"
        "[[loads]]\nbody = \"bar\"\nnodes = { plane = { point = [4, 0, 0], normal = [1, 0, 0] } }\n"
        "traction = [5, 0, 0]\n" +
        std::string(curve) + "[[phases]]\nkind = \"static\"\nend_time = 1\n";
    Simulation sim(core::parse_scene(text, "bar.toml"));
    sim.run();
    const NodeFields n = sim.nodes();
    double u = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < n.size(); ++i)
      if (n.position[i].x > 3.5) u += n.position[i].x - 4.0, ++count;
    u /= count;
    std::printf("factor %g: end displacement %.9g m against %.9g\n", factor, u, 0.02 * factor);
    EXPECT_NEAR(u, 0.02 * factor, 1e-3 * 0.02 * factor);
  }
}

// Reference: a run restarted from its checkpoint ends bit-identical to the whole run
// (docs/restart.md), loads included: a block of hexahedra under a ramped traction and a block of
// particles under a ramped force, checkpointed halfway; their histories match to the last digit.
TEST(Loads, ARestartEndsAsTheWholeRun) {
  const test::ScratchDir scratch;
  const std::filesystem::path whole = scratch.path() / "whole",
                              restarted = scratch.path() / "restarted";
  const std::string text =
      "[run]\nend_time = 0.2\nhistory_every = 5\ncheckpoint_every = 0.1\n" + kMaterial +
      "[grid]\ncell = 0.25\nmin = [-1, -1, -1]\nmax = [3, 3, 3]\n"
      "[[bodies]]\nname = \"grains\"\nmaterial = \"gel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [2, 1, 1] } }\n"
      "[[bodies]]\nname = \"block\"\nmaterial = \"gel\"\ndiscretisation = \"hexahedra\"\n"
      "shape = { box = { min = [5, 0, 0], max = [7, 1, 1] } }\nmesh = { divisions = [4, 2, 2] }\n"
      "[[loads]]\nbody = \"grains\"\nparticles = { box = { min = [1.87, -1, -1], max = [3, 3, 3] "
      "} }\nforce = [0, 10, 0]\ncurve = [[0, 0], [0.2, 1]]\n"
      "[[loads]]\nbody = \"block\"\nnodes = { plane = { point = [7, 0, 0], normal = [1, 0, 0] } "
      "}\ntraction = [0, 10, 0]\ncurve = [[0, 0], [0.2, 1]]\n";
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
  EXPECT_LT(second.time(), 0.15);  // restarted at the checkpoint at 0.1, not at the end
  second.run();
  auto read = [](const std::filesystem::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  EXPECT_EQ(read(whole / "history.csv"), read(restarted / "history.csv"));
  EXPECT_GT(read(whole / "history.csv").size(), 1000u);
}

// Reference: the scene rules of [[loads]]: each refusal names the file, the key and what is
// allowed.
TEST(Loads, LoadsTheBodyCannotTakeAreErrors) {
  const std::string block = free_block(true, "", 1.0);
  const std::string head = block.substr(0, block.find("[[loads]]"));
  const std::string traction = test::error_of(
      head +
          "[[loads]]\nbody = \"block\"\nparticles = { box = { min = [1.87, -1, -1], max = [3, "
          "3, 3] } }\ntraction = [0, 10, 0]\n",
      "bad.toml");
  EXPECT_NE(traction.find("bad.toml:"), std::string::npos) << traction;
  EXPECT_NE(traction.find("traction"), std::string::npos) << traction;
  EXPECT_NE(traction.find("carry no surface area"), std::string::npos) << traction;
  const std::string nodes = test::error_of(
      head +
      "[[loads]]\nbody = \"block\"\nnodes = { box = { min = [0, 0, 0], max = [1, 1, 1] } "
      "}\nforce = [0, 10, 0]\n");
  EXPECT_NE(nodes.find("particles = { ... }"), std::string::npos) << nodes;
  const std::string both = test::error_of(
      head +
      "[[loads]]\nbody = \"block\"\nparticles = { box = { min = [0, 0, 0], max = [1, 1, "
      "1] } }\nforce = [0, 10, 0]\ntraction = [0, 1, 0]\n");
  EXPECT_NE(both.find("give either traction"), std::string::npos) << both;
  auto run_error = [](const std::string& text) -> std::string {
    try {
      Simulation sim(core::parse_scene(text, "run.toml"));
      sim.run();
    } catch (const core::InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no InputError for:\n" << text;
    return "";
  };
  const std::string empty = run_error(
      head +
      "[[loads]]\nbody = \"block\"\nparticles = { box = { min = [5, 5, 5], max = [6, 6, 6] "
      "} }\nforce = [0, 10, 0]\n");
  EXPECT_NE(empty.find("holds no particle of body \"block\""), std::string::npos) << empty;
  const std::string twice = run_error(
      head +
      "[[loads]]\nbody = \"block\"\nparticles = { box = { min = [1.5, -1, -1], max = [3, 3, "
      "3] } }\nforce = [0, 10, 0]\n[[loads]]\nbody = \"block\"\n"
      "particles = { box = { min = [1.87, -1, -1], max = [3, 3, 3] } }\nforce = [0, 0, 1]\n");
  EXPECT_NE(twice.find("entries 1 and 2"), std::string::npos) << twice;
  const std::string hex = free_block(false, "", 1.0);
  const std::string hex_head = hex.substr(0, hex.find("[[loads]]"));
  const std::string inner =
      run_error(hex_head +
                "[[loads]]\nbody = \"block\"\nnodes = { plane = { point = [1, 0, 0], normal = [1, "
                "0, 0] } }\ntraction = [0, 10, 0]\n");
  EXPECT_NE(inner.find("no boundary face"), std::string::npos) << inner;
  const std::string converting = test::error_of(
      hex_head +
      "conversion = { plastic_strain = 0.5 }\n[grid]\ncell = 0.5\nmin = [-1, -1, -1]\n"
      "max = [3, 3, 3]\n[[loads]]\nbody = \"block\"\nnodes = { plane = { point = [2, 0, "
      "0], normal = [1, 0, 0] } }\ntraction = [0, 10, 0]\n");
  EXPECT_NE(converting.find("converts elements into particles"), std::string::npos) << converting;
  const std::string implicit =
      run_error(hex_head +
                "element = \"full\"\n[[loads]]\nbody = \"block\"\nnodes = { plane = { point = [2, "
                "0, 0], normal = [1, "
                "0, 0] } }\ntraction = [0, 10, 0]\ncurve = [[0, 0], [1, 1]]\n"
                "[[phases]]\nkind = \"implicit\"\nend_time = 1\ntime_step = 0.1\n");
  EXPECT_NE(implicit.find("holds the loads it starts with"), std::string::npos) << implicit;
}

}  // namespace
}  // namespace afemp
