// LS-DYNA keyword decks into scenes (fem/lsdyna_deck_import.cpp): each keyword of the subset
// into the scene's fields (reference: the card layouts of the LS-DYNA Keyword User's Manual,
// Vol. I and II), unit conversion, *INCLUDE, keywords outside the subset listed with their
// line, and errors that name the file, the line and the keyword.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <variant>

#include "afemp/deck_import.hpp"
#include "core/plausibility.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "fem/lsdyna_deck_import.hpp"
#include "mpm/test_support.hpp"
#include "scratch_dir.hpp"

namespace afemp::fem {
namespace {

// A cube of 2 x 2 x 2 one-mm hexahedra, nodes 1..27 at (i, j, k) mm; `first` shifts the node
// and element numbers, `z` the cube along z.
std::string cube_mesh(int part = 1, int first = 0, int z = 0) {
  std::string s = "*NODE\n";
  for (int k = 0, n = 1 + first; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i, ++n)
        s += std::to_string(n) + "," + std::to_string(i) + "," + std::to_string(j) + "," +
             std::to_string(k + z) + "\n";
  s += "*ELEMENT_SOLID\n";
  const auto node = [&](int i, int j, int k) {
    return std::to_string(1 + first + i + 3 * j + 9 * k);
  };
  for (int k = 0, e = 1 + first; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i, ++e)
        s += std::to_string(e) + "," + std::to_string(part) + "," + node(i, j, k) + "," +
             node(i + 1, j, k) + "," + node(i + 1, j + 1, k) + "," + node(i, j + 1, k) + "," +
             node(i, j, k + 1) + "," + node(i + 1, j, k + 1) + "," + node(i + 1, j + 1, k + 1) +
             "," + node(i, j + 1, k + 1) + "\n";
  return s;
}

// Copper (Johnson-Cook with damage, Grueneisen EOS with E0) striking a wall; the lines of the
// keywords the tests name are counted in comments.
const std::string kDeck =
    "*KEYWORD\n"                                                       // 1
    "*TITLE\ncube on a wall\n"                                         // 2-3
    "*CONTROL_TERMINATION\n0.02,5000\n"                                // 4-5
    "*CONTROL_TIMESTEP\n0.0,0.67\n"                                    // 6-7
    "*DATABASE_BINARY_D3PLOT\n0.001\n"                                 // 8-9
    "*PART\ncube\n1,1,1,1,1\n"                                         // 10-12
    "*SECTION_SOLID\n1,1\n"                                            // 13-14
    "*MAT_JOHNSON_COOK\n"                                              // 15
    "1,8.93e-3,46000.,124000.,0.34\n"                                  // 16
    "90.,292.,0.31,0.025,1.09,1356.,293.,1.0e-3\n"                     // 17
    "383.,0.,0.,0.,0.54,4.89,-3.03,0.014\n"                            // 18
    "1.12\n"                                                           // 19
    "*EOS_GRUNEISEN\n1,3940.,1.49,0.,0.,1.96,0.,0.0893\n"              // 20-21
    "*HOURGLASS\n1,6,1.0\n"                                            // 22-23
    "*INITIAL_VELOCITY_GENERATION\n1,2,0.,0.,0.,-300.\n0,0,0,0,0,0\n"  // 24-26
    "*RIGIDWALL_PLANAR\n0\n0.,0.,-0.5,0.,0.,1.,0.1\n"                  // 27-29
    "*DATABASE_MATSUM\n1.0e-4\n"                                       // 30-31
    "*DATABASE_GLSTAT\n1.0e-4\n" +                                     // 32-33
    cube_mesh() +
    "*END\n";

struct Imported {
  core::DeckImport deck;
  core::Scene scene;
};

Imported import_text(const test::ScratchDir& dir, const std::string& deck,
                     const std::string& units = "") {
  const std::string deck_path = dir.write("deck.k", deck);
  const std::string scene_path = dir.file("scene.toml");
  core::DeckImport d = core::import_deck(deck_path, scene_path, {units});
  core::write_deck_import(d, scene_path);
  return {std::move(d), core::read_scene(scene_path)};
}

std::string error_of(const std::string& deck) {
  try {
    import_lsdyna_deck(deck, "bad.k", "scene.toml", {});
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST(LsDynaDeckImport, KeywordsBecomeTheSceneFields) {
  test::ScratchDir dir;
  const Imported im = import_text(dir, kDeck);
  const core::Scene& s = im.scene;
  EXPECT_EQ(s.run.title, "cube on a wall");
  EXPECT_DOUBLE_EQ(s.run.end_time, 0.02);
  EXPECT_EQ(s.run.max_steps, 5000);
  EXPECT_DOUBLE_EQ(s.run.element_time_step_factor, 0.67);
  EXPECT_DOUBLE_EQ(s.run.output_every, 0.001);

  ASSERT_EQ(s.materials.size(), 1u);
  const core::Material& m = s.materials[0];
  EXPECT_DOUBLE_EQ(m.density, 8.93e-3);
  EXPECT_DOUBLE_EQ(m.youngs_modulus, 124000.);
  EXPECT_DOUBLE_EQ(m.poisson_ratio, 0.34);
  const auto& jc = std::get<core::JohnsonCook>(m.strength);
  EXPECT_DOUBLE_EQ(jc.A, 90.);
  EXPECT_DOUBLE_EQ(jc.B, 292.);
  EXPECT_DOUBLE_EQ(jc.n, 0.31);
  EXPECT_DOUBLE_EQ(jc.C, 0.025);
  EXPECT_DOUBLE_EQ(jc.m, 1.09);
  EXPECT_DOUBLE_EQ(jc.melt_temperature, 1356.);
  EXPECT_DOUBLE_EQ(jc.room_temperature, 293.);
  EXPECT_DOUBLE_EQ(jc.reference_strain_rate, 1e-3);
  const auto& mg = std::get<core::MieGruneisen>(m.eos);
  EXPECT_DOUBLE_EQ(mg.c0, 3940.);
  EXPECT_DOUBLE_EQ(mg.s, 1.49);
  EXPECT_DOUBLE_EQ(mg.gamma0, 1.96);
  EXPECT_NE(im.deck.scene.find("failure = { model = \"johnson-cook\", D1 = 0.54, D2 = 4.89, "
                               "D3 = -3.03, D4 = 0.014, D5 = 1.12"),
            std::string::npos)
      << im.deck.scene;

  ASSERT_EQ(s.bodies.size(), 1u);
  const core::BodySpec& b = s.bodies[0];
  EXPECT_EQ(b.name, "cube");
  EXPECT_EQ(b.discretisation, core::Discretisation::hexahedra);
  EXPECT_EQ(b.element, core::HexFormulation::one_point);
  EXPECT_EQ(b.hourglass.form, core::HourglassForm::assumed_strain);
  EXPECT_DOUBLE_EQ(b.hourglass.effective_coefficient(), 1.0);
  EXPECT_DOUBLE_EQ(b.velocity.z, -300.);
  EXPECT_DOUBLE_EQ(b.internal_energy, 0.0893 / 8.93e-3);  // E0 per volume over RO
  EXPECT_EQ(std::get<core::MeshFileShape>(b.shape).parts, std::vector<std::string>{"cube"});

  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_DOUBLE_EQ(s.walls[0].point.z, -0.5);
  EXPECT_DOUBLE_EQ(s.walls[0].normal.z, 1.0);
  EXPECT_DOUBLE_EQ(s.walls[0].friction, 0.1);
}

// Reference: nothing of the deck is dropped without a line: the two output keywords outside
// the subset are listed with their lines, in the notes and as comments at the top of the scene.
TEST(LsDynaDeckImport, KeywordsOutsideTheSubsetAreListedWithTheirLines) {
  test::ScratchDir dir;
  const Imported im = import_text(dir, kDeck);
  std::vector<std::string> listed;
  for (const core::DeckNote& n : im.deck.notes)
    if (!n.approximated) listed.push_back(n.keyword + ":" + std::to_string(n.at.line));
  EXPECT_EQ(listed, (std::vector<std::string>{"*DATABASE_MATSUM:30", "*DATABASE_GLSTAT:32"}));
  EXPECT_NE(
      im.deck.scene.find("#   " + dir.file("deck.k") + ":30: *DATABASE_MATSUM: not translated"),
      std::string::npos)
      << im.deck.scene;
  EXPECT_TRUE(im.scene.run.untranslated.empty());
}

// Reference: issue 47, a deck must run as it means or be refused. A load (*LOAD_BODY_Z, line
// 34) outside the subset changes the run: the import stops at its file, line and keyword; with
// allow_untranslated the scene is written, and [run] untranslated carries the keyword so that
// the scene's plausibility warnings (what `afemp check` prints) repeat it.
TEST(LsDynaDeckImport, UntranslatedKeywordThatChangesTheRunIsRefusedUnlessAllowed) {
  std::string deck = kDeck;
  deck.insert(deck.find("*NODE"), "*LOAD_BODY_Z\n1,1.0\n");  // lines 34-35
  const std::string e = error_of(deck);
  EXPECT_NE(e.find("bad.k:34:"), std::string::npos) << e;
  EXPECT_NE(e.find("*LOAD_BODY_Z"), std::string::npos) << e;
  EXPECT_NE(e.find("--allow-untranslated"), std::string::npos) << e;

  test::ScratchDir dir;
  const std::string deck_path = dir.write("deck.k", deck);
  const std::string scene_path = dir.file("scene.toml");
  core::DeckImportOptions options;
  options.allow_untranslated = true;
  const core::DeckImport d = core::import_deck(deck_path, scene_path, options);
  core::write_deck_import(d, scene_path);
  EXPECT_NE(d.scene.find("# WARNING: imported with --allow-untranslated"), std::string::npos)
      << d.scene;
  const core::Scene s = core::read_scene(scene_path);
  ASSERT_EQ(s.run.untranslated.size(), 1u);
  EXPECT_NE(s.run.untranslated[0].find(":34: *LOAD_BODY_Z: not translated, the run differs"),
            std::string::npos)
      << s.run.untranslated[0];
  std::vector<std::string> warned;
  for (const core::SceneWarning& w : core::plausibility_warnings(s))
    if (w.key == "run.untranslated") warned.push_back(w.message);
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_NE(warned[0].find("*LOAD_BODY_Z"), std::string::npos) << warned[0];
}

// Reference: 1 kg/m^3 = 1e-6 g/mm^3, 1 Pa = 1e-6 MPa, 1 m = 1000 mm, 1 s = 1000 ms; the mesh
// keeps its numbers and is scaled by 1000 on reading.
TEST(LsDynaDeckImport, SiDeckIsConvertedIntoMillimetresMilliseconds) {
  test::ScratchDir dir;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n2.0e-5\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,2\n"
      "*MAT_PLASTIC_KINEMATIC\n1,7850.,200.0e9,0.3,500.0e6,2.0e9,1.0\n"
      "*INITIAL_VELOCITY_GENERATION\n1,2,0.,0.,100.,0.\n0,0,0,0,0,0\n"
      "*RIGIDWALL_PLANAR\n0\n0.,0.,-0.001,0.,0.,1.\n" +
      cube_mesh() + "*END\n";
  const Imported im = import_text(dir, deck, "m-s-kg");
  const core::Scene& s = im.scene;
  EXPECT_NEAR(s.run.end_time, 0.02, 1e-15);
  EXPECT_NEAR(s.materials[0].density, 7.85e-3, 1e-15);
  EXPECT_NEAR(s.materials[0].youngs_modulus, 200e3, 1e-9);
  const auto& j2 = std::get<core::J2Plasticity>(s.materials[0].strength);
  EXPECT_NEAR(j2.yield_stress, 500, 1e-9);
  EXPECT_NEAR(j2.hardening, 200e3 * 2e3 / (200e3 - 2e3), 1e-6);
  EXPECT_NEAR(s.bodies[0].velocity.y, 100, 1e-12);
  EXPECT_EQ(s.bodies[0].element, core::HexFormulation::full);  // ELFORM 2
  EXPECT_DOUBLE_EQ(std::get<core::MeshFileShape>(s.bodies[0].shape).scale, 1000.0);
  EXPECT_NEAR(s.walls[0].point.z, -1.0, 1e-12);
  // The converted scene states its units, so that its plausibility is checked in them.
  EXPECT_EQ(s.run.units, "mm-ms-g");
  EXPECT_TRUE(import_text(dir, kDeck).scene.run.units.empty());  // kept as the deck's
}

// *INCLUDE: the mesh in a file beside the deck; the scene's body reads it through the deck.
TEST(LsDynaDeckImport, IncludedMeshIsRead) {
  test::ScratchDir dir;
  dir.write("mesh.k", "*KEYWORD\n" + cube_mesh() + "*END\n");
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n0.01\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,1\n"
      "*MAT_ELASTIC\n1,7.85e-3,200.0e3,0.3\n*INCLUDE\nmesh.k\n*END\n";
  const Imported im = import_text(dir, deck);
  EXPECT_EQ(std::get<core::MeshFileShape>(im.scene.bodies[0].shape).parts,
            std::vector<std::string>{"block"});
  EXPECT_TRUE(std::holds_alternative<core::Elastic>(im.scene.materials[0].strength));
}

// Holmquist-Johnson-Cook concrete (MAT_111; the 48 MPa concrete of docs/scene-format.md, SI).
TEST(LsDynaDeckImport, HolmquistJohnsonCookConcreteMapsEveryField) {
  test::ScratchDir dir;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n1.0e-4\n*PART\nslab\n1,1,1\n*SECTION_SOLID\n1,1\n"
      "*MAT_JOHNSON_HOLMQUIST_CONCRETE\n"
      "1,2440.,14.86e9,0.79,1.60,0.007,0.61,48.0e6\n"
      "4.0e6,1.0,0.01,7.0,16.0e6,0.001,800.0e6,0.10\n"
      "0.04,1.0,85.0e9,-171.0e9,208.0e9,0.0\n" +
      cube_mesh() + "*END\n";
  const Imported im = import_text(dir, deck);
  const core::Material& m = im.scene.materials[0];
  const auto& hjc = std::get<core::HolmquistJohnsonCook>(m.strength);
  EXPECT_DOUBLE_EQ(hjc.A, 0.79);
  EXPECT_DOUBLE_EQ(hjc.B, 1.60);
  EXPECT_DOUBLE_EQ(hjc.N, 0.61);
  EXPECT_DOUBLE_EQ(hjc.C, 0.007);
  EXPECT_DOUBLE_EQ(hjc.compressive_strength, 48e6);
  EXPECT_DOUBLE_EQ(hjc.tensile_strength, 4e6);
  EXPECT_DOUBLE_EQ(hjc.min_fracture_strain, 0.01);
  EXPECT_DOUBLE_EQ(hjc.max_strength, 7.0);
  EXPECT_DOUBLE_EQ(hjc.D1, 0.04);
  EXPECT_DOUBLE_EQ(hjc.D2, 1.0);
  EXPECT_NEAR(m.shear_modulus(), 14.86e9, 1e-3);
}

TEST(LsDynaDeckImport, ErrorsNameFileLineKeywordAndWhatIsAllowed) {
  const std::string head = "*KEYWORD\n*CONTROL_TERMINATION\n0.01\n*PART\nblock\n1,1,1,1\n";
  std::string e = error_of(head + "*SECTION_SOLID\n1,10\n" + cube_mesh());
  EXPECT_NE(e.find("bad.k:8:"), std::string::npos) << e;
  EXPECT_NE(e.find("*SECTION_SOLID"), std::string::npos) << e;
  EXPECT_NE(e.find("ELFORM 10"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: 1"), std::string::npos) << e;

  e = error_of(head + "*SECTION_SOLID\n1,1\n" + cube_mesh());
  EXPECT_NE(e.find("bad.k:6:"), std::string::npos) << e;
  EXPECT_NE(e.find("material 1, which is not defined"), std::string::npos) << e;

  e = error_of(head +
               "*SECTION_SOLID\n1,1\n*MAT_JOHNSON_COOK\n1,8.93e-3,46000.,1.24e5,0.34\n"
               "90.,292.,0.31\n" +
               cube_mesh());
  EXPECT_NE(e.find("EOS 1, which is not defined"), std::string::npos) << e;

  e = error_of(head + "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,7.85e-3,2oo.0e3,0.3\n" + cube_mesh());
  EXPECT_NE(e.find("bad.k:10:"), std::string::npos) << e;
  EXPECT_NE(e.find("*MAT_ELASTIC"), std::string::npos) << e;
  EXPECT_NE(e.find("'2oo.0e3'"), std::string::npos) << e;

  e = error_of("*KEYWORD\n*INCLUDE\nmissing.k\n");
  EXPECT_NE(e.find("bad.k:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot open"), std::string::npos) << e;

  e = error_of("*KEYWORD\n*PART\nblock\n1,1,1\n" + cube_mesh());
  EXPECT_NE(e.find("*CONTROL_TERMINATION"), std::string::npos) << e;
}

// Reference: LS-DYNA's *MAT_015 takes its solids' elasticity from G and the EOS; with E and PR
// blank the scene's E and nu are those of G and K = rho0 c0^2 (K = 8.93e-3 x 3940^2 =
// 138,622 MPa, G = 43,333 MPa: E = 9 K G / (3 K + G) = 117,700, nu = 0.3581). The stiffness
// hourglass form with QM blank takes LS-DYNA's 0.1, not afemp's own 0.05.
TEST(LsDynaDeckImport, JohnsonCookWithoutEAndPrTakesThemFromGAndTheEos) {
  test::ScratchDir dir;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n0.01\n*PART\nbar\n1,1,1,1,1\n*SECTION_SOLID\n1,1\n"
      "*MAT_JOHNSON_COOK\n1,8.93e-3,43333.33\n157.,425.,1.0\n"
      "*EOS_GRUNEISEN\n1,3940.,1.49,0.,0.,1.96\n*HOURGLASS\n1,5\n" +
      cube_mesh() + "*END\n";
  const Imported im = import_text(dir, deck);
  const core::Material& m = im.scene.materials[0];
  const double K = 8.93e-3 * 3940.0 * 3940.0, G = 43333.33;
  EXPECT_NEAR(m.youngs_modulus, 9 * K * G / (3 * K + G), 1e-6);
  EXPECT_NEAR(m.poisson_ratio, (3 * K - 2 * G) / (2 * (3 * K + G)), 1e-12);
  EXPECT_NEAR(m.shear_modulus(), G, 1e-6);
  EXPECT_EQ(im.scene.bodies[0].hourglass.form, core::HourglassForm::stiffness);
  EXPECT_DOUBLE_EQ(im.scene.bodies[0].hourglass.effective_coefficient(), 0.1);
}

// Fixed-column cards (10 characters a field), as most decks write them.
TEST(LsDynaDeckImport, FixedColumnCardsAreRead) {
  test::ScratchDir dir;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n$   endtim\n     0.015\n*PART\nblock\n"
      "$      pid     secid       mid\n         1         1         7\n*SECTION_SOLID\n"
      "         1         1\n*MAT_ELASTIC\n$      mid        ro         e        pr\n"
      "         7   7.85e-3   2.0e+05      0.29\n" +
      cube_mesh() + "*END\n";
  const Imported im = import_text(dir, deck);
  EXPECT_DOUBLE_EQ(im.scene.run.end_time, 0.015);
  EXPECT_DOUBLE_EQ(im.scene.materials[0].youngs_modulus, 2.0e5);
  EXPECT_DOUBLE_EQ(im.scene.materials[0].poisson_ratio, 0.29);
  EXPECT_EQ(im.deck.notes.size(), 0u);
  EXPECT_NE(im.deck.scene.find("Everything the deck holds is translated"), std::string::npos);
}

// `afemp check` and `afemp run` given an LS-DYNA deck say to import it, not "TOML syntax
// error".
TEST(LsDynaDeckImport, CommandSaysToImportADeck) {
  test::ScratchDir dir;
  const std::string deck = dir.write("cube.k", kDeck);
  for (const char* cmd : {"check", "run"}) {
    const mpm::test::CommandResult r =
        mpm::test::run_afemp(std::string(cmd) + " \"" + deck + "\"", dir);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("this is an LS-DYNA deck, not a scene; import it with `afemp import " +
                         deck + " -o SCENE.toml`"),
              std::string::npos)
        << r.err;
  }
}

// Two elastic cubes, part 1 (nodes 1..27) and part 2 (nodes 101..127, 3 mm above), and what
// is added between the parts and the mesh.
std::string two_cubes(const std::string& extra) {
  return "*KEYWORD\n*CONTROL_TERMINATION\n0.01\n*PART\nstriker\n1,1,1\n*PART\ntarget\n2,1,1\n"
         "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,7.85e-3,2.0e5,0.3\n" +
         extra + cube_mesh(1) + cube_mesh(2, 100, 3) + "*END\n";
}

std::string node_list(int sid, int first, int count) {
  std::string s = "*SET_NODE_LIST\n" + std::to_string(sid) + "\n";
  for (int n = 0; n < count; ++n)
    s += std::to_string(first + n) + (n % 8 == 7 || n + 1 == count ? "\n" : ",");
  return s;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. I, *INITIAL_VELOCITY (NSID NSIDEX BOXID
// IRIGID ICID / VX VY VZ VXR VYR VZR) and *INITIAL_VELOCITY_NODE (NID VX VY VZ VXR VYR VZR
// ICID): the nodes given start at that velocity. A node set holding exactly part 1's 27 nodes
// is body striker's velocity; every node of part 2 listed with one velocity is target's.
TEST(LsDynaDeckImport, NodeVelocitiesOfWholePartsAreTheBodiesVelocities) {
  test::ScratchDir dir;
  std::string nodes = "*INITIAL_VELOCITY_NODE\n";
  for (int n = 101; n <= 127; ++n) nodes += std::to_string(n) + ",10.0,0,0\n";
  const Imported im =
      import_text(dir, two_cubes(node_list(7, 1, 27) + "*INITIAL_VELOCITY\n7\n0,0,-200\n" + nodes));
  ASSERT_EQ(im.scene.bodies.size(), 2u);
  EXPECT_EQ(im.scene.bodies[0].name, "striker");
  EXPECT_DOUBLE_EQ(im.scene.bodies[0].velocity.z, -200.0);
  EXPECT_DOUBLE_EQ(im.scene.bodies[0].velocity.x, 0.0);
  EXPECT_DOUBLE_EQ(im.scene.bodies[1].velocity.x, 10.0);
  EXPECT_DOUBLE_EQ(im.scene.bodies[1].velocity.z, 0.0);

  // NSID 0: every node.
  const Imported all = import_text(dir, two_cubes("*INITIAL_VELOCITY\n0\n5,0,0\n"));
  EXPECT_DOUBLE_EQ(all.scene.bodies[0].velocity.x, 5.0);
  EXPECT_DOUBLE_EQ(all.scene.bodies[1].velocity.x, 5.0);
}

// Reference: afemp gives a body one translational velocity (docs/scene-format.md, `velocity`),
// so a velocity on part of a part's nodes, a rotational one, or two on one part are refused
// with the keyword, its line and why (issue 47: run as the deck means, or refuse).
TEST(LsDynaDeckImport, NodeVelocitiesAfempCannotStateAreRefused) {
  // Lines: 1-13 the parts, 14-19 the set (26 nodes on 4 cards), 20 *INITIAL_VELOCITY, 22 VX..
  std::string e = error_of(two_cubes(node_list(7, 1, 26) + "*INITIAL_VELOCITY\n7\n0,0,-200\n"));
  EXPECT_NE(e.find("bad.k:22:"), std::string::npos) << e;
  EXPECT_NE(e.find("*INITIAL_VELOCITY"), std::string::npos) << e;
  EXPECT_NE(e.find("26 of the 27 nodes of part 1"), std::string::npos) << e;

  e = error_of(two_cubes("*INITIAL_VELOCITY\n0\n0,0,-200,1.0\n"));
  EXPECT_NE(e.find("bad.k:16:"), std::string::npos) << e;
  EXPECT_NE(e.find("VXR, VYR, VZR"), std::string::npos) << e;

  e = error_of(two_cubes("*INITIAL_VELOCITY\n0\n0,0,-200\n*INITIAL_VELOCITY_NODE\n5,1,0,0\n"));
  EXPECT_NE(e.find("two velocities"), std::string::npos) << e;
  EXPECT_NE(e.find("part 1"), std::string::npos) << e;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. I, *CONTACT (SSID MSID SSTYP MSTYP ... /
// FS FD DC ...; SSTYP 3 a part, 2 a part set; mu = FD + (FS - FD) exp(-DC v), FS at DC = 0):
// each contact becomes afemp's penalty contact between the bodies of its parts; a single
// surface, every pair of its parts and each part with itself.
TEST(LsDynaDeckImport, ContactsBecomePenaltyContactsBetweenTheParts) {
  test::ScratchDir dir;
  Imported im = import_text(
      dir, two_cubes("*CONTACT_ERODING_SURFACE_TO_SURFACE_ID\n5,impact\n1,2,3,3\n0.2,0.1\n\n"
                     "0,1,0\n"));
  ASSERT_EQ(im.scene.contacts.size(), 1u);
  EXPECT_EQ(im.scene.contacts[0].method, core::ContactMethod::penalty);
  EXPECT_EQ(im.scene.contacts[0].bodies, (std::array<int, 2>{0, 1}));
  EXPECT_DOUBLE_EQ(im.scene.contacts[0].friction, 0.2);  // DC 0: FS

  // A part set (*SET_PART_LIST, defined after the contact) against a part; DC > 0: FD.
  im = import_text(dir, two_cubes("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n9,1,2,3\n0.3,0.1,0.5\n"
                                  "*SET_PART_LIST\n9\n2\n"));
  ASSERT_EQ(im.scene.contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(im.scene.contacts[0].friction, 0.1);

  // Single surface over every part: the pair and each cube with itself.
  im = import_text(dir, two_cubes("*CONTACT_AUTOMATIC_SINGLE_SURFACE\n0\n"));
  ASSERT_EQ(im.scene.contacts.size(), 3u);
  EXPECT_EQ(im.scene.contacts[0].bodies, (std::array<int, 2>{0, 0}));
  EXPECT_EQ(im.scene.contacts[1].bodies, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(im.scene.contacts[2].bodies, (std::array<int, 2>{1, 1}));

  // A segment set (SSTYP 0) afemp cannot state: refused with the field and what is allowed.
  const std::string e = error_of(two_cubes("*CONTACT_AUTOMATIC_NODES_TO_SURFACE\n1,2,0,3\n"));
  EXPECT_NE(e.find("bad.k:15:"), std::string::npos) << e;
  EXPECT_NE(e.find("SSTYP 0"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: 3 (a part)"), std::string::npos) << e;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. II, *MAT_ADD_EROSION (MID EXCL MXPRES MNEPS
// EFFEPS VOLEPS NUMFIP NCS; a criterion equal to EXCL is off) and *MAT_PLASTIC_KINEMATIC (FS:
// the element is deleted at that effective plastic strain): the bodies of the material erode
// at EFFEPS as plastic strain, at V / V0 = 1 + VOLEPS, and where the material fails.
TEST(LsDynaDeckImport, ErosionCriteriaBecomeTheBodiesErosion) {
  test::ScratchDir dir;
  const std::string parts =
      "*KEYWORD\n*CONTROL_TERMINATION\n0.01\n*PART\nblock\n1,1,1\n*SECTION_SOLID\n1,1\n";
  Imported im =
      import_text(dir, parts +
                           "*MAT_ADD_EROSION\n1,9.0,9.0,,0.8,-0.6\n*MAT_PLASTIC_KINEMATIC\n"
                           "1,7.85e-3,2.0e5,0.3,500.0,1000.0,1.0\n0,0,1.2\n" +
                           cube_mesh() + "*END\n");
  ASSERT_EQ(im.scene.bodies.size(), 1u);
  ASSERT_TRUE(im.scene.bodies[0].erosion.has_value());
  const core::ErosionSettings& e = *im.scene.bodies[0].erosion;
  EXPECT_DOUBLE_EQ(e.plastic_strain, 0.8);
  EXPECT_DOUBLE_EQ(e.volume_ratio, 0.4);
  EXPECT_TRUE(e.material_failure);
  EXPECT_DOUBLE_EQ(im.scene.materials[0].failure_strain, 1.2);

  // MXPRES (a compressive pressure limit) has no afemp criterion: refused, naming it.
  const std::string err = error_of(parts +
                                   "*MAT_ADD_EROSION\n1,0,5000.0\n*MAT_ELASTIC\n"
                                   "1,7.85e-3,2.0e5,0.3\n" +
                                   cube_mesh());
  EXPECT_NE(err.find("bad.k:10:"), std::string::npos) << err;
  EXPECT_NE(err.find("MXPRES"), std::string::npos) << err;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. II, *MAT_RIGID (MID RO E PR ... / CMO
// CON1 CON2; CMO 1: global constraints, CON1 and CON2 0 free, 1 x, ..., 4 x and y, ..., 7
// all): the part is afemp's rigid body with those components fixed; a single-surface contact
// gives it no self-contact (a rigid body does not fold).
TEST(LsDynaDeckImport, RigidMaterialIsARigidBodyWithItsConstraints) {
  test::ScratchDir dir;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n0.01\n*PART\nstriker\n1,1,1\n*PART\nanvil\n2,1,2\n"
      "*SECTION_SOLID\n1,1\n*MAT_ELASTIC\n1,7.85e-3,2.0e5,0.3\n*MAT_RIGID\n"
      "2,7.85e-3,2.0e5,0.3\n1,4,7\n*CONTACT_AUTOMATIC_SINGLE_SURFACE\n0\n" +
      cube_mesh(1) + cube_mesh(2, 100, 3) + "*END\n";
  const Imported im = import_text(dir, deck);
  ASSERT_EQ(im.scene.bodies.size(), 2u);
  EXPECT_FALSE(im.scene.bodies[0].rigid.has_value());
  ASSERT_TRUE(im.scene.bodies[1].rigid.has_value()) << im.deck.scene;
  EXPECT_EQ(im.scene.bodies[1].rigid->fixed,
            (std::array<bool, 6>{true, true, false, true, true, true}));
  ASSERT_EQ(im.scene.contacts.size(), 2u);
  EXPECT_EQ(im.scene.contacts[0].bodies, (std::array<int, 2>{0, 0}));
  EXPECT_EQ(im.scene.contacts[1].bodies, (std::array<int, 2>{0, 1}));

  // Local constraints (CMO -1) are refused with the card's line.
  std::string local = deck;
  local.replace(local.find("1,4,7\n"), 6, "-1,4,7\n");
  const std::string e = error_of(local);
  EXPECT_NE(e.find("bad.k:16:"), std::string::npos) << e;
  EXPECT_NE(e.find("CMO -1"), std::string::npos) << e;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. II, *MAT_MOONEY-RIVLIN_RUBBER (MID RO PR A B
// REF; shear modulus 2 (A + B)), and the incompressible Mooney-Rivlin solid in uniaxial
// tension (Rivlin 1948; Treloar's form): sigma_zz - sigma_xx = 2 (l^2 - 1/l) (C10 + C01 / l).
// The imported cube of rubber (A 0.2, B 0.05 MPa, PR 0.499), put at the isochoric stretch
// l = 1.5, carries that stress difference at every point to 1e-9; the step factor is held to
// 0.5, where a twisting column of this PR stays stable (tests/fem/test_hyperelastic_hexahedra).
TEST(LsDynaDeckImport, MooneyRivlinRubberIsAfempsMooneyRivlinSolid) {
  test::ScratchDir dir;
  const std::string deck =
      "*KEYWORD\n*CONTROL_TERMINATION\n1.0\n*PART\nrubber\n1,1,1\n*SECTION_SOLID\n1,1\n"
      "*MAT_MOONEY-RIVLIN_RUBBER\n1,1.1e-3,0.499,0.2,0.05\n" +
      cube_mesh() + "*END\n";
  const Imported im = import_text(dir, deck, "mm-ms-g");
  const core::Material& m = im.scene.materials[0];
  const auto& mr = std::get<core::MooneyRivlin>(m.strength);
  EXPECT_DOUBLE_EQ(mr.c10, 0.2);
  EXPECT_DOUBLE_EQ(mr.c01, 0.05);
  EXPECT_NEAR(m.shear_modulus(), 0.5, 1e-12);
  // K = E / (3 (1 - 2 PR)) with E = 4 (A + B) (1 + PR).
  EXPECT_NEAR(m.bulk_modulus(), 4.0 * 0.25 * 1.499 / (3.0 * 0.002), 1e-9);
  EXPECT_DOUBLE_EQ(im.scene.run.element_time_step_factor, 0.5);
  bool volumetric = false;
  for (const core::DeckNote& n : im.deck.notes)
    volumetric = volumetric || (n.approximated && n.what.find("III") != std::string::npos);
  EXPECT_TRUE(volumetric);

  FeSolver solver(im.scene);
  const double l = 1.5, t = 1.0 / std::sqrt(l);
  FeNodes& nodes = solver.mutable_nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const core::Vec3& x = nodes.initial_position[i];
    nodes.position[i] = {t * x.x, t * x.y, l * x.z};
  }
  solver.step(1e-12);
  const double expected = 2.0 * (l * l - 1.0 / l) * (0.2 + 0.05 / l);
  for (const core::SymTensor& s : solver.hexahedra().stress) {
    EXPECT_NEAR(s.zz - s.xx, expected, 1e-9 * expected);
    EXPECT_NEAR(s.yy - s.xx, 0.0, 1e-9 * expected);
  }

  // A and B fitted to a curve (A = B = 0), and an EOS given to it, are refused.
  std::string fitted = deck;
  fitted.replace(fitted.find("0.2,0.05"), 8, "0.0,0.0");
  std::string e = error_of(fitted);
  EXPECT_NE(e.find("bad.k:10:"), std::string::npos) << e;
  EXPECT_NE(e.find("LCID"), std::string::npos) << e;
  std::string with_eos = deck;
  with_eos.replace(with_eos.find("1,1,1\n"), 6, "1,1,1,1\n");
  with_eos.replace(with_eos.find("*END"), 4, "*EOS_LINEAR_POLYNOMIAL\n1,0.0,2500.0\n*END");
  e = error_of(with_eos);
  EXPECT_NE(e.find("allowed EOSID 0"), std::string::npos) << e;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. I, *BOUNDARY_PRESCRIBED_MOTION_SET (NSID
// DOF VAD LCID SF ...: DOF 3 z, VAD 0 a velocity SF x curve(t)) and *DEFINE_CURVE (LCID SIDR SFA
// SFO OFFA OFFO / A O pairs: t = SFA A + OFFA, value = SFO O + OFFO): the node set's z velocity
// is prescribed as -50 x the curve, (0, 1) to (0.005, 0) with SFO 2 and OFFA 0.001.
TEST(LsDynaDeckImport, PrescribedMotionIsAConstraintVelocityWithTheCurve) {
  test::ScratchDir dir;
  const std::string deck = two_cubes(node_list(3, 119, 9) +
                                     "*DEFINE_CURVE\n4,0,1.0,2.0,0.001\n0.0,0.5\n0.005,0.0\n"
                                     "*BOUNDARY_PRESCRIBED_MOTION_SET\n3,3,0,4,-50.0\n");
  const Imported im = import_text(dir, deck);
  ASSERT_EQ(im.scene.constraints.size(), 1u) << im.deck.scene;
  const core::ConstraintSpec& c = im.scene.constraints[0];
  EXPECT_EQ(c.nodes.kind, core::NodeSelector::Kind::set);
  EXPECT_EQ(c.nodes.set, "set 3");
  EXPECT_EQ(c.components, (std::array<bool, 3>{false, false, true}));
  EXPECT_DOUBLE_EQ(c.velocity.z, -50.0);
  ASSERT_EQ(c.curve.size(), 2u);
  EXPECT_DOUBLE_EQ(c.curve[0][0], 0.001);
  EXPECT_DOUBLE_EQ(c.curve[0][1], 1.0);
  EXPECT_DOUBLE_EQ(c.curve[1][0], 0.006);
  EXPECT_DOUBLE_EQ(c.curve[1][1], 0.0);

  // A displacement (VAD 2) is refused with its card's line (the set: lines 14-17).
  std::string e = error_of(two_cubes(node_list(3, 119, 9) +
                                     "*DEFINE_CURVE\n4\n0.0,1.0\n0.005,0.0\n"
                                     "*BOUNDARY_PRESCRIBED_MOTION_SET\n3,3,2,4,-50.0\n"));
  EXPECT_NE(e.find("bad.k:23:"), std::string::npos) << e;
  EXPECT_NE(e.find("VAD 2"), std::string::npos) << e;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. I, *CONTROL_HOURGLASS (IHQ QH: the form of
// the parts without *HOURGLASS), *CONTROL_BULK_VISCOSITY (Q1 Q2 TYPE BTYPE: the bulk viscosity
// of the parts whose *HOURGLASS gives none), *CONTROL_SOLID (tetrahedra, cohesive and implicit
// settings; PSFAIL erodes solids at a principal stress) and *CONTROL_CONTACT (SLSFAC scales the
// penalty stiffness; SFRIC, DFRIC, EDC the friction of parts without *PART_CONTACT's). Most
// decks carry them: they translate instead of stopping the import.
TEST(LsDynaDeckImport, ControlKeywordsSetTheDefaultsOfTheParts) {
  test::ScratchDir dir;
  // Striker names no *HOURGLASS: *CONTROL_HOURGLASS's type 6 and *CONTROL_BULK_VISCOSITY's
  // coefficients. Target's *HOURGLASS 2 (type 5, no Q1 and Q2) keeps its form and takes the
  // control's bulk viscosity.
  std::string deck = two_cubes(
      "*CONTROL_HOURGLASS\n6,0.8\n*CONTROL_BULK_VISCOSITY\n1.2,0.05,1\n"
      "*CONTROL_SOLID\n1,0,0,0,0\n*CONTROL_CONTACT\n0.1\n\n0.3,0.2\n*HOURGLASS\n2,5,0.04\n");
  deck.replace(deck.find("target\n2,1,1"), 12, "target\n2,1,1,0,2");
  Imported im = import_text(dir, deck);
  ASSERT_EQ(im.scene.bodies.size(), 2u);
  const core::BodySpec &striker = im.scene.bodies[0], &target = im.scene.bodies[1];
  EXPECT_EQ(striker.hourglass.form, core::HourglassForm::assumed_strain);
  EXPECT_DOUBLE_EQ(striker.hourglass.effective_coefficient(), 0.8);
  EXPECT_EQ(target.hourglass.form, core::HourglassForm::stiffness);
  EXPECT_DOUBLE_EQ(target.hourglass.effective_coefficient(), 0.04);
  for (const core::BodySpec* b : {&striker, &target}) {
    const core::BulkViscositySettings q = core::bulk_viscosity_of(im.scene, *b);
    EXPECT_DOUBLE_EQ(q.quadratic, 1.2);
    EXPECT_DOUBLE_EQ(q.linear, 0.05);
  }
  EXPECT_TRUE(im.scene.run.untranslated.empty());
  bool esort = false, slsfac = false;
  for (const core::DeckNote& n : im.deck.notes) {
    esort = esort || (n.keyword == "*CONTROL_SOLID" && n.approximated);
    slsfac = slsfac || (n.keyword == "*CONTROL_CONTACT" && n.approximated);
  }
  EXPECT_TRUE(esort);
  EXPECT_TRUE(slsfac);

  // PSFAIL erodes solids: refused unless allowed, with the file, line and keyword.
  const std::string e = error_of(two_cubes("*CONTROL_SOLID\n0,0,0,0,3\n"));
  EXPECT_NE(e.find("bad.k:14:"), std::string::npos) << e;
  EXPECT_NE(e.find("*CONTROL_SOLID"), std::string::npos) << e;
  EXPECT_NE(e.find("PSFAIL"), std::string::npos) << e;
}

// Reference: LS-DYNA Keyword User's Manual R13 Vol. I, *PART_CONTACT (a third card per part:
// FS FD DC VC OPTT SFT SSF) and *CONTACT_... FS = -1 (the parts' coefficients, *CONTROL_CONTACT's
// SFRIC where a part gives none, times FSF); FS -2 (a table) is refused with what is allowed.
TEST(LsDynaDeckImport, PartContactGivesTheFrictionOfContactsWithFsMinusOne) {
  test::ScratchDir dir;
  const std::string plain_parts = "*PART\nstriker\n1,1,1\n*PART\ntarget\n2,1,1\n";
  const auto deck = [&](const std::string& parts, const std::string& extra) {
    std::string d = two_cubes(extra);
    return d.replace(d.find(plain_parts), plain_parts.size(), parts);
  };
  const std::string parts =
      "*PART_CONTACT\nstriker\n1,1,1\n0.25\n*PART_CONTACT\ntarget\n2,1,1\n0.25,0.1\n";
  const std::string contact = "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n1,2,3,3\n-1.0\n";
  Imported im = import_text(dir, deck(parts, contact));
  ASSERT_EQ(im.scene.bodies.size(), 2u);
  EXPECT_EQ(im.scene.bodies[1].name, "target");
  ASSERT_EQ(im.scene.contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(im.scene.contacts[0].friction, 0.25);  // both parts' FS (DC 0)

  // Parts without FS take *CONTROL_CONTACT's SFRIC (0.4); FSF (0.5) scales it.
  im = import_text(dir, deck("*PART_CONTACT\nstriker\n1,1,1\n\n*PART_CONTACT\ntarget\n2,1,1\n\n",
                             "*CONTROL_CONTACT\n\n\n0.4\n" + contact + "0,0,0,0,0,0,0.5\n"));
  ASSERT_EQ(im.scene.contacts.size(), 1u);
  EXPECT_DOUBLE_EQ(im.scene.contacts[0].friction, 0.2);

  const std::string e =
      error_of(deck(parts, "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n1,2,3,3\n-2.0\n"));
  EXPECT_NE(e.find("FS -2"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: FS >= 0, or -1"), std::string::npos) << e;
}

}  // namespace
}  // namespace afemp::fem
