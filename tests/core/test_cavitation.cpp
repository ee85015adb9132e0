// Cavitation of water (Material::pressure_cutoff, core/materials/constitutive_update.hpp). Two
// water blocks of Steinberg's Mie-Grueneisen water (rho0 1.0 g/cm^3, c0 1647 m/s, s 1.921,
// gamma0 0.28: D. J. Steinberg, UCRL-MA-106439, 1996) fly apart at 20 m/s each, held laterally
// (a plane wave). Reference: the acoustic tension rho0 c0 v = 1e-3 x 1647 x 20 = 32.9 MPa. Without
// a cutoff the water pulls beyond 80 % of that (46 MPa: the release rings); with
// pressure_cutoff = 0 no particle's pressure ever falls below 0 (exactly: the cut pressure is
// the value set), and the energy balance closes to 1 % (the cut's work is done at the cut
// pressure; the uncut water's ringing ends 1.7 % off). With a cutoff of -10 MPa the water
// reaches it and stays there, the balance again within 1 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "explosive_scenes.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

namespace afemp::mpm {
namespace {

std::string water(const std::string& cutoff) {
  return R"([run]
end_time = 0.01
[grid]
cell = 0.5
min = [0, 0, -10]
max = [1, 1, 10]
boundary = { xmin = "symmetric", xmax = "symmetric", ymin = "symmetric", ymax = "symmetric" }
)" + test::water_material() +
         cutoff + R"(
[[bodies]]
name = "lower"
material = "water"
shape = { box = { min = [0, 0, -5], max = [1, 1, 0] } }
velocity = [0, 0, -20]
[[bodies]]
name = "upper"
material = "water"
shape = { box = { min = [0, 0, 0], max = [1, 1, 5] } }
velocity = [0, 0, 20]
)";
}

struct Pull {
  double lowest = 0.0, balance = 0.0;
};

Pull pull(const std::string& cutoff) {
  const core::Scene scene = core::parse_scene(water(cutoff), "water.toml");
  MpmSolver solver(scene, generate_particles(scene));
  const double e0 = solver.energies().total();
  Pull r;
  while (solver.time() < 0.002) {
    solver.step(std::min(solver.stable_time_step(), 0.002 - solver.time()));
    for (const core::SymTensor& s : solver.particles().stress)
      r.lowest = std::min(r.lowest, core::pressure(s));
  }
  r.balance = solver.energies().total() / e0 - 1.0;
  return r;
}

TEST(Cavitation, WaterCarriesNoTensionBelowItsCutoff) {
  const Pull free = pull("");
  const Pull cut = pull("pressure_cutoff = 0.0");
  std::printf(
      "water pulled apart at 2 x 20 m/s: lowest pressure %.2f MPa without a cutoff "
      "(rho0 c0 v = 32.9), %.3g MPa with cutoff 0; energy balance %+.3f %% and %+.3f %%\n",
      free.lowest, cut.lowest, 100.0 * free.balance, 100.0 * cut.balance);
  EXPECT_LT(free.lowest, -0.8 * 32.9);
  EXPECT_GE(cut.lowest, 0.0);
  EXPECT_LT(std::abs(cut.balance), 0.01);
  // A cutoff below zero: the water pulls down to it, never beyond, and the work done at the
  // cut pressure keeps the balance.
  const Pull deep = pull("pressure_cutoff = -10.0");
  EXPECT_GE(deep.lowest, -10.0);
  EXPECT_LT(deep.lowest, -9.9);
  EXPECT_LT(std::abs(deep.balance), 0.01);
}

TEST(Cavitation, ACutoffWithoutAnEosIsRefused) {
  try {
    core::parse_scene(
        "[run]\nend_time = 1.0\n[materials.steel]\ndensity = 7.85e-3\nE = 200e3\nnu = 0.3\n"
        "pressure_cutoff = -100\n[[bodies]]\nname = \"b\"\nmaterial = \"steel\"\n"
        "discretisation = \"hexahedra\"\nshape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\n",
        "steel.toml");
    ADD_FAILURE() << "taken";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'materials.steel.pressure_cutoff': a pressure "
                                         "cutoff (cavitation) acts on an eos's pressure"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace afemp::mpm
