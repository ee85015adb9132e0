// Boundary faces of hexahedral meshes (fem/surface_faces.cpp): the face links found once and
// swept as elements die.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/scene.hpp"
#include "fem/fe_solver.hpp"
#include "fem/surface_faces.hpp"

namespace afemp::fem {
namespace {

using Face = std::array<std::int32_t, 4>;

std::vector<Face> sorted_faces(const SurfaceFaces& s) {
  std::vector<Face> out;
  for (Face f : s.nodes) {
    std::sort(f.begin(), f.end());
    out.push_back(f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Reference: counting. A box of 3 x 3 x 3 hexahedra has 6 x 9 = 54 boundary faces; without
// its centre element 54 + 6; without a corner element as well 60 - 3 + 3. Two bodies side by
// side (their own nodes) keep their own faces: selecting one gives its 54. The linked sweep
// gives the same faces as comparing all faces by sorting (elements not linked), each face
// once, with its live element.
TEST(SurfaceFaces, BoundaryFacesFollowTheLiveElements) {
  const std::string text =
      "[run]\nend_time = 1\n"
      "[materials.steel]\ndensity = 7.85e-3\nE = 2.1e5\nnu = 0.3\n"
      "[[bodies]]\nname = \"a\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [0, 0, 0], max = [3, 3, 3] } }\nmesh = { divisions = [3, 3, 3] }\n"
      "[[bodies]]\nname = \"b\"\ndiscretisation = \"hexahedra\"\nmaterial = \"steel\"\n"
      "shape = { box = { min = [3, 0, 0], max = [6, 3, 3] } }\nmesh = { divisions = [3, 3, 3] }\n";
  const core::Scene scene = core::parse_scene(text, "faces.toml");
  FeSolver solver(scene);
  HexElements& hexes = solver.mutable_hexahedra();
  ASSERT_EQ(hexes.across.size(), 54u);
  HexElements unlinked = hexes;
  unlinked.across.clear();
  unlinked.shared_offsets.clear();
  unlinked.shared_faces.clear();
  const std::vector<char> first{1, 0}, both{1, 1};
  auto check = [&](std::size_t expected) {
    const SurfaceFaces linked = boundary_faces(hexes, first);
    unlinked.alive = hexes.alive;
    EXPECT_EQ(linked.nodes.size(), expected);
    EXPECT_EQ(sorted_faces(linked), sorted_faces(boundary_faces(unlinked, first)));
    for (std::size_t f = 0; f < linked.nodes.size(); ++f) {
      const auto e = static_cast<std::size_t>(linked.element[f]);
      EXPECT_TRUE(hexes.alive[e]);
      EXPECT_LT(e, 27u);
      for (std::int32_t k : linked.nodes[f])
        EXPECT_NE(std::find(hexes.nodes[e].begin(), hexes.nodes[e].end(), k), hexes.nodes[e].end());
    }
    EXPECT_EQ(sorted_faces(boundary_faces(hexes, both)),
              sorted_faces(boundary_faces(unlinked, both)));
  };
  check(54);
  // The centre element of body a: the one whose centroid is (1.5, 1.5, 1.5).
  const FeNodes& nodes = solver.nodes();
  auto element_at = [&](const Vec3& c) {
    for (std::size_t e = 0; e < 27; ++e) {
      Vec3 m;
      for (std::int32_t k : hexes.nodes[e])
        m += 0.125 * nodes.position[static_cast<std::size_t>(k)];
      if (core::norm(m - c) < 1e-9) return e;
    }
    ADD_FAILURE() << "no element at the point";
    return std::size_t{0};
  };
  hexes.alive[element_at({1.5, 1.5, 1.5})] = 0;
  check(60);
  hexes.alive[element_at({0.5, 0.5, 0.5})] = 0;
  check(60);
}

}  // namespace
}  // namespace afemp::fem
