// Mesh importers (fem/mesh_import.hpp): one model, two 1 x 0.5 x 0.25 hexahedra sharing a face
// plus two trusses, written as Gmsh 4.1, Abaqus and LS-DYNA files, reads back with the exact
// coordinates, connectivity, parts, sets, areas and constraints the file states; every broken
// file is an InputError naming the file and the line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "afemp/errors.hpp"
#include "fem/mesh_import.hpp"
#include "scene_errors.hpp"
#include "scratch_dir.hpp"

namespace afemp::fem {
namespace {

// Box nodes 101..112 sit at x = i, y = 0.5 j, z = 0.25 k with label 101 + i + 3 j + 6 k; node
// 201 is the apex of the two trusses. All coordinates are exact in binary.
core::Vec3 expected_position(std::int64_t label) {
  if (label == 201) return {1.0, 0.25, 1.0};
  const std::int64_t n = label - 101;
  return {static_cast<double>(n % 3), 0.5 * static_cast<double>((n / 3) % 2),
          0.25 * static_cast<double>(n / 6)};
}

const std::vector<std::vector<std::int64_t>> kHexahedra = {
    {101, 102, 105, 104, 107, 108, 111, 110}, {102, 103, 106, 105, 108, 109, 112, 111}};
const std::vector<std::vector<std::int64_t>> kLines = {{107, 201}, {201, 109}};
constexpr double kHexVolume = 1.0 * 0.5 * 0.25;

// Volume of a hexahedron in the node order of fem/mesh.hpp, as six tetrahedra around the
// diagonal 0-6; each is positive for a right-handed element.
double hexahedron_volume(const MeshData& m, const Hexahedron& h) {
  const int tets[6][2] = {{1, 2}, {2, 3}, {3, 7}, {7, 4}, {4, 5}, {5, 1}};
  const core::Vec3& p0 = m.nodes[static_cast<std::size_t>(h[0])];
  const core::Vec3& p6 = m.nodes[static_cast<std::size_t>(h[6])];
  double v = 0.0;
  for (const auto& t : tets) {
    const core::Vec3 a = m.nodes[static_cast<std::size_t>(h[static_cast<std::size_t>(t[0])])] - p0;
    const core::Vec3 b = m.nodes[static_cast<std::size_t>(h[static_cast<std::size_t>(t[1])])] - p0;
    const double tet = core::dot(a, core::cross(b, p6 - p0)) / 6.0;
    EXPECT_GT(tet, 0.0) << "inverted tetrahedron: the element is not in the fem/mesh.hpp order";
    v += tet;
  }
  return v;
}

std::vector<std::int64_t> labels_of(const MeshData& m, const std::vector<std::int32_t>& nodes) {
  std::vector<std::int64_t> out;
  for (std::int32_t n : nodes) out.push_back(m.node_labels[static_cast<std::size_t>(n)]);
  return out;
}

template <std::size_t N>
std::vector<std::int64_t> labels_of(const MeshData& m, const std::array<std::int32_t, N>& e) {
  return labels_of(m, std::vector<std::int32_t>(e.begin(), e.end()));
}

// The geometry shared by the three files: exact coordinates (written with at most 3
// significant digits), connectivity by label, and each hexahedron's volume 0.125 to 1e-15.
void expect_two_hexahedra_and_two_trusses(const MeshData& m) {
  ASSERT_EQ(m.nodes.size(), 13u);
  ASSERT_EQ(m.node_labels.size(), 13u);
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const core::Vec3 x = expected_position(m.node_labels[i]);
    EXPECT_EQ(m.nodes[i].x, x.x) << "node " << m.node_labels[i];
    EXPECT_EQ(m.nodes[i].y, x.y) << "node " << m.node_labels[i];
    EXPECT_EQ(m.nodes[i].z, x.z) << "node " << m.node_labels[i];
  }
  ASSERT_EQ(m.hexahedra.size(), 2u);
  for (std::size_t e = 0; e < 2; ++e) {
    EXPECT_EQ(labels_of(m, m.hexahedra[e]), kHexahedra[e]);
    EXPECT_NEAR(hexahedron_volume(m, m.hexahedra[e]), kHexVolume, 1e-15);
  }
  ASSERT_EQ(m.lines.size(), 2u);
  for (std::size_t e = 0; e < 2; ++e) EXPECT_EQ(labels_of(m, m.lines[e]), kLines[e]);
}

const NamedSet* find_set(const std::vector<NamedSet>& sets, const std::string& name) {
  const auto it =
      std::find_if(sets.begin(), sets.end(), [&](const NamedSet& s) { return s.name == name; });
  return it == sets.end() ? nullptr : &*it;
}

std::vector<std::int64_t> node_set_labels(const MeshData& m, const std::string& name) {
  const NamedSet* s = find_set(m.node_sets, name);
  if (s == nullptr) {
    ADD_FAILURE() << "no node set '" << name << "'";
    return {};
  }
  auto labels = labels_of(m, s->members);
  std::sort(labels.begin(), labels.end());
  return labels;
}

// The constraint on the node set `name`, as {x, y, z} fixed flags.
std::array<bool, 3> fixed_on(const MeshData& m, const std::string& name) {
  for (const ImportedConstraint& c : m.constraints)
    if (m.node_sets[static_cast<std::size_t>(c.node_set)].name == name) return c.fixed;
  ADD_FAILURE() << "no constraint on '" << name << "'";
  return {false, false, false};
}

using test::line_of;

// The message of the InputError `f` throws ("" and a failure when it throws none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

const std::vector<std::int64_t> kBoxNodes = {101, 102, 103, 104, 105, 106,
                                             107, 108, 109, 110, 111, 112};
const std::vector<std::int64_t> kBaseNodes = {101, 104, 107, 110};  // the face x = 0

// ---------------------------------------------------------------------------------------------
// Gmsh 4.1: one volume entity (physical "BLOCK"), truss 1 on curve 1 ("TRUSS"), truss 2 on curve 2
// (no group), a quadrangle on the x = 0 face ("BASE", skipped but naming its nodes) and a point
// element on node 201 ("TIP"). Node 107 is stored parametric on curve 1.
const std::string kGmsh = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
0 4 "TIP"
1 2 "TRUSS"
2 3 "BASE"
3 1 "BLOCK"
$EndPhysicalNames
$Entities
1 2 1 1
1 1 0.25 1 1 4
1 0 0 0.25 1 0.25 1 1 2 0
2 1 0 0.25 2 0.25 1 0 0
1 0 0 0 0 0.5 0.25 1 3 0
1 0 0 0 2 0.5 0.25 1 1 0
$EndEntities
$Nodes
3 13 101 201
3 1 0 11
101
102
103
104
105
106
108
109
110
111
112
0 0 0
1 0 0
2 0 0
0 0.5 0
1 0.5 0
2 0.5 0
1 0 0.25
2 0 0.25
0 0.5 0.25
1 0.5 0.25
2 0.5 0.25
1 1 1 1
107
0 0 0.25 0
0 1 0 1
201
1 0.25 1
$EndNodes
$Elements
5 6 1 6
3 1 5 2
1 101 102 105 104 107 108 111 110
2 102 103 106 105 108 109 112 111
1 1 1 1
3 107 201
1 2 1 1
4 201 109
2 1 3 1
5 101 104 110 107
0 1 15 1
6 201
$EndElements
)";

