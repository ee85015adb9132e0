// MPM3D decks into scenes (mpm/mpm3d_deck_import.cpp): keyword by keyword into the scene's
// fields (reference: MPM3D-F90's DataIn.f90, the deck's meaning; Ma 2005, appendix A), the
// generators' particles, unit conversion, the list of what is not translated, and errors that
// name the file, the line and the keyword.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <variant>

#include "afemp/deck_import.hpp"
#include "core/scene.hpp"
#include "mpm/mpm3d_deck_import.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace afemp::mpm {
namespace {

// A sphere (nR = 2 spacings of 0.5 mm) of steel at 1000 m/s onto a block (4 x 4 x 2 particles)
// of copper with a Grueneisen EOS, MUSL, gravity, contact, output options.
const std::string kDeck =
    "mpm3d *** sphere onto a plate\n"                                          // 1
    "nbco 2\nnbbo 2\n"                                                         // 2-3
    "nbmp 64\n"                                                                // 4
    "nmat 2\n"                                                                 // 5
    "spx -4 4\nspy -4 4\nspz -4 6\ndcell 1.0\n"                                // 6-9
    "dtscale 0.5\nendtime 0.01\nouttime 0.002\n"                               // 10-12
    "musl on\njaum off\n"                                                      // 13-14
    "fixed 0 0 0 0 1 2\n"                                                      // 15
    "outr seqv\n"                                                              // 16
    "tecp\n"                                                                   // 17
    "material\n"                                                               // 18
    " 1 john 8.93d-3 117.0d3 0.35 90 292 0.31 0.025 1.09 293 1356 383 1e-3\n"  // 19
    " 2 pla2 7.85d-3 200.0d3 0.3 500 2000\n"                                   // 20
    "seos 1 2 3940 1.49 1.96 0\n"                                              // 21
    "particle block 1 1 8.93e-3 0.5 -1 -1 -1\n 4 4 2\n"                        // 22-23
    "particle sphere 2 2 7.85e-3 0.5 0 0 2 2\n"                                // 24
    "velo\nbody 2 0 0 -1000\nendv\n"                                           // 25-27
    "load\ngrav 1 0 0 -9.81e-3\ngrav 2 0 0 -9.81e-3\nendl\n"                   // 28-31
    "contact lagr 0.2 1\n"                                                     // 32
    "deto 0 0 0\n"                                                             // 33
    "endi\n";

// The sphere generator's count for nR = 2 (DataIn.f90): lattice centres (i - 1/2) dp, i from
// 1 - nR to nR per axis, strictly inside the radius nR dp: 32 of the 64 candidates.
constexpr std::size_t kSphereParticles = 32;

struct Imported {
  core::DeckImport deck;
  core::Scene scene;
};

Imported import_text(const test::ScratchDir& dir, const std::string& deck,
                     const std::string& units = "") {
  const std::string deck_path = dir.write("deck.mpm", deck);
  const std::string scene_path = (dir.path() / "scene.toml").string();
  core::DeckImport d = core::import_deck(deck_path, scene_path, {units});
  core::write_deck_import(d, scene_path);
  return {std::move(d), core::read_scene(scene_path)};
}

// The rows "x y z volume" of a point list the importer wrote.
std::vector<std::array<double, 4>> points_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::array<double, 4>> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with('#')) continue;
    std::istringstream row(line);
    std::array<double, 4> p{};
    row >> p[0] >> p[1] >> p[2] >> p[3];
    out.push_back(p);
  }
  return out;
}

