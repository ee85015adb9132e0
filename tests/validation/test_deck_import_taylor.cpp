// Imported decks run as the scenes they stand for (label `validation`): the Taylor bar of
// Ma 2005, §2.3.2 (OFHC copper at 190 m/s, quarter model, to 72 us) written as an MPM3D-F90
// deck and as an LS-DYNA keyword deck, imported with afemp::import_deck and run, against
// examples/taylor_bar/mpm.toml and fe.toml at the same resolution and time-step factor.
// Each prints L, D, W of both runs. References and tolerances: the example's L, D, W within 1 %
// (MPM3D deck) and 0.5 % (LS-DYNA deck). Measured (2 threads, 2-core Intel Xeon VM):
//   MPM3D deck   L 16.479 D 13.539 W 10.304 against 16.482 13.624 10.286 (0.02, 0.62, 0.17 %)
//   LS-DYNA deck L 16.314 D 13.497 W 10.146 against 16.299 13.478 10.138 (0.09, 0.14, 0.08 %)
// The MPM3D deck's anvil is a symmetric face (MPM3D's z0 = 2), the example's a wall the bar may
// leave; the LS-DYNA deck has a Gruneisen EOS, fe.toml none.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "afemp/deck_import.hpp"
#include "analysis/reference_checks.hpp"
#include "analysis/taylor_metrics.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "coupling/make_model.hpp"
#include "fem/mesh_generation.hpp"
#include "scratch_dir.hpp"