TEST(GmshImport, TwoHexahedraAndTwoTrussesKeepCoordinatesPartsAndPhysicalGroups) {
  const MeshData m = parse_gmsh(kGmsh, "model.msh");
  expect_two_hexahedra_and_two_trusses(m);
  // Parts: the entity's physical group, or the entity when it has none.
  EXPECT_EQ(m.part_names, (std::vector<std::string>{"BLOCK", "TRUSS", "curve entity 2"}));
  EXPECT_EQ(m.hexahedron_part, (std::vector<std::int32_t>{0, 0}));
  EXPECT_EQ(m.line_part, (std::vector<std::int32_t>{1, 2}));
  EXPECT_EQ(m.line_area, (std::vector<double>{0.0, 0.0}));
  // A node set for every physical group; element sets for the volume and curve groups.
  ASSERT_EQ(m.node_sets.size(), 4u);
  EXPECT_EQ(node_set_labels(m, "TIP"), (std::vector<std::int64_t>{201}));
  EXPECT_EQ(node_set_labels(m, "TRUSS"), (std::vector<std::int64_t>{107, 201}));
  EXPECT_EQ(node_set_labels(m, "BASE"), kBaseNodes);
  EXPECT_EQ(node_set_labels(m, "BLOCK"), kBoxNodes);
  ASSERT_EQ(m.hexahedron_sets.size(), 1u);
  EXPECT_EQ(m.hexahedron_sets[0].name, "BLOCK");
  EXPECT_EQ(m.hexahedron_sets[0].members, (std::vector<std::int32_t>{0, 1}));
  ASSERT_EQ(m.line_sets.size(), 1u);
  EXPECT_EQ(m.line_sets[0].name, "TRUSS");
  EXPECT_EQ(m.line_sets[0].members, (std::vector<std::int32_t>{0}));
  EXPECT_TRUE(m.constraints.empty());
}