std::string error_of(const std::string& deck) {
  try {
    import_mpm3d_deck(deck, "bad.mpm", "scene.toml", {});
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

// Runs the solver at its stable step to the end time; the largest energy-balance error on the
// way, |total - initial| / initial (the initial energy all kinetic or all chemical).
double run_to_end(MpmSolver& solver, double end_time) {
  const double e0 = solver.energies().total();
  double largest = 0.0;
  while (solver.time() < end_time) {
    solver.step(solver.stable_time_step());
    largest = std::max(largest, std::abs(solver.energies().total() - e0) / e0);
  }
  return largest;
}

TEST(Mpm3dDeckImport, KeywordsBecomeTheSceneFields) {
  test::ScratchDir dir;
  const Imported im = import_text(dir, kDeck);
  const core::Scene& s = im.scene;
  EXPECT_EQ(s.run.title, "sphere onto a plate");
  EXPECT_DOUBLE_EQ(s.run.end_time, 0.01);
  EXPECT_DOUBLE_EQ(s.run.output_every, 0.002);
  EXPECT_DOUBLE_EQ(s.run.time_step_factor, 0.5);
  EXPECT_DOUBLE_EQ(s.run.gravity.z, -9.81e-3);
  EXPECT_DOUBLE_EQ(s.mpm.grid.cell, 1.0);
  EXPECT_DOUBLE_EQ(s.mpm.grid.min.z, -4.0);
  EXPECT_DOUBLE_EQ(s.mpm.grid.max.z, 6.0);
  EXPECT_EQ(s.mpm.grid.faces[4], core::FaceCondition::fixed);      // zmin: 1
  EXPECT_EQ(s.mpm.grid.faces[5], core::FaceCondition::symmetric);  // zmax: 2
  EXPECT_EQ(s.mpm.grid.faces[0], core::FaceCondition::outflow);    // 0: particles may leave
  EXPECT_EQ(s.mpm.scheme, core::UpdateScheme::MUSL);
  EXPECT_FALSE(s.mpm.jaumann);

  ASSERT_EQ(s.materials.size(), 2u);
  const core::Material& cu = s.materials[0];
  EXPECT_DOUBLE_EQ(cu.density, 8.93e-3);
  EXPECT_DOUBLE_EQ(cu.youngs_modulus, 117e3);
  EXPECT_DOUBLE_EQ(cu.poisson_ratio, 0.35);
  const auto& jc = std::get<core::JohnsonCook>(cu.strength);
  EXPECT_DOUBLE_EQ(jc.A, 90);
  EXPECT_DOUBLE_EQ(jc.B, 292);
  EXPECT_DOUBLE_EQ(jc.n, 0.31);
  EXPECT_DOUBLE_EQ(jc.C, 0.025);
  EXPECT_DOUBLE_EQ(jc.m, 1.09);
  EXPECT_DOUBLE_EQ(jc.room_temperature, 293);
  EXPECT_DOUBLE_EQ(jc.melt_temperature, 1356);
  EXPECT_DOUBLE_EQ(jc.reference_strain_rate, 1e-3);
  const auto& mg = std::get<core::MieGruneisen>(cu.eos);
  EXPECT_DOUBLE_EQ(mg.c0, 3940);
  EXPECT_DOUBLE_EQ(mg.s, 1.49);
  EXPECT_DOUBLE_EQ(mg.gamma0, 1.96);
  // pla2: Et 2000 is the tangent modulus, H = E Et / (E - Et) (as Constitution.f90's PlaMod).
  const auto& j2 = std::get<core::J2Plasticity>(s.materials[1].strength);
  EXPECT_DOUBLE_EQ(j2.yield_stress, 500);
  EXPECT_NEAR(j2.hardening, 200e3 * 2000 / (200e3 - 2000), 1e-9);

  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].material, 0);
  EXPECT_EQ(s.bodies[1].material, 1);
  EXPECT_DOUBLE_EQ(s.bodies[1].velocity.z, -1000);
  EXPECT_DOUBLE_EQ(s.bodies[0].velocity.z, 0);
  ASSERT_EQ(s.contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(s.contacts[0].friction, 0.2);
}

// Reference: DataIn.f90's generators. The block of 4 x 4 x 2 at dp 0.5 from (-1, -1, -1) puts
// particles at -1 + (i + 1/2) 0.5; the sphere's particles lie within nR dp = 1 of (0, 0, 2).
// Each particle's mass is density dp^3, so the volume written is dp^3 exactly.
TEST(Mpm3dDeckImport, GeneratorsMakeTheParticlesMpm3dMakes) {
  test::ScratchDir dir;
  const Imported im = import_text(dir, kDeck);
  EXPECT_EQ(std::get<core::PointListShape>(im.scene.bodies[1].shape).path,
            dir.file("scene.body2.txt"));
  const std::vector<std::array<double, 4>> block = points_of(dir.file("scene.body1.txt"));
  const std::vector<std::array<double, 4>> sphere = points_of(dir.file("scene.body2.txt"));
  ASSERT_EQ(block.size(), 32u);
  ASSERT_EQ(sphere.size(), kSphereParticles);
  EXPECT_DOUBLE_EQ(block.front()[0], -0.75);
  EXPECT_DOUBLE_EQ(block.back()[0], 0.75);
  EXPECT_DOUBLE_EQ(block.back()[2], -0.25);
  for (const auto& p : sphere) {
    EXPECT_LT(p[0] * p[0] + p[1] * p[1] + (p[2] - 2.0) * (p[2] - 2.0), 1.0);
    EXPECT_NEAR(p[3], 0.125, 1e-12);
  }
}

TEST(Mpm3dDeckImport, WhatIsNotTranslatedIsListedWithItsLineAndInTheScene) {
  test::ScratchDir dir;
  const Imported im = import_text(dir, kDeck);
  std::vector<std::string> listed;
  for (const core::DeckNote& n : im.deck.notes)
    if (!n.approximated) listed.push_back(n.keyword + ":" + std::to_string(n.at.line));
  EXPECT_EQ(listed, (std::vector<std::string>{"outr:16", "tecp:17", "deto:33"}));
  EXPECT_NE(im.deck.scene.find("deck.mpm:33: deto: not translated"), std::string::npos)
      << im.deck.scene;
  EXPECT_NE(im.deck.scene.find("# Units: the deck's own"), std::string::npos);
  bool contact_noted = false;
  for (const core::DeckNote& n : im.deck.notes)
    contact_noted = contact_noted || (n.approximated && n.keyword == "contact" && n.at.line == 32);
  EXPECT_TRUE(contact_noted);
}

// Reference: issue 47, a deck runs as it means or is refused. A particle's own velocity (velo
// node), a force on a body (load body) and damping change the run: the import stops at the
// file, line and keyword unless allowed, and then the scene's [run] untranslated carries them.
// A scheme switch (bimp: B-spline MPM) changes the discretisation, not the physics: noted as
// approximated, the deck imports with afemp's quadratic B-spline.
TEST(Mpm3dDeckImport, UntranslatedInitialConditionsAndLoadsAreRefusedUnlessAllowed) {
  std::string deck = kDeck;
  deck.replace(deck.find("body 2 0 0 -1000\n"), 17, "body 2 0 0 -1000\nnode 3 0 0 -10\n");
  // line 27: node 3 ...; the load block moves down a line
  std::string e = error_of(deck);
  EXPECT_NE(e.find("bad.mpm:27:"), std::string::npos) << e;
  EXPECT_NE(e.find("velo"), std::string::npos) << e;
  EXPECT_NE(e.find("--allow-untranslated"), std::string::npos) << e;
  std::string loaded = kDeck;
  loaded.replace(loaded.find("endl\n"), 5, "body 1 0 0 5\nendl\n");  // line 31
  e = error_of(loaded);
  EXPECT_NE(e.find("bad.mpm:31:"), std::string::npos) << e;
  e = error_of(std::string(kDeck).replace(kDeck.find("endi"), 4, "damp 0.05\nendi"));
  EXPECT_NE(e.find("bad.mpm:34:"), std::string::npos) << e;

  test::ScratchDir dir;
  const std::string deck_path = dir.write("deck.mpm", deck);
  const std::string scene_path = (dir.path() / "scene.toml").string();
  core::DeckImportOptions options;
  options.allow_untranslated = true;
  const core::DeckImport d = core::import_deck(deck_path, scene_path, options);
  core::write_deck_import(d, scene_path);
  const core::Scene s = core::read_scene(scene_path);
  ASSERT_EQ(s.run.untranslated.size(), 1u);
  EXPECT_NE(s.run.untranslated[0].find(":27: velo: not translated, the run differs"),
            std::string::npos)
      << s.run.untranslated[0];

  const Imported im =
      import_text(dir, std::string(kDeck).replace(kDeck.find("endi"), 4, "bimp\nendi"));
  bool noted = false;
  for (const core::DeckNote& n : im.deck.notes)
    noted = noted || (n.keyword == "bimp" && n.approximated && n.at.line == 34);
  EXPECT_TRUE(noted);
  EXPECT_TRUE(im.scene.run.untranslated.empty());
  EXPECT_EQ(im.scene.mpm.shape, core::ShapeFunction::bspline2);
}

// Reference: 1 kg/m^3 = 1e-6 g/mm^3, 1 Pa = 1e-6 MPa, 1 m = 1000 mm, 1 s = 1000 ms, so the
// SI deck's numbers become the mm-ms-g deck's.
TEST(Mpm3dDeckImport, SiDeckIsConvertedIntoMillimetresMilliseconds) {
  test::ScratchDir dir;
  const std::string si =
      "mpm3d *** SI\nnbmp 8\nnmat 1\nspx 0 0.004\nspy 0 0.004\nspz 0 0.004\ndcell 0.001\n"
      "endtime 1e-5\nmaterial\n 1 pla1 8930 117e9 0.35 240e6\n"
      "particle block 1 1 8930 0.001 0.001 0.001 0.001 2 2 2\nvelo\nbody 1 0 0 -200\nendv\nload\n"
      "grav 1 0 0 -9.81\nendl\nendi\n";
  const Imported im = import_text(dir, si, "m-s-kg");
  const core::Scene& s = im.scene;
  EXPECT_NEAR(s.materials[0].density, 8.93e-3, 1e-15);
  EXPECT_NEAR(s.materials[0].youngs_modulus, 117e3, 1e-9);
  EXPECT_NEAR(std::get<core::J2Plasticity>(s.materials[0].strength).yield_stress, 240, 1e-12);
  EXPECT_NEAR(s.run.end_time, 0.01, 1e-15);
  EXPECT_NEAR(s.mpm.grid.cell, 1.0, 1e-12);
  EXPECT_NEAR(s.bodies[0].velocity.z, -200, 1e-12);
  EXPECT_NEAR(s.run.gravity.z, -9.81e-3, 1e-15);
  const auto p = points_of(dir.file("scene.body1.txt"));
  EXPECT_NEAR(p[0][0], 1.5, 1e-12);
  EXPECT_NEAR(p[0][3], 1.0, 1e-9);
  EXPECT_NE(im.deck.scene.find("m, s, kg, N, Pa"), std::string::npos);
  // The converted scene states its units, so that its plausibility is checked in them.
  EXPECT_EQ(s.run.units, "mm-ms-g");
}

// MPM3D (2005, appendix A): a particle table "id material component x y z" of volume
// dcell^3 / ppc, velocities by component, seos type 1 with c0, lambda, gamma0, dt and tstep.
TEST(Mpm3dDeckImport, ThesisFormatDeckIsRead) {
  test::ScratchDir dir;
  const std::string deck =
      "mpm3d *** test\nppc 8\nnbmp 2\nnmat 1\nncomp 2\nspx 0 4\nspy 0 4\nspz 0 4\ndcell 1.0\n"
      "dt 1.0d-4\ntstep 400\nostep 4\njaum on\ncont on\nfixed 2 0 2 0 2 0\n"
      "material\n 1 john 8.9d-3 100.0d3 0.3d0 90 392 0.5 0.0\nseos 1 1 3.3d3 1.49 1.96\n"
      "particle\n 1 1 1 0.25 0.25 0.25\n 2 1 2 0.75 0.25 2.25\n"
      "velo\n comp 1 0 0 200\nendv\nendi\n";
  const Imported im = import_text(dir, deck);
  const core::Scene& s = im.scene;
  EXPECT_DOUBLE_EQ(s.run.fixed_time_step, 1e-4);
  EXPECT_DOUBLE_EQ(s.run.end_time, 0.04);
  EXPECT_DOUBLE_EQ(s.run.output_every, 4e-4);
  // MPM3D's default USL, which afemp's contact refuses: MUSL, with a note.
  EXPECT_EQ(s.mpm.scheme, core::UpdateScheme::MUSL);
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_DOUBLE_EQ(s.bodies[0].velocity.z, 200);
  EXPECT_DOUBLE_EQ(points_of(dir.file("scene.body1.txt"))[0][3], 0.125);
  EXPECT_DOUBLE_EQ(std::get<core::MieGruneisen>(s.materials[0].eos).c0, 3300);
  EXPECT_EQ(s.contacts.size(), 1u);
  ASSERT_EQ(im.deck.notes.size(), 1u);
  EXPECT_EQ(im.deck.notes[0].keyword, "contact");
  EXPECT_TRUE(im.deck.notes[0].approximated);
}

TEST(Mpm3dDeckImport, ErrorsNameFileLineKeywordAndWhatIsAllowed) {
  std::string e = error_of("mpm3d *** x\nnbmp 1\nspx 0 1\nfoo 3\n");
  EXPECT_NE(e.find("bad.mpm:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("'foo'"), std::string::npos) << e;
  EXPECT_NE(e.find("known: mpm3d"), std::string::npos) << e;

  e = error_of("nbmp 1\nnmat 1\nmaterial\n 1 rubr 1.6e-3 6.9 0.3\n");
  EXPECT_NE(e.find("bad.mpm:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("'rubr'"), std::string::npos) << e;
  EXPECT_NE(e.find("no afemp counterpart"), std::string::npos) << e;
  EXPECT_NE(e.find("translated: elas, pla1"), std::string::npos) << e;

  // A JWL belongs to an explosive, and an explosive needs one and a detonation point.
  e = error_of("nbmp 1\nnmat 1\nmaterial\n 1 hiex 1.63e-3 6930\nseos 1 2 3940 1.49 1.96 0\n");
  EXPECT_NE(e.find("bad.mpm:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("hiex with 3 (JWL"), std::string::npos) << e;
  e = error_of(
      "nbmp 1\nnmat 1\nendtime 1\nspx 0 1\nspy 0 1\nspz 0 1\ndcell 0.5\nmaterial\n"
      " 1 hiex 1.63e-3 6930\nparticle block 1 1 1.63e-3 0.5 0 0 0 1 1 1\n");
  EXPECT_NE(e.find("bad.mpm:9:"), std::string::npos) << e;
  EXPECT_NE(e.find("seos 1 3 A B R1 R2 omega E0"), std::string::npos) << e;
  e = error_of(
      "nbmp 1\nnmat 1\nendtime 1\nspx 0 1\nspy 0 1\nspz 0 1\ndcell 0.5\nmaterial\n"
      " 1 hiex 1.63e-3 6930\nseos 1 3 3.712e5 3.21e3 4.15 0.95 0.3 6993\n"
      "particle block 1 1 1.63e-3 0.5 0 0 0 1 1 1\n");
  EXPECT_NE(e.find("no detonation point"), std::string::npos) << e;

  e = error_of("nbmp 1\nnmat 1\nmaterial\n 1 sjc 8.93e-3 117e3 0.35 157\n");
  EXPECT_NE(e.find("bad.mpm:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("found 4 values"), std::string::npos) << e;

  e = error_of(
      "nbmp 1\nnmat 1\nmaterial\n 1 elas 8.93e-3 117e3 0.35\ndcell 0.5\n"
      "particle block 1 1 8.93e-3 0.5 0 0 0 2 1 1\n");
  EXPECT_NE(e.find("nbmp is 1 but the particle sets make 2"), std::string::npos) << e;

  e = error_of("nbmp 1\nnmat 1\nmaterial\n 1 elas 8.93e-3 117e3 x.35\n");
  EXPECT_NE(e.find("bad.mpm:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("'x.35'"), std::string::npos) << e;

  e = error_of("nbmp 1\nnmat 1\nmaterial\n 1 elas 8.93e-3 117e3 0.35\nseos 1 3 1 2 3 4 5 6\n");
  EXPECT_NE(e.find("bad.mpm:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("JWL"), std::string::npos) << e;
}

// `afemp check` and `afemp run` given a deck say to import it; `afemp import` writes the scene
// and lists what it left out.
TEST(Mpm3dDeckImport, CommandRefusesToRunADeckAndImportsIt) {
  test::ScratchDir dir;
  const std::string deck = dir.write("deck.mpm", kDeck);
  for (const char* cmd : {"check", "run"}) {
    const test::CommandResult r = test::run_afemp(std::string(cmd) + " \"" + deck + "\"", dir);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(
        r.err.find("this is an MPM3D deck, not a scene; import it with `afemp import " + deck),
        std::string::npos)
        << r.err;
  }
  const std::string scene = dir.file("scene.toml");
  const test::CommandResult r =
      test::run_afemp("import \"" + deck + "\" -o \"" + scene + "\"", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(deck + ":33: deto: not translated"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "scene.body2.txt"));
  const test::CommandResult check = test::run_afemp("check \"" + scene + "\"", dir);
  EXPECT_EQ(check.exit_code, 0) << check.err;
}

// A detonation deck in MPM3D-F90's form (its Data/Deto1k.mpm, shortened: a 20 mm column of
// TNT lit at x = 0, symmetric faces around it) imports to a JWL explosive with programmed burn
// and runs. References: TNT at 1.63 g/cm^3 detonates at D = 6.93 km/s with a Chapman-Jouguet
// pressure of 21.0 GPa (Dobratz & Crawford, LLNL Explosives Handbook, 1985); the importer's
// pcj, the JWL's own CJ point, within 1 % of it. The run: the front reaches x = 10 mm at
// 10 / D (every particle lights at its distance over D), and the pressure behind it rises to
// the CJ state and falls in the Taylor wave: the largest pressure at the particle nearest
// x = 10 mm within 15 % of pcj (the burn spreads the front over 1.5 cells of 0.2 mm, which
// caps the spike: measured 18,330 MPa, -12.6 %), reached within 0.3 us of the front's
// arrival, and energy neither made nor lost beyond 2 % of the chemical energy (0.94 %).
TEST(Mpm3dDeckImport, DetonationDeckBurnsToTheJwlsChapmanJouguetPressure) {
  test::ScratchDir dir;
  const Imported im =
      import_text(dir,
                  "mpm3d *** 1D TNT\n! Unit: mm  g  N  ms  MPa\nnbco 1\nnbbo 1\nnbmp 800\nnmat 1\n"
                  "spx 0.0 20.0\nspy 0.0 0.2\nspz 0.0 0.2\ndcell 0.2\ndtscale 0.1\nendtime 0.0022\n"
                  "outtime 1.0d-3\nmusl on\njaum on\nbulk 1.5 0.06\nfixed 2 0 2 2 2 2\n"
                  "material\n 1 hiex 1.63d-3 6930\n"
                  "seos 1 3 3.712d5 3.21d3 4.15 0.95 0.3 6993\n"
                  "deto 0 0 0\n"
                  "Particle block 1\n 1 1.63d-3 0.1 0 0 0 200 2 2\nendi\n");
  const core::Scene& scene = im.scene;
  ASSERT_EQ(scene.materials.size(), 1u);
  const core::Material& tnt = scene.materials[0];
  ASSERT_TRUE(tnt.burn.has_value());
  const double pcj = tnt.burn->cj_pressure;
  std::printf("imported: D %.1f m/s, pcj %.1f MPa (published 21000)\n",
              tnt.burn->detonation_velocity, pcj);
  EXPECT_DOUBLE_EQ(tnt.burn->detonation_velocity, 6930.0);
  EXPECT_NEAR(pcj, 21000.0, 0.01 * 21000.0);
  ASSERT_EQ(scene.detonations.size(), 1u);

  MpmSolver solver(scene, generate_particles(scene));
  const Particles& p = solver.particles();
  std::size_t gauge = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(p.position[i].x - 10.0) < std::abs(p.position[gauge].x - 10.0)) gauge = i;
  const double x0 = p.position[gauge].x;
  const Energies e0 = solver.energies();
  const double chemical = e0.internal;
  double peak = 0.0, peak_time = 0.0, largest_error = 0.0;
  while (solver.time() < scene.run.end_time) {
    solver.step(solver.stable_time_step());
    const double pressure = -p.stress[gauge].trace() / 3.0;
    if (pressure > peak) {
      peak = pressure;
      peak_time = solver.time();
    }
    const Energies e = solver.energies();
    largest_error = std::max(largest_error, std::abs(e.kinetic + e.internal - chemical) / chemical);
  }
  const double arrival = x0 / 6930.0;
  std::printf(
      "gauge at x = %.3f mm: peak %.0f MPa at %.5f ms (front due %.5f ms); largest "
      "energy error %.3f %%\n",
      x0, peak, peak_time, arrival, 100.0 * largest_error);
  EXPECT_NEAR(peak, pcj, 0.15 * pcj);
  EXPECT_GT(peak_time, arrival);
  EXPECT_LT(peak_time, arrival + 0.0003);
  EXPECT_LT(largest_error, 0.02);
}

// A null material (MPM3D-F90's water: density, bulk modulus, viscosity) with its weakly
// compressible EOS: afemp's fluid with p = K mu, K the deck's bulk modulus, since MPM3D-F90
// runs the EOS with c = sqrt(K / density) whatever c the seos gives (DataIn.f90's Initial);
// both are noted, the viscosity as left out. Reference: the deck format's meaning, exactly.
// A null material with a Grueneisen seos is refused (MPM3D-F90 overwrites its first constant).
TEST(Mpm3dDeckImport, NullMaterialIsAFluidWithTheBulkModulusMpm3dRunsWith) {
  test::ScratchDir dir;
  const std::string deck =
      "mpm3d *** water block\nnbco 1\nnbbo 1\nnbmp 8\nnmat 1\nspx 0 2\nspy 0 2\nspz 0 2\n"
      "dcell 1\nendtime 0.01\nmaterial\n 1 null 1.0d-3 2.2d3 1.0d-6\nseos 1 4 35.0\n"
      "particle block 1 1 1.0d-3 0.5 0 0 0 2 2 2\nendi\n";
  const Imported im = import_text(dir, deck);
  ASSERT_EQ(im.scene.materials.size(), 1u);
  const core::Material& water = im.scene.materials[0];
  EXPECT_TRUE(std::holds_alternative<core::Fluid>(water.strength));
  ASSERT_TRUE(std::holds_alternative<core::LinearEos>(water.eos));
  EXPECT_DOUBLE_EQ(std::get<core::LinearEos>(water.eos).bulk_modulus, 2.2e3);
  int approximated = 0;
  for (const core::DeckNote& n : im.deck.notes)
    approximated += n.approximated && n.what.find("(null)") != std::string::npos;
  EXPECT_EQ(approximated, 2);  // the viscosity, and the c of the seos

  std::string e =
      error_of("nbmp 1\nnmat 1\nmaterial\n 1 null 1.0d-3 2.2d3 0\nseos 1 2 1480 1.9 0.1 0\n");
  EXPECT_NE(e.find("bad.mpm:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("null with 4"), std::string::npos) << e;
}

// The hypervelocity deck kind of MPM3D-F90's Data/ (its LeadHypervelocityImpact.mpm's form,
// written here small: a lead sphere of `sjcf` Johnson-Cook with failure and a Grueneisen
// `seos`, generated by `particle sphere`, at 6580 m/s into a lead plate of `particle block`, free
// faces all round) imports and runs. References: the grid conserves momentum exactly (no face
// is reached in 0.6 us: none leaves), so the x-momentum stays m_sphere v0 to 1e-10 relative, and
// the energy balance (the bulk-viscous and plastic heat booked) closes within 3 %.
TEST(Mpm3dDeckImport, HypervelocityDeckKindConservesMomentumAndEnergy) {
  test::ScratchDir dir;
  const Imported im = import_text(
      dir,
      "mpm3d *** lead sphere on lead plate\n! Unit: mm g N ms MPa\nnbco 2\nnbbo 2\nnbmp 1160\n"
      "nmat 1\nspx -4 8\nspy -6 6\nspz -6 6\ndcell 1.0\nfixed 0 0 0 0 0 0\ndtscale 0.1\n"
      "endtime 0.0006\nouttime 0.0002\nmusl on\njaum on\nmaterial\n"
      " 1 sjcf 11.350d-3 22.4d3 0.42d0 12.0 125.0 1.0 0.0 1e-3 3.0\n"
      "seos 1 2 2.092d3 1.45 2.0 0\n"
      "Particle sphere 1\n 1 11.35d-3 0.5 -2.0 0 0 3\n"
      "Particle block 2\n 1 11.35d-3 0.5 0 -4 -4 4 16 16\n"
      "velo\nbody 1 6580.0 0.0 0.0\nendv\nendi\n");
  const core::Scene& scene = im.scene;
  ASSERT_EQ(scene.bodies.size(), 2u);
  MpmSolver solver(scene, generate_particles(scene));
  const Particles& p = solver.particles();
  const auto momentum_x = [&] {
    double m = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) m += p.mass[i] * p.velocity[i].x;
    return m;
  };
  const double p0 = momentum_x();
  const double largest_error = run_to_end(solver, scene.run.end_time);
  double plate_x = 0.0, plate_mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == 1) plate_x += p.mass[i] * p.velocity[i].x, plate_mass += p.mass[i];
  std::printf(
      "%zu particles, %ld left; x-momentum %.6e -> %.6e (relative %.2e); plate's mean "
      "velocity %.0f m/s; largest energy error %.3f %%\n",
      p.size(), solver.outflow_count(), p0, momentum_x(), std::abs(momentum_x() - p0) / p0,
      plate_x / plate_mass, 100.0 * largest_error);
  EXPECT_EQ(solver.outflow_count(), 0);
  EXPECT_NEAR(momentum_x(), p0, 1e-10 * std::abs(p0));
  EXPECT_GT(plate_x / plate_mass, 0.0);  // the sphere has struck the plate and pushed it
  EXPECT_LT(largest_error, 0.03);
}

// The explosive-with-metal deck kind (MPM3D-F90's TNT3D.mpm form, written here in one
// dimension: a 10 mm `hiex` TNT column with its JWL `seos`, lit at x = 0 by `deto`, driving a
// 2 mm `sjc` copper plate, symmetric faces around them and none in contact) imports and runs.
// References: momentum conservation (the products' and the plate's momenta cancel: the sum
// stays zero to 1e-9 of the plate's; a free face behind the charge, far enough that nothing
// leaves), the energy balance (within 4 %: measured -2.9 % at 6 us, lost in the transfers while
// the products blow off into vacuum, as the run's summary says of MUSL with pure FLIP), and
// Gurney's open-faced sandwich (Cooper, Explosives Engineering, 1996): the plate's final
// velocity sqrt(2E) [((1 + 2 M/C)^3 + 1) / (6 (1 + M/C)) + M/C]^(-1/2) = 1258 m/s for TNT's
// sqrt(2E) = 2.44 km/s and M/C = 1.096, which the plate approaches from below as the products
// expand: at 6 us it moves at 80-100 % of it (measured 88 %).
TEST(Mpm3dDeckImport, ExplosiveDrivingAPlateKindConservesMomentumAndApproachesGurney) {
  test::ScratchDir dir;
  const Imported im =
      import_text(dir,
                  "mpm3d *** TNT driving copper\nnbco 2\nnbbo 2\nnbmp 480\nnmat 2\n"
                  "deto 0.0 0.0 0.0\nmaterial\n1 hiex 1.63d-3 6930\n"
                  "2 sjc 8.93d-3 117.0d3 0.35d0 90 292 0.31 0.025 1d-3\n"
                  "seos 1 3 3.712d5 3.21d3 4.15 0.95 0.30 6993\nseos 2 2 3.94d3 1.49 1.96 0\n"
                  "spx -100.0 40.0\nspy 0.0 0.2\nspz 0.0 0.2\ndcell 0.2\nfixed 0 0 2 2 2 2\n"
                  "dtscale 0.2\nendtime 0.006\nmusl on\njaum on\nbulk 1.5 0.06\n"
                  "Particle block 1\n 1 1.63d-3 0.1 0 0 0 100 2 2\n"
                  "Particle block 2\n 2 8.93d-3 0.1 10.0 0 0 20 2 2\nendi\n");
  const core::Scene& scene = im.scene;
  ASSERT_EQ(scene.bodies.size(), 2u);
  MpmSolver solver(scene, generate_particles(scene));
  const Particles& p = solver.particles();
  const double largest_error = run_to_end(solver, scene.run.end_time);
  double total = 0.0, plate = 0.0, plate_mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    total += p.mass[i] * p.velocity[i].x;
    if (p.body[i] == 1) plate += p.mass[i] * p.velocity[i].x, plate_mass += p.mass[i];
  }
  const double m_over_c = (8.93e-3 * 2.0) / (1.63e-3 * 10.0);
  const double gurney =
      2440.0 /
      std::sqrt((std::pow(1.0 + 2.0 * m_over_c, 3) + 1.0) / (6.0 * (1.0 + m_over_c)) + m_over_c);
  std::printf(
      "plate at %.0f m/s against Gurney's %.0f (%.1f %%); momentum sum %.2e of the plate's; "
      "largest energy error %.3f %%; %ld particles left\n",
      plate / plate_mass, gurney, 100.0 * plate / plate_mass / gurney, total / plate,
      100.0 * largest_error, solver.outflow_count());
  EXPECT_NEAR(total, 0.0, 1e-9 * std::abs(plate));
  EXPECT_GT(plate / plate_mass, 0.8 * gurney);
  EXPECT_LT(plate / plate_mass, gurney);
  EXPECT_LT(largest_error, 0.04);
}

TEST(Mpm3dDeckImport, DruckerPragerMaterialCarriesMpm3dsConstantsAndRuns) {
  // A 2 x 2 x 2 block of dpm soil (DataIn.f90's case 10: density, E, nu, q_fai, k_fai, q_psi,
  // ten_f) under gravity. Reference: the constants carried over exactly (the tension cutoff
  // min(ten_f, k_fai / q_fai), 0 without friction, as Constitution.f90's M3DM9 takes it), and
  // 20 steps after which every particle lies on or inside the cone and the cutoff (1e-12 MPa).
  test::ScratchDir dir;
  auto deck = [](const std::string& constants) {
    return "mpm3d *** soil block\nnbco 1\nnbbo 1\nnbmp 8\nnmat 1\nspx 0 2\nspy 0 2\n"
           "spz 0 2\ndcell 1\nendtime 0.01\nmaterial\n 1 dpm 2.1d-3 70 0.3 " +
           constants +
           "\nparticle block 1 1 2.1d-3 0.5 0 0 0 2 2 2\nload\ngrav 1 0 0 -9.8d-3\nendl\nendi\n";
  };
  const Imported im = import_text(dir, deck("0.3545 9.74d-3 0.05 5.0d-3"));
  ASSERT_EQ(im.scene.materials.size(), 1u);
  const core::Material& soil = im.scene.materials[0];
  EXPECT_EQ(soil.density, 2.1e-3);
  EXPECT_EQ(soil.youngs_modulus, 70.0);
  EXPECT_EQ(soil.poisson_ratio, 0.3);
  EXPECT_FALSE(soil.has_eos());
  ASSERT_TRUE(std::holds_alternative<core::DruckerPrager>(soil.strength));
  const auto& dp = std::get<core::DruckerPrager>(soil.strength);
  EXPECT_EQ(dp.q_phi, 0.3545);
  EXPECT_EQ(dp.k_phi, 9.74e-3);
  EXPECT_EQ(dp.q_psi, 0.05);
  EXPECT_EQ(dp.tension_cutoff, 5.0e-3);

  MpmSolver solver(im.scene, generate_particles(im.scene));
  for (int n = 0; n < 20; ++n) solver.step(solver.stable_time_step());
  for (const core::SymTensor& sigma : solver.particles().stress) {
    const core::SymTensor s = sigma.deviator();
    const double tau = std::sqrt(0.5 * core::double_dot(s, s));
    EXPECT_LE(tau + dp.q_phi * sigma.mean() - dp.k_phi, 1e-12);
    EXPECT_LE(sigma.mean(), dp.tension_cutoff + 1e-12);
  }
  EXPECT_GT(solver.time(), 0.0);

  // A cutoff beyond the apex is the apex; without friction the cutoff is 0.
  const Imported apex = import_text(dir, deck("0.3545 9.74d-3 0.05 1.0"));
  const auto& a = std::get<core::DruckerPrager>(apex.scene.materials[0].strength);
  EXPECT_DOUBLE_EQ(a.tension_cutoff, 9.74e-3 / 0.3545);
  const Imported tresca = import_text(dir, deck("0 9.74d-3 0 1.0"));
  EXPECT_EQ(std::get<core::DruckerPrager>(tresca.scene.materials[0].strength).tension_cutoff, 0.0);

  // M3DM9 runs without an EOS: a seos for it is refused at its line.
  const std::string e = error_of(
      "nbmp 1\nnmat 1\nmaterial\n 1 dpm 2.1d-3 70 0.3 0.3545 9.74d-3 0.05 5.0d-3\n"
      "seos 1 2 1480 1.9 0.1 0\n");
  EXPECT_NE(e.find("bad.mpm:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("without an EOS"), std::string::npos) << e;
}

TEST(Mpm3dDeckImport, NeoHookeanMaterialIsTheLogFormMpm3dRuns) {
  // A 2 x 2 x 8 block of neoh (DataIn.f90's case 11: density, E, nu) stretched along z.
  // Reference: Constitution.f90's M3DM10 and M3DM11, sigma = (mu (B - I) + lambda ln J I) / J
  // at each particle's F (afemp's "log" form), to 1e-10 of mu + K, at every step of the first
  // quarter period of a stretch that reaches 7.5 %, where the two forms part.
  test::ScratchDir dir;
  const Imported im =
      import_text(dir,
                  "mpm3d *** rubber block\nnbco 1\nnbbo 1\nnbmp 256\nnmat 1\nspx 0 2\nspy 0 2\n"
                  "spz 0 10\ndcell 1\ndtscale 0.3\nendtime 1\nmaterial\n 1 neoh 1.1d-3 17 0.45\n"
                  "particle block 1 1 1.1d-3 0.5 0 0 1 4 4 16\nendi\n");
  ASSERT_EQ(im.scene.materials.size(), 1u);
  const core::Material& rubber = im.scene.materials[0];
  EXPECT_EQ(rubber.youngs_modulus, 17.0);
  EXPECT_EQ(rubber.poisson_ratio, 0.45);
  ASSERT_TRUE(std::holds_alternative<core::NeoHookean>(rubber.strength));
  EXPECT_EQ(std::get<core::NeoHookean>(rubber.strength).form, core::NeoHookean::Form::log);
  Particles p = generate_particles(im.scene);
  for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = {0, 0, 3.0 * (p.position[i].z - 5.0)};
  MpmSolver solver(im.scene, std::move(p));
  const double mu = rubber.shear_modulus(), k = rubber.bulk_modulus(), lambda = k - 2.0 * mu / 3.0;
  double worst = 0.0, stretch = 0.0;
  // Over the first quarter of the block's axial period (2 L / c = 0.13 ms), every step.
  while (solver.time() < 0.035) {
    solver.step(solver.stable_time_step());
    const Particles& q = solver.particles();
    for (std::size_t i = 0; i < q.size(); ++i) {
      const core::Mat3& f = q.deformation_gradient[i];
      const double j = core::determinant(f);
      stretch = std::max(stretch, f.m[2][2]);
      double b[3][3];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          b[r][c] = f.m[r][0] * f.m[c][0] + f.m[r][1] * f.m[c][1] + f.m[r][2] * f.m[c][2];
      const core::SymTensor& s = q.stress[i];
      const double got[3][3] = {{s.xx, s.xy, s.xz}, {s.xy, s.yy, s.yz}, {s.xz, s.yz, s.zz}};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const double expected =
              (mu * (b[r][c] - (r == c ? 1.0 : 0.0)) + (r == c ? lambda * std::log(j) : 0.0)) / j;
          worst = std::max(worst, std::abs(got[r][c] - expected));
        }
    }
  }
  std::printf("[ neoh ] largest F_zz %.4f; |sigma - M3DM10's| %.2e of mu + K\n", stretch,
              worst / (mu + k));
  EXPECT_GT(stretch, 1.05);
  EXPECT_LT(worst, 1e-10 * (mu + k));
}

}  // namespace
}  // namespace afemp::mpm