namespace afemp::test {
namespace {

constexpr double kRadius = 3.8, kLength = 25.4, kSpeed = 190.0, kDensity = 8.93e-3;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs the scene and measures body 0 as the flat-ended cylinder it was made from (an imported
// body is a point list or a mesh file; `mesh_size` is the element length of a meshed bar).
core::TaylorMeasures run_and_measure(const core::Scene& scene, const char* label,
                                     double mesh_size) {
  const std::unique_ptr<core::Model> model = coupling::make_model(scene);
  const core::RunSummary s = analysis::run(*model, scene, {});
  core::Scene bar = scene;
  bar.bodies[0].shape = core::CylinderShape{{0, 0, 0}, {0, 0, 1}, kRadius, kLength, {}};
  bar.bodies[0].mesh.size = mesh_size;
  const core::BodyPoints points = model->body_points(0);
  const core::TaylorMeasures m =
      analysis::measure_taylor(bar, 0, points.position, points.half_size);
  std::printf("| %s | %.3f | %.3f | %.3f | %ld | %.2g | %.1f | %d |\n", label, m.length,
              m.impact_diameter, m.bulge_diameter, s.steps, s.min_dt, s.wall_seconds,
              core::thread_count());
  std::fflush(stdout);
  return m;
}

void expect_close(const core::TaylorMeasures& a, const core::TaylorMeasures& b, double tol) {
  const auto rel = [](double x, double y) { return std::abs(x - y) / y; };
  std::printf("relative differences: L %.4f %%, D %.4f %%, W %.4f %% (allowed %.2g %%)\n",
              100 * rel(a.length, b.length), 100 * rel(a.impact_diameter, b.impact_diameter),
              100 * rel(a.bulge_diameter, b.bulge_diameter), 100 * tol);
  EXPECT_LE(rel(a.length, b.length), tol);
  EXPECT_LE(rel(a.impact_diameter, b.impact_diameter), tol);
  EXPECT_LE(rel(a.bulge_diameter, b.bulge_diameter), tol);
}

core::Scene import_and_read(const ScratchDir& dir, const std::string& deck_name,
                            const std::string& deck) {
  const std::string deck_path = (dir.path() / deck_name).string();
  const std::string scene_path = (dir.path() / "imported.toml").string();
  std::ofstream(deck_path) << deck;
  const core::DeckImport imported = core::import_deck(deck_path, scene_path);
  core::write_deck_import(imported, scene_path);
  for (const core::DeckNote& n : imported.notes)
    std::printf("note: %s\n", core::describe(n).c_str());
  return core::read_scene(scene_path);
}

// The quarter bar as MPM3D-F90 writes it: a point list "id material mass x y z" of the lattice
// mpm.toml's cylinder makes (cell 0.5, 2 particles per cell per direction, centres at
// (j + 1/2) h / 2), seed 001's copper (sjc: density, E, nu, A, B, n, C, epso), MUSL, the
// default time-step factor 0.3 of afemp's scene, symmetric faces x0, y0 and z0 (MPM3D's wall).
std::string mpm3d_taylor_deck() {
  const double spacing = 0.25, mass = kDensity * spacing * spacing * spacing;
  std::string points;
  long n = 0;
  char line[160];
  for (int k = 0; (k + 0.5) * spacing < kLength; ++k)
    for (int j = 0; (j + 0.5) * spacing <= kRadius; ++j)
      for (int i = 0; (i + 0.5) * spacing <= kRadius; ++i) {
        const double x = (i + 0.5) * spacing, y = (j + 0.5) * spacing, z = (k + 0.5) * spacing;
        if (std::hypot(x, y) > kRadius) continue;
        std::snprintf(line, sizeof line, " %ld 1 %.9e %.6f %.6f %.6f\n", ++n, mass, x, y, z);
        points += line;
      }
  return "mpm3d *** Taylor bar, OFHC copper, 190 m/s (Ma 2005, 2.3.2), quarter\n"
         "! Unit: mm g N ms MPa\n"
         "nbco 1\nnbbo 1\nnbmp " +
         std::to_string(n) +
         "\nnmat 1\n"
         "spx 0.0 10.0\nspy 0.0 10.0\nspz 0.0 26.0\ndcell 0.5\n"
         "musl on\njaum on\ndtscale 0.3\nendtime 0.072\nouttime 0.008\n"
         "!      x0  xn  y0  yn  z0  zn\nfixed  2   0   2   0   2   0\n"
         "material\n"
         "!  num mtype density young's Poisson A B n C epso\n"
         "    1  sjc  8.93d-3 117.0d3 0.35 157.0 425.0 1.0 0.0 1e-3\n"
         "particle point 1 " +
         std::to_string(n) + "\n" + points + "velo\nbody 1 0.0 0.0 -190.0\nendv\nendi\n";
}

// The quarter O-grid of fe.toml (elements of 0.25 mm: the divisions fem's builder picks for
// `size = 0.25, sectors = 1`) as an LS-DYNA deck: *MAT_JOHNSON_COOK with *EOS_GRUNEISEN
// (copper: c0 3940 m/s, S1 1.49, Gamma0 1.96), ELFORM 1, symmetry by *BOUNDARY_SPC_SET on the
// cut planes, *RIGIDWALL_PLANAR at z = 0, *INITIAL_VELOCITY_GENERATION of the part.
std::string lsdyna_taylor_deck() {
  const core::CylinderShape bar{{0, 0, 0}, {0, 0, 1}, kRadius, kLength, {}};
  const fem::MeshData mesh = fem::cylinder_mesh(bar, 24, 8, 102, 1);
  std::string s =
      "*KEYWORD\n*TITLE\nTaylor bar, OFHC copper, 190 m/s, LS-DYNA deck\n"
      "$ units: mm, ms, g, N, MPa\n"
      "*CONTROL_TERMINATION\n$ ENDTIM\n0.072\n"
      "*CONTROL_TIMESTEP\n$ DTINIT TSSFAC\n0.0,0.9\n"
      "*DATABASE_BINARY_D3PLOT\n0.008\n"
      "*PART\nbar\n$ PID SECID MID EOSID\n1,1,1,1\n"
      "*SECTION_SOLID\n$ SECID ELFORM\n1,1\n"
      "*MAT_JOHNSON_COOK\n"
      "$ MID RO G E PR\n1,8.93e-3,43333.33,117000.0,0.35\n"
      "$ A B N C M TM TR EPSO\n157.0,425.0,1.0,0.0,0.0,1356.0,293.0,1.0e-3\n"
      "$ CP PC SPALL IT D1 D2 D3 D4\n0.0\n"
      "*EOS_GRUNEISEN\n$ EOSID C S1 S2 S3 GAMAO A E0\n1,3940.0,1.49,0.0,0.0,1.96,0.0,0.0\n"
      "*INITIAL_VELOCITY_GENERATION\n$ ID STYP OMEGA VX VY VZ\n1,2,0.0,0.0,0.0,-190.0\n"
      "0.0,0.0,0.0,0.0,0.0,0.0\n"
      "*RIGIDWALL_PLANAR\n0\n$ XT YT ZT XH YH ZH\n0.0,0.0,0.0,0.0,0.0,1.0\n";
  char line[200];
  for (int axis = 0; axis < 2; ++axis) {
    s += "*SET_NODE_LIST\n" + std::to_string(axis + 1) + "\n";
    int on_card = 0;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
      if (std::abs(mesh.nodes[i][axis]) < 1e-6) {
        s += std::to_string(i + 1) + (++on_card % 8 == 0 ? "\n" : ",");
      }
    if (s.back() == ',') s.back() = '\n';
  }
  s += "*BOUNDARY_SPC_SET\n$ NSID CID DOFX DOFY DOFZ\n1,0,1,0,0\n2,0,0,1,0\n*NODE\n";
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    std::snprintf(line, sizeof line, "%zu,%.17g,%.17g,%.17g\n", i + 1, mesh.nodes[i].x,
                  mesh.nodes[i].y, mesh.nodes[i].z);
    s += line;
  }
  s += "*ELEMENT_SOLID\n";
  for (std::size_t e = 0; e < mesh.hexahedra.size(); ++e) {
    s += std::to_string(e + 1) + ",1";
    for (const std::int32_t n : mesh.hexahedra[e]) {
      s += ',';  // not "," + string: GCC 12 warns falsely (-Wrestrict) on that concatenation
      s += std::to_string(n + 1);
    }
    s += "\n";
  }
  return s + "*END\n";
}

void print_header() {
  std::printf(
      "| run | L | D | W | steps | smallest dt | wall s | threads "
      "|\n|---|---|---|---|---|---|---|---|\n");
}

TEST(DeckImportTaylorBar, Mpm3dDeckRunsToTheMpmExampleWithinOnePercent) {
  ScratchDir dir;
  const core::Scene imported = import_and_read(dir, "taylor.mpm", mpm3d_taylor_deck());
  const std::string example = std::string(AFEMP_SOURCE_DIR) + "/examples/taylor_bar/mpm.toml";
  const core::Scene reference = core::parse_scene(read_file(example), example);
  ASSERT_EQ(imported.bodies.size(), 1u);
  print_header();
  const core::TaylorMeasures a = run_and_measure(imported, "MPM3D-F90 deck, imported", 0.0);
  const core::TaylorMeasures b = run_and_measure(reference, "examples/taylor_bar/mpm.toml", 0.0);
  expect_close(a, b, 0.01);
}

TEST(DeckImportTaylorBar, LsDynaDeckRunsToTheFeExampleWithinHalfAPercent) {
  ScratchDir dir;
  const core::Scene imported = import_and_read(dir, "taylor.k", lsdyna_taylor_deck());
  const std::string example = std::string(AFEMP_SOURCE_DIR) + "/examples/taylor_bar/fe.toml";
  const core::Scene reference = core::parse_scene(read_file(example), example);
  ASSERT_EQ(imported.bodies.size(), 1u);
  print_header();
  const core::TaylorMeasures a = run_and_measure(imported, "LS-DYNA deck, imported", 0.25);
  const core::TaylorMeasures b = run_and_measure(reference, "examples/taylor_bar/fe.toml", 0.25);
  expect_close(a, b, 0.005);
}

}  // namespace
}  // namespace afemp::test