TEST(GmshImport, OtherVersionsAndBinaryFilesAreRejectedWithTheSettingToChange) {
  std::string v22 = kGmsh;
  v22.replace(v22.find("4.1 0 8"), 7, "2.2 0 8");
  const std::string old = input_error([&] { parse_gmsh(v22, "old.msh"); });
  EXPECT_NE(old.find("old.msh:2:"), std::string::npos) << old;
  EXPECT_NE(old.find("version 2.2"), std::string::npos) << old;
  EXPECT_NE(old.find("4.1"), std::string::npos) << old;

  std::string binary = kGmsh;
  binary.replace(binary.find("4.1 0 8"), 7, "4.1 1 8");
  const std::string bin = input_error([&] { parse_gmsh(binary, "bin.msh"); });
  EXPECT_NE(bin.find("bin.msh:2:"), std::string::npos) << bin;
  EXPECT_NE(bin.find("binary"), std::string::npos) << bin;
}

TEST(GmshImport, MalformedCoordinateAndMissingNodeNameTheirLines) {
  std::string bad = kGmsh;
  bad.replace(bad.find("2 0.5 0.25\n"), 10, "2 0.5 0.2x");
  const std::string number = input_error([&] { parse_gmsh(bad, "bad.msh"); });
  EXPECT_NE(number.find("bad.msh:" + std::to_string(line_of(bad, "2 0.5 0.2x")) + ":"),
            std::string::npos)
      << number;
  EXPECT_NE(number.find("'0.2x'"), std::string::npos) << number;

  std::string missing = kGmsh;
  missing.replace(missing.find("4 201 109"), 9, "4 201 999");
  const std::string node = input_error([&] { parse_gmsh(missing, "gap.msh"); });
  EXPECT_EQ(node, "gap.msh:" + std::to_string(line_of(missing, "4 201 999")) +
                      ": key '$Elements': element 4 lists node 999, which is not defined");
}

