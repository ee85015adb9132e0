// Absorbing boundaries of meshes (fem/absorbing_boundary.cpp; the viscous boundary of Lysmer &
// Kuhlemeyer 1969).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "fem/driven_column_scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {
namespace {

struct Echo {
  double incident = 0.0, reflected = 0.0;  // the probe's largest |v_z| in each window
  double balance = 0.0;  // (E - E0 - W_ext) / W_in, W_in the work the driven face put in
  double left = 0.0;     // (E - E0 - viscous heat) / W_in: the wave's energy still inside
};

// An elastic copper column (20 mm, 4 x 4 x 80 hexahedra of 0.25 mm, every node held in x and
// y: uniaxial strain, c_L = 4623 m/s) whose top face is driven by a triangular velocity pulse
// (0 -> 10 m/s -> 0 over 1 us, 4.6 mm long); its bottom face is `bottom` ("free" or an
// [[absorbing]] boundary). The probe, the node at the column's middle, sees the incident pulse
// by 3.4 us and the bottom's echo between 3.4 and 9 us (it arrives at 6.5 us; the driven face,
// held after the pulse, would send it back at 10.8 us).
Echo run_column(bool absorbing) {
  std::string text = test::driven_copper_column("", 1.0, 0.0, 20.0, 4, 80, 10.0,
                                                "[[0, 0], [0.0005, 1], [0.001, 0]]");
  if (absorbing)
    text += "[[absorbing]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n";
  const core::Scene scene = core::parse_scene(text, "column.toml");
  FeSolver solver(scene);
  // The plan says what the nodal update does: the 25 top nodes follow the curve along z, and
  // the 25 bottom nodes carry the dashpots.
  const std::string plan = solver.plan().describe();
  EXPECT_NE(plan.find("25 node components following a curve"), std::string::npos) << plan;
  EXPECT_EQ(plan.find("absorbing boundary on 25 nodes") != std::string::npos, absorbing) << plan;
  const FeNodes& nodes = solver.nodes();
  std::size_t probe = 0;
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (core::norm(nodes.position[n] - Vec3{0.5, 0.5, 10.0}) <
        core::norm(nodes.position[probe] - Vec3{0.5, 0.5, 10.0}))
      probe = n;
  const core::Energies e0 = solver.energies();
  Echo r;
  double work_in = 0.0;
  while (solver.time() < 9.0e-3) {
    solver.step(std::min(solver.stable_time_step(), 9.0e-3 - solver.time()));
    const double v = std::abs(nodes.velocity[probe].z);
    (solver.time() < 3.4e-3 ? r.incident : r.reflected) =
        std::max(solver.time() < 3.4e-3 ? r.incident : r.reflected, v);
    if (solver.time() < 1.0e-3) work_in = solver.energies().external_work;
  }
  const core::Energies e = solver.energies();
  r.balance = (e.total() - e0.total() - e.external_work) / work_in;
  r.left = (e.total() - e0.total() - (e.viscous - e0.viscous)) / work_in;
  std::printf(
      "column, bottom %s: incident %.3f m/s, echo %.3f m/s (%.1f %%); of the work put "
      "in, %.3g left in the column besides the bulk viscosity's heat (%.3g); balance "
      "%.1e\n",
      absorbing ? "absorbing" : "free", r.incident, r.reflected, 100.0 * r.reflected / r.incident,
      r.left, (e.viscous - e0.viscous) / work_in, r.balance);
  return r;
}

// Reference: the viscous boundary takes a plane wave at normal incidence without reflection
// (Lysmer & Kuhlemeyer 1969), a free end reflects all of it (the velocity doubles there and
// returns at the incident amplitude). Pass: the echo below 5 % of the incident pulse against
// over 90 % from the free end; with the boundary the pulse's energy leaves the column (under
// 1 % left besides the bulk viscosity's heat), and the balance with the dashpots' work booked
// as external work closes within 1 %.
TEST(FeAbsorbing, APlaneWaveLeavesThroughAnAbsorbingBoundaryWithoutEcho) {
  const Echo free_end = run_column(false);
  const Echo absorbed = run_column(true);
  EXPECT_GT(free_end.reflected, 0.9 * free_end.incident);
  EXPECT_LT(absorbed.reflected, 0.05 * absorbed.incident);
  EXPECT_NEAR(absorbed.incident, free_end.incident, 1e-9);
  EXPECT_LT(absorbed.left, 0.01);
  EXPECT_LT(std::abs(absorbed.balance), 0.01);
}

// Reference: the scene rules of [[absorbing]]: a body that is not of hexahedra, and a selector
// that holds no boundary face, are input errors naming the key and what is allowed.
TEST(FeAbsorbing, BoundariesOnWhatHasNoFacesAreErrors) {
  const std::string head =
      "[run]\nend_time = 1.0\n[grid]\ncell = 1.0\nmin = [0, 0, 0]\nmax = [4, 4, 4]\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 2e5\nnu = 0.3\n"
      "[[bodies]]\nname = \"cube\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }\nmesh = { divisions = [2, 2, 2] }\n"
      "[[bodies]]\nname = \"grains\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [2, 2, 2], max = [3, 3, 3] } }\n";
  auto error_of = [&](const std::string& absorbing) -> std::string {
    try {
      const core::Scene scene = core::parse_scene(head + absorbing, "bad.toml");
      core::check_scene(scene);
      FeSolver solver(scene);
    } catch (const core::InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string particles = error_of(
      "[[absorbing]]\nnodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }\n"
      "body = \"grains\"\n");
  EXPECT_NE(particles.find("bad.toml:"), std::string::npos) << particles;
  EXPECT_NE(particles.find("absorbing"), std::string::npos) << particles;
  EXPECT_NE(particles.find("made of particles"), std::string::npos) << particles;
  // A plane through the cube's middle holds nodes but no boundary face.
  const std::string inner =
      error_of("[[absorbing]]\nnodes = { plane = { point = [0, 0, 0.5], normal = [0, 0, 1] } }\n");
  EXPECT_NE(inner.find("no boundary face"), std::string::npos) << inner;
}

}  // namespace
}  // namespace afemp::fem