TEST(GmshImport, HeaderCountThatDisagreesWithTheBlocksIsAnError) {
  std::string bad = kGmsh;
  bad.replace(bad.find("5 6 1 6"), 7, "5 7 1 6");
  const std::string msg = input_error([&] { parse_gmsh(bad, "count.msh"); });
  EXPECT_NE(msg.find("count.msh:" + std::to_string(line_of(bad, "5 7 1 6")) + ":"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("announces 7 elements, the blocks hold 6"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------------
// Abaqus: mixed-case keywords, a continued element line, a skipped shell, GENERATE, a set made
// of sets, truss area from *SOLID SECTION, and *BOUNDARY by set, by node and by name.
const std::string kAbaqus = R"(*Heading
 two hexahedra and two trusses
** nodes
*NODE, NSET=BOX
101, 0.0, 0.0, 0.0
102, 1.0, 0.0, 0.0
103, 2.0, 0.0, 0.0
104, 0.0, 0.5, 0.0
105, 1.0, 0.5, 0.0
106, 2.0, 0.5, 0.0
107, 0.0, 0.0, 0.25
108, 1.0, 0.0, 0.25
109, 2.0, 0.0, 0.25
110, 0.0, 0.5, 0.25
111, 1.0, 0.5, 0.25
112, 2.0, 0.5, 0.25
*Node
201, 1., 0.25, 1.
*ELEMENT, TYPE=C3D8R,
 ELSET=BLOCK
1, 101, 102, 105, 104, 107, 108, 111, 110
2, 102, 103, 106, 105,
   108, 109, 112, 111
*Element, type=T3D2, elset=TRUSS
3, 107, 201
4, 201, 109
*Element, type=S4R, elset=SKIN
5, 101, 104, 110, 107
*Nset, nset=BASE, generate
101, 112, 3
*NSET, NSET=TOP
107, 108, 109, 110, 111, 112
*ELSET, ELSET=EVERYTHING
BLOCK, TRUSS, 5
*Solid Section, elset=TRUSS, material=STEEL
0.01,
*Solid Section, elset=BLOCK, material=STEEL
,
*Material, name=STEEL
*Elastic
210000., 0.3
*Boundary
BASE, 1, 3
103, 2
base, 5, 6
201, PINNED
TOP, ZSYMM
)";

TEST(AbaqusImport, TwoHexahedraAndTwoTrussesKeepCoordinatesSetsAreasAndConstraints) {
  const MeshData m = parse_abaqus(kAbaqus, "model.inp");
  expect_two_hexahedra_and_two_trusses(m);
  // Parts are the ELSET of *ELEMENT; the S4R shell is skipped.
  EXPECT_EQ(m.part_names, (std::vector<std::string>{"BLOCK", "TRUSS"}));
  EXPECT_EQ(m.hexahedron_part, (std::vector<std::int32_t>{0, 0}));
  EXPECT_EQ(m.line_part, (std::vector<std::int32_t>{1, 1}));
  EXPECT_EQ(m.line_area, (std::vector<double>{0.01, 0.01}));
  EXPECT_EQ(node_set_labels(m, "BOX"), kBoxNodes);
  EXPECT_EQ(node_set_labels(m, "BASE"), kBaseNodes);  // GENERATE 101..112 step 3
  EXPECT_EQ(node_set_labels(m, "TOP"), (std::vector<std::int64_t>{107, 108, 109, 110, 111, 112}));
  EXPECT_EQ(node_set_labels(m, "node 103"), (std::vector<std::int64_t>{103}));
  EXPECT_EQ(node_set_labels(m, "node 201"), (std::vector<std::int64_t>{201}));
  ASSERT_EQ(m.hexahedron_sets.size(), 2u);
  EXPECT_EQ(find_set(m.hexahedron_sets, "BLOCK")->members, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(find_set(m.hexahedron_sets, "EVERYTHING")->members, (std::vector<std::int32_t>{0, 1}));
  ASSERT_EQ(m.line_sets.size(), 2u);
  EXPECT_EQ(find_set(m.line_sets, "TRUSS")->members, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(find_set(m.line_sets, "EVERYTHING")->members, (std::vector<std::int32_t>{0, 1}));
  // Translations only: "base, 5, 6" (rotations) adds nothing; PINNED fixes 1-3, ZSYMM 3.
  ASSERT_EQ(m.constraints.size(), 4u);
  EXPECT_EQ(fixed_on(m, "BASE"), (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(fixed_on(m, "node 103"), (std::array<bool, 3>{false, true, false}));
  EXPECT_EQ(fixed_on(m, "node 201"), (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(fixed_on(m, "TOP"), (std::array<bool, 3>{false, false, true}));
}

TEST(AbaqusImport, MalformedNumberMissingNodeAndUnknownSetNameTheirLines) {
  std::string bad = kAbaqus;
  bad.replace(bad.find("110, 0.0, 0.5"), 13, "110, 0.0, O.5");
  const std::string number = input_error([&] { parse_abaqus(bad, "bad.inp"); });
  EXPECT_EQ(number, "bad.inp:" + std::to_string(line_of(bad, "110, 0.0, O.5")) +
                        ": key '*NODE': expected a finite number for a coordinate of node 110, "
                        "found 'O.5'");

  std::string missing = kAbaqus;
  missing.replace(missing.find("4, 201, 109"), 11, "4, 201, 199");
  const std::string node = input_error([&] { parse_abaqus(missing, "gap.inp"); });
  EXPECT_EQ(node, "gap.inp:" + std::to_string(line_of(missing, "4, 201, 199")) +
                      ": key '*ELEMENT': element 4 lists node 199, which is not defined");

  std::string unknown = kAbaqus;
  unknown.replace(unknown.find("TOP, ZSYMM"), 10, "LID, ZSYMM");
  const std::string set = input_error([&] { parse_abaqus(unknown, "set.inp"); });
  EXPECT_EQ(set, "set.inp:" + std::to_string(line_of(unknown, "LID, ZSYMM")) +
                     ": key '*BOUNDARY': node set 'LID' is not defined");
}

// ---------------------------------------------------------------------------------------------
// LS-DYNA: a card in fixed columns from the widths and values given (right-aligned).
std::string columns(const std::vector<int>& widths, const std::vector<std::string>& values) {
  std::ostringstream s;
  for (std::size_t i = 0; i < values.size(); ++i) s << std::setw(widths[i]) << values[i];
  return s.str() + "\n";
}

// Nodes in fixed columns (node 103 with a 16-character x that touches its label, so only a
// column reader gets it right) and in free format; solid 1 on one card, solid 2 in the legacy
// two-card form; a skipped shell and *SECTION_SOLID; truss area A of an ELFORM 3 section.
std::string lsdyna_deck() {
  const std::vector<int> node{8, 16, 16, 16};
  const std::vector<int> i8(10, 8);
  const std::vector<int> i10(8, 10);
  std::string k = "*KEYWORD\n*TITLE\ntwo hexahedra and two trusses\n$ nid x y z\n*NODE\n";
  k += columns(node, {"101", "0.0", "0.0", "0.0"});
  k += columns(node, {"102", "1.0", "0.0", "0.0"});
  k += "     1032.00000000000000             0.0             0.0\n";
  k += columns(node, {"104", "0.0", "5.0e-01", "0.0"});
  k += columns(node, {"105", "1.0", "0.5", "0.0"});
  k += columns(node, {"106", "2.0", "0.5", "0.0"});
  k += "107,0.0,0.0,0.25\n108, 1.0, 0.0, 0.25\n109,2.0,,0.25\n110,0,0.5,2.5D-1\n";
  k += columns(node, {"111", "1.0", "0.5", "0.25"});
  k += columns(node, {"112", "2.0", "0.5", "0.25"});
  k += columns(node, {"201", "1.0", "0.25", "1.0"});
  k += "*PART\n$ heading\nblock of steel\n$ pid secid mid\n";
  k += columns(i10, {"1", "1", "1"});
  k += "truss bars\n" + columns(i10, {"2", "2", "1"});
  k += "*SECTION_SOLID\n" + columns(i10, {"1", "1"});
  k += "*SECTION_BEAM\n" + columns(i10, {"2", "3"}) + columns(i10, {"0.01"});
  k += "*ELEMENT_SOLID\n";
  k += columns(i8, {"1", "1", "101", "102", "105", "104", "107", "108", "111", "110"});
  k += columns(i8, {"2", "1"});
  k += columns(i8, {"102", "103", "106", "105", "108", "109", "112", "111"});
  k += "*ELEMENT_BEAM\n" + columns(i8, {"3", "2", "107", "201"}) + "4,2,201,109\n";
  k += "*ELEMENT_SHELL\n" + columns(i8, {"5", "3", "101", "104", "110", "107"});
  k += "*SET_NODE_LIST\n" + columns(i10, {"1"}) + columns(i10, {"101", "104", "107", "110"});
  k += "*SET_NODE_LIST_TITLE\nTIP\n" + columns(i10, {"2"}) + columns(i10, {"201"});
  k += "*BOUNDARY_SPC_SET\n$ nsid cid dofx dofy dofz dofrx dofry dofrz\n";
  k += columns(i10, {"1", "0", "1", "1", "1", "1", "1", "1"});
  k += columns(i10, {"2", "0", "0", "0", "1"});
  k += "*BOUNDARY_SPC_NODE\n" + columns(i10, {"103", "0", "0", "1", "0"});
  k += "*END\n";
  return k;
}

TEST(LsDynaImport, TwoHexahedraAndTwoTrussesKeepCoordinatesPartsAreasAndConstraints) {
  const MeshData m = parse_lsdyna(lsdyna_deck(), "model.k");
  expect_two_hexahedra_and_two_trusses(m);
  // Part names are the *PART headings; the trusses' area is A of their ELFORM 3 section.
  EXPECT_EQ(m.part_names, (std::vector<std::string>{"block of steel", "truss bars"}));
  EXPECT_EQ(m.hexahedron_part, (std::vector<std::int32_t>{0, 0}));
  EXPECT_EQ(m.line_part, (std::vector<std::int32_t>{1, 1}));
  EXPECT_EQ(m.line_area, (std::vector<double>{0.01, 0.01}));
  ASSERT_EQ(m.node_sets.size(), 3u);
  EXPECT_EQ(node_set_labels(m, "set 1"), kBaseNodes);
  EXPECT_EQ(node_set_labels(m, "TIP"), (std::vector<std::int64_t>{201}));
  EXPECT_EQ(node_set_labels(m, "node 103"), (std::vector<std::int64_t>{103}));
  ASSERT_EQ(m.constraints.size(), 3u);
  EXPECT_EQ(fixed_on(m, "set 1"), (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(fixed_on(m, "TIP"), (std::array<bool, 3>{false, false, true}));
  EXPECT_EQ(fixed_on(m, "node 103"), (std::array<bool, 3>{false, true, false}));
}

TEST(LsDynaImport, MissingNodeDegenerateSolidAndMalformedNumberNameTheirLines) {
  const std::string deck = lsdyna_deck();
  const std::string solid1 = "       1       1     101";
  std::string missing = deck;
  missing.replace(missing.find(solid1), solid1.size(), "       7       1      99");
  EXPECT_EQ(input_error([&] { parse_lsdyna(missing, "gap.k"); }),
            "gap.k:" + std::to_string(line_of(missing, "       7       1      99")) +
                ": key '*ELEMENT_SOLID': element 7 lists node 99, which is not defined");

  // A wedge written as a hexahedron (n4 = n3, n8 = n7), in the two-card form.
  const std::string nodes2 = "     102     103     106     105     108     109     112     111";
  std::string wedge = deck;
  wedge.replace(wedge.find(nodes2), nodes2.size(),
                "     102     103     106     106     108     109     112     112");
  const std::string degenerate = input_error([&] { parse_lsdyna(wedge, "wedge.k"); });
  EXPECT_EQ(degenerate,
            "wedge.k:" + std::to_string(line_of(wedge, "     102     103     106     106")) +
                ": key '*ELEMENT_SOLID': element 2 repeats node 106: wedges and "
                "tetrahedra written as degenerate hexahedra are not supported");

  std::string bad = deck;
  bad.replace(bad.find("108, 1.0, 0.0, 0.25"), 19, "108, 1.0, 0.0, 0..25");
  EXPECT_EQ(input_error([&] { parse_lsdyna(bad, "bad.k"); }),
            "bad.k:" + std::to_string(line_of(bad, "108, 1.0")) +
                ": key '*NODE': expected a finite number for a coordinate of node 108, found "
                "'0..25'");
}

TEST(LsDynaImport, UnsupportedOptionOfAReadKeywordIsAnErrorNotSilentlySkipped) {
  std::string deck = lsdyna_deck();
  deck.replace(deck.find("*BOUNDARY_SPC_SET\n"), 18, "*BOUNDARY_SPC_SET_ID\n");
  const std::string msg = input_error([&] { parse_lsdyna(deck, "id.k"); });
  EXPECT_NE(msg.find("id.k:" + std::to_string(line_of(deck, "*BOUNDARY_SPC_SET_ID")) +
                     ": key '*BOUNDARY_SPC_SET_ID'"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("*BOUNDARY_SPC_SET,"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------------

TEST(MeshImport, ExtensionChoosesTheReaderAndAnUnknownOneListsTheAllowed) {
  const test::ScratchDir dir;
  for (const std::string& file :
       {dir.write("a.msh", kGmsh), dir.write("b.INP", kAbaqus), dir.write("c.k", lsdyna_deck()),
        dir.write("d.key", lsdyna_deck()), dir.write("e.dyn", lsdyna_deck())}) {
    SCOPED_TRACE(file);
    expect_two_hexahedra_and_two_trusses(read_mesh(file));
  }
  const std::string stl = dir.write("part.stl", "solid part\nendsolid part\n");
  const std::string msg = input_error([&] { read_mesh(stl); });
  EXPECT_EQ(msg, stl +
                     ": key 'mesh': unknown mesh file extension '.stl'; allowed: .msh (Gmsh 4.1 "
                     "ASCII), .inp (Abaqus), .k, .key, .dyn (LS-DYNA keyword)");
  const std::string absent = dir.file("absent.msh");
  EXPECT_EQ(input_error([&] { read_mesh(absent); }),
            absent + ": key 'mesh': cannot open the mesh file");
}

}  // namespace
}  // namespace afemp::fem
