// Generated meshes against the geometry they stand for: box volumes and faces, the O-grid
// cylinder's volume (the inscribed polygon prism, converging as h^2 to pi R^2 L), its surface
// radius, cut planes and element shape; truss lengths; rebar positions from cover and spacing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/mesh_generation.hpp"
#include "fem/mesh_quality.hpp"

namespace afemp::fem {
namespace {

using core::Vec3;

const NamedSet& node_set(const MeshData& m, const std::string& name) {
  for (const NamedSet& s : m.node_sets)
    if (s.name == name) return s;
  throw std::runtime_error("no node set " + name);
}

bool has_node_set(const MeshData& m, const std::string& name) {
  return std::any_of(m.node_sets.begin(), m.node_sets.end(),
                     [&](const NamedSet& s) { return s.name == name; });
}

// Smallest distance between two nodes (all pairs; the meshes here have a few thousand nodes).
double closest_pair(const MeshData& m) {
  double best = INFINITY;
  for (std::size_t a = 0; a < m.nodes.size(); ++a)
    for (std::size_t b = a + 1; b < m.nodes.size(); ++b)
      best = std::min(best, core::norm(m.nodes[a] - m.nodes[b]));
  return best;
}

template <class F>
std::string error_of(F&& make) {
  try {
    make();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(BoxMesh, CountsVolumeAndShapeMatchTheBox) {
  // Reference: (n+1)^3-type counts, V = 2 x 1 x 4 = 8 (1e-12 relative), right-angled elements
  // (scaled Jacobian 1) of size 0.5 x 1/3 x 0.8 (aspect 0.8 / (1/3) = 2.4).
  const MeshData m = box_mesh({{1, 2, 3}, {3, 3, 7}}, {4, 3, 5});
  EXPECT_NO_THROW(validate(m, "box"));
  EXPECT_EQ(m.nodes.size(), 5u * 4u * 6u);
  EXPECT_EQ(m.hexahedra.size(), 4u * 3u * 5u);
  ASSERT_EQ(m.part_names.size(), 1u);
  EXPECT_EQ(m.part_names[0], "mesh");
  const MeshQualityReport r = mesh_quality(m);
  EXPECT_NEAR(r.total_volume, 8.0, 1e-12 * 8.0);
  EXPECT_NEAR(r.min_scaled_jacobian, 1.0, 1e-12);
  EXPECT_NEAR(r.max_aspect_ratio, 2.4, 1e-12);
  EXPECT_EQ(r.inverted, 0u);
  EXPECT_GT(closest_pair(m), 1e-9);
}

TEST(BoxMesh, FaceSetsHoldExactlyTheNodesOnEachFace) {
  // Reference: a face normal to axis d holds the product of the other two (n + 1); every member
  // lies on the face exactly, and no other node does.
  const core::BoxShape box{{-1, 0, 2}, {1, 3, 2.5}};
  const std::array<int, 3> n{2, 3, 4};
  const MeshData m = box_mesh(box, n);
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      const NamedSet& s = node_set(m, names[2 * d + side]);
      const double face = side == 0 ? box.min[d] : box.max[d];
      EXPECT_EQ(s.members.size(),
                static_cast<std::size_t>((n[(d + 1) % 3] + 1) * (n[(d + 2) % 3] + 1)));
      std::set<std::int32_t> members(s.members.begin(), s.members.end());
      for (std::size_t v = 0; v < m.nodes.size(); ++v)
        EXPECT_EQ(members.count(static_cast<std::int32_t>(v)) == 1, m.nodes[v][d] == face);
    }
}

TEST(BoxMesh, RejectsMissingDivisionsAndEmptyBoxes) {
  EXPECT_NE(error_of([] {
              box_mesh({{0, 0, 0}, {1, 1, 1}}, {2, 0, 2});
            }).find("along y"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              box_mesh({{0, 0, 1}, {1, 1, 1}}, {1, 1, 1});
            }).find("along z"),
            std::string::npos);
}

TEST(BoxMesh, GradedAxesPlaceTheNodePlanesOfTheirSegments) {
  // Reference: x as [[1, 4], [4, 3]] from 0 puts planes every 0.25 to 1, then every 1 to 4;
  // y and z even. Volume 4 x 1 x 2 = 8 (1e-12), 7 x 2 x 2 elements, every element a right
  // box (scaled Jacobian 1), the largest aspect 1 / 0.25 = 4.
  const std::vector<double> x = graded_lines(0.0, {{1.0, 4.0}, {4.0, 3.0}});
  const std::vector<double> expected{0, 0.25, 0.5, 0.75, 1, 2, 3, 4};
  ASSERT_EQ(x.size(), expected.size());
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], expected[i], 1e-15);
  const MeshData m = box_mesh({x, {0.0, 0.5, 1.0}, {0.0, 1.0, 2.0}});
  EXPECT_NO_THROW(validate(m, "graded box"));
  EXPECT_EQ(m.hexahedra.size(), 7u * 2u * 2u);
  const MeshQualityReport r = mesh_quality(m);
  EXPECT_NEAR(r.total_volume, 8.0, 1e-12 * 8.0);
  EXPECT_NEAR(r.min_scaled_jacobian, 1.0, 1e-12);
  EXPECT_NEAR(r.max_aspect_ratio, 4.0, 1e-12);
  EXPECT_EQ(node_set(m, "xmax").members.size(), 3u * 3u);
  EXPECT_NE(error_of([] {
              box_mesh({std::vector<double>{0.0, 0.5, 0.5, 1.0}, std::vector<double>{0.0, 1.0},
                        std::vector<double>{0.0, 1.0}});
            }).find("increase along x"),
            std::string::npos);
}

// Exact volume of the mesh of a cylinder: the cross-section's boundary is the inscribed polygon
// with 4 n_core chords round the full circle, tiled exactly by straight-sided quadrilaterals
// (a quarter or half is that fraction of the polygon, its cut edges through the centre).
double polygon_prism_volume(double radius, double length, int n_core, int sectors) {
  const int chords = 4 * n_core;
  return sectors / 4.0 * chords / 2.0 * radius * radius *
         std::sin(2.0 * std::numbers::pi / chords) * length;
}

TEST(CylinderMesh, VolumeIsTheInscribedPolygonPrism) {
  // Reference: polygon_prism_volume above, for full, half and quarter meshes; 1e-12 relative.
  const core::CylinderShape c{{0.5, -1, 2}, {0, 0, 1}, 2.5, 7.0, {}};
  for (int sectors : {1, 2, 4})
    for (auto [n_core, n_ring] : {std::pair{2, 1}, std::pair{4, 3}, std::pair{6, 2}}) {
      const MeshData m = cylinder_mesh(c, n_core, n_ring, 3, sectors);
      EXPECT_NO_THROW(validate(m, "cylinder"));
      const double exact = polygon_prism_volume(c.radius, c.length, n_core, sectors);
      EXPECT_NEAR(mesh_quality(m).total_volume, exact, 1e-12 * exact)
          << "sectors " << sectors << ", n_core " << n_core << ", n_ring " << n_ring;
    }
}

TEST(CylinderMesh, VolumeConvergesAtSecondOrderToTheCylinder) {
  // Reference: pi R^2 L times the sector fraction. The chords' error is O(h^2): doubling n_core
  // divides it by 4 (3.9..4.1 allowed, the O(h^4) term shifts it by ~1 %), and n_core = 8
  // (32 chords) is within 1 %.
  const core::CylinderShape c{{0, 0, 0}, {0, 0, 1}, 1.0, 2.0, {}};
  for (int sectors : {1, 2, 4}) {
    const double exact = sectors / 4.0 * std::numbers::pi * c.radius * c.radius * c.length;
    double previous = 0.0;
    for (int n_core : {4, 8, 16}) {
      const double error =
          std::abs(mesh_quality(cylinder_mesh(c, n_core, n_core / 2, 2, sectors)).total_volume -
                   exact) /
          exact;
      std::printf("cylinder sectors %d n_core %2d: relative volume error %.3e", sectors, n_core,
                  error);
      if (previous > 0.0) {
        std::printf(", ratio %.3f", previous / error);
        EXPECT_NEAR(previous / error, 4.0, 0.1);
      }
      std::printf("\n");
      if (n_core == 8) {
        EXPECT_LT(error, 0.01);
      }
      previous = error;
    }
  }
}

TEST(CylinderMesh, QuarterAndHalfAreExactPartsOfTheFullMesh) {
  // Reference: the sectors are cut from the same layout, so 4 V_quarter = 2 V_half = V_full to
  // roundoff (1e-13 relative); node and element counts: the full mesh has
  // ((n+1)^2 + 4 n n_ring)(n_axial + 1) nodes and (n^2 + 4 n n_ring) n_axial hexahedra.
  const core::CylinderShape c{{0, 0, 0}, {0, 0, 1}, 3.0, 1.0, {}};
  const int n = 6, ring = 3, axial = 4;
  const MeshData full = cylinder_mesh(c, n, ring, axial, 4);
  EXPECT_EQ(full.nodes.size(),
            static_cast<std::size_t>(((n + 1) * (n + 1) + 4 * n * ring) * (axial + 1)));
  EXPECT_EQ(full.hexahedra.size(), static_cast<std::size_t>((n * n + 4 * n * ring) * axial));
  const MeshData quarter = cylinder_mesh(c, n, ring, axial, 1);
  EXPECT_EQ(quarter.hexahedra.size(), full.hexahedra.size() / 4);
  EXPECT_EQ(quarter.nodes.size(),
            static_cast<std::size_t>(((n / 2 + 1) * (n / 2 + 1) + (n + 1) * ring) * (axial + 1)));
  const double v_full = mesh_quality(full).total_volume;
  EXPECT_NEAR(4.0 * mesh_quality(quarter).total_volume, v_full, 1e-13 * v_full);
  EXPECT_NEAR(2.0 * mesh_quality(cylinder_mesh(c, n, ring, axial, 2)).total_volume, v_full,
              1e-13 * v_full);
}

// Local (x, y, axial) coordinates of p in the cylinder's frame.
Vec3 local(const core::CylinderShape& c, const Vec3& p) {
  const CylinderFrame f = cylinder_frame(c.axis);
  const Vec3 d = p - c.base;
  return {core::dot(d, f.x), core::dot(d, f.y), core::dot(d, f.z)};
}

// Checks the surface, base and top sets against the radius and length (1e-12 R), and that the
// surface holds one node per chord end and layer.
void expect_boundary_sets_on_the_cylinder(const core::CylinderShape& c, const MeshData& m,
                                          int n_core, int n_axial, int sectors) {
  const double tol = 1e-12 * c.radius;
  const NamedSet& surface = node_set(m, "surface");
  EXPECT_EQ(surface.members.size(),
            static_cast<std::size_t>((sectors * n_core + (sectors == 4 ? 0 : 1)) * (n_axial + 1)));
  for (std::int32_t v : surface.members) {
    const Vec3 q = local(c, m.nodes[v]);
    EXPECT_NEAR(std::hypot(q.x, q.y), c.radius, tol);
  }
  for (std::int32_t v : node_set(m, "base").members) EXPECT_NEAR(local(c, m.nodes[v]).z, 0.0, tol);
  for (std::int32_t v : node_set(m, "top").members)
    EXPECT_NEAR(local(c, m.nodes[v]).z, c.length, tol);
  EXPECT_EQ(node_set(m, "base").members.size() * (n_axial + 1), m.nodes.size());
  EXPECT_EQ(node_set(m, "top").members.size() * (n_axial + 1), m.nodes.size());
}

TEST(CylinderMesh, SurfaceBaseAndTopSetsLieOnTheCylinder) {
  const core::CylinderShape c{{1, 2, 3}, {0, 0, 1}, 5.0, 12.0, {}};
  for (int sectors : {1, 2, 4}) {
    SCOPED_TRACE(sectors);
    expect_boundary_sets_on_the_cylinder(c, cylinder_mesh(c, 4, 2, 5, sectors), 4, 5, sectors);
  }
}

TEST(CylinderMesh, ScaledJacobianStaysAboveOneHalfForAnyDivisions) {
  // Reference: the O-grid's worst corners are the three 120-degree corners at the core's corners
  // (sin 120 = 0.866); the bound asked of the mesher is 0.5. No element may be inverted. Axial
  // spacing 1 / n_core, close to the core spacing, so the aspect ratio printed is the section's.
  const core::CylinderShape c{{0, 0, 0}, {0, 0, 1}, 1.0, 1.0, {}};
  for (auto [n_core, n_ring] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{2, 6}, std::pair{4, 1},
                                std::pair{4, 2}, std::pair{4, 4}, std::pair{8, 2}, std::pair{8, 8},
                                std::pair{16, 4}, std::pair{3, 5}, std::pair{12, 2}}) {
    const MeshQualityReport r = mesh_quality(cylinder_mesh(c, n_core, n_ring, n_core));
    std::printf("cylinder n_core %2d n_ring %d: min scaled Jacobian %.3f, max aspect ratio %.2f\n",
                n_core, n_ring, r.min_scaled_jacobian, r.max_aspect_ratio);
    EXPECT_GT(r.min_scaled_jacobian, 0.5) << n_core << " x " << n_ring;
    // From two core divisions on, the bowed core beats a straight one (135 deg corners, 0.707).
    if (n_core >= 2) {
      EXPECT_GT(r.min_scaled_jacobian, 0.79) << n_core << " x " << n_ring;
    }
    EXPECT_EQ(r.inverted, 0u);
  }
}

TEST(CylinderMesh, OgiveNoseFollowsItsArcAndHoldsItsVolume) {
  // Hanchak's projectile as a quarter: R = 12.7, length 143.7, CRH 3 nose with a 4 mm meplat.
  // References: every node of the "surface" set lies on the profile (the shank's radius or the
  // arc r(t), core/ogive_nose.hpp) to 1e-12, as the O-grid's boundary does on the circle; the
  // "top" disc has the meplat's radius; the volume is pi R^2 L_shank + V_nose over 4, within
  // 1 % at 16 core divisions and 1 mm layers (the chords cost 0.3 %, the straight layers of
  // the nose a little more); no element is inverted.
  core::CylinderShape c{{0, 0, 0}, {0, 0, 1}, 12.7, 143.7, {}};
  c.nose = {3.0, 4.0};
  const double nose = core::ogive_nose_length(c.nose, c.radius), shank = c.length - nose;
  const MeshData m = cylinder_mesh(c, 16, 8, 144, 1);
  EXPECT_NO_THROW(validate(m, "ogive"));
  auto set = [&](const std::string& name) -> const std::vector<std::int32_t>& {
    for (const auto& s : m.node_sets)
      if (s.name == name) return s.members;
    ADD_FAILURE() << "no set " << name;
    return m.node_sets.front().members;
  };
  for (std::int32_t i : set("surface")) {
    const Vec3& x = m.nodes[static_cast<std::size_t>(i)];
    const double profile =
        x.z > shank ? core::ogive_radius(c.nose, c.radius, x.z - shank) : c.radius;
    EXPECT_NEAR(std::hypot(x.x, x.y), profile, 1e-12 * c.radius) << "node " << i;
  }
  double top_radius = 0.0;
  for (std::int32_t i : set("top")) {
    const Vec3& x = m.nodes[static_cast<std::size_t>(i)];
    top_radius = std::max(top_radius, std::hypot(x.x, x.y));
    EXPECT_NEAR(x.z, c.length, 1e-12 * c.length);
  }
  EXPECT_NEAR(top_radius, 2.0, 1e-12 * c.radius);
  const MeshQualityReport q = mesh_quality(m);
  const double exact =
      (std::numbers::pi * c.radius * c.radius * shank + core::ogive_nose_volume(c.nose, c.radius)) /
      4.0;
  std::printf(
      "ogive quarter: volume %.6g, exact %.6g, relative error %.2e; min scaled Jacobian "
      "%.3f\n",
      q.total_volume, exact, (q.total_volume - exact) / exact, q.min_scaled_jacobian);
  EXPECT_NEAR(q.total_volume, exact, 0.01 * exact);
  EXPECT_EQ(q.inverted, 0u);
  // A sharp tip would collapse the last layer: the mesher refuses it with a reason.
  c.nose.meplat = 0.0;
  EXPECT_NE(error_of([&] { cylinder_mesh(c, 4, 2, 10, 1); }).find("meplat"), std::string::npos);
}

TEST(CylinderMesh, NoTwoNodesCoincide) {
  // Reference: shared nodes are generated once: no two nodes closer than 1e-9 R.
  const core::CylinderShape c{{0, 0, 0}, {0, 0, 1}, 2.0, 1.0, {}};
  for (int sectors : {1, 2, 4})
    for (auto [n_core, n_ring] : {std::pair{2, 1}, std::pair{4, 3}}) {
      const MeshData m = cylinder_mesh(c, n_core, n_ring, 2, sectors);
      EXPECT_GT(closest_pair(m), 1e-9 * c.radius) << "sectors " << sectors << ", n_core " << n_core;
    }
}

TEST(CylinderMesh, CutSetsHoldExactlyTheNodesOnTheCutPlanes) {
  // Reference: the quarter lies in local x >= 0, y >= 0; cut_0 is the plane y = 0 and cut_1 the
  // plane x = 0 (members within 1e-12 R; every node within 1e-9 R of the plane is a member).
  // The half lies in y >= 0 and has cut_0 only; the full cylinder has no cut sets.
  for (const Vec3 axis : {Vec3{0, 0, 1}, Vec3{1, 1, 0}, Vec3{-0.3, 0.5, -0.8}}) {
    const core::CylinderShape c{{1, -1, 0.5}, axis, 2.0, 3.0, {}};
    for (int sectors : {1, 2}) {
      const MeshData m = cylinder_mesh(c, 4, 2, 2, sectors);
      const double tol = 1e-12 * c.radius;
      for (const Vec3& p : m.nodes) {
        EXPECT_GE(local(c, p).y, -tol);
        if (sectors == 1) {
          EXPECT_GE(local(c, p).x, -tol);
        }
      }
      auto check = [&](const char* name, int component) {
        const NamedSet& s = node_set(m, name);
        std::set<std::int32_t> members(s.members.begin(), s.members.end());
        for (std::size_t v = 0; v < m.nodes.size(); ++v) {
          const double off = std::abs(local(c, m.nodes[v])[component]);
          if (members.count(static_cast<std::int32_t>(v))) {
            EXPECT_LE(off, tol) << name;
          } else {
            EXPECT_GT(off, 1e-9 * c.radius) << name;
          }
        }
      };
      check("cut_0", 1);
      if (sectors == 1) check("cut_1", 0);
      EXPECT_EQ(has_node_set(m, "cut_1"), sectors == 1);
    }
    EXPECT_FALSE(has_node_set(cylinder_mesh(c, 4, 2, 2, 4), "cut_0"));
  }
}

TEST(CylinderMesh, QuarterAlongZOccupiesThePositiveQuadrant) {
  // Reference: for axis +z the local frame is the global one, so the quarter's nodes have
  // x >= 0 and y >= 0 exactly (the cut-plane nodes get exact zeros).
  const MeshData m = cylinder_mesh({{0, 0, 0}, {0, 0, 1}, 1.0, 1.0, {}}, 4, 2, 1, 1);
  for (const Vec3& p : m.nodes) {
    EXPECT_GE(p.x, 0.0);
    EXPECT_GE(p.y, 0.0);
  }
  for (std::int32_t v : node_set(m, "cut_0").members) EXPECT_EQ(m.nodes[v].y, 0.0);
  for (std::int32_t v : node_set(m, "cut_1").members) EXPECT_EQ(m.nodes[v].x, 0.0);
}

TEST(CylinderMesh, RotatedAxisGivesTheSameVolumeRadiiAndShapes) {
  // Reference: a rigid rotation and shift change neither volume (1e-12 relative) nor the radius
  // of the surface nodes nor the scaled Jacobian (1e-12).
  const core::CylinderShape along_z{{0, 0, 0}, {0, 0, 1}, 1.5, 4.0, {}};
  const core::CylinderShape tilted{{3, -2, 1}, {1, 1, 0}, 1.5, 4.0, {}};
  for (int sectors : {1, 4}) {
    const MeshQualityReport a = mesh_quality(cylinder_mesh(along_z, 6, 3, 4, sectors));
    const MeshData m = cylinder_mesh(tilted, 6, 3, 4, sectors);
    const MeshQualityReport b = mesh_quality(m);
    EXPECT_NEAR(b.total_volume, a.total_volume, 1e-12 * a.total_volume);
    EXPECT_NEAR(b.min_scaled_jacobian, a.min_scaled_jacobian, 1e-12);
    expect_boundary_sets_on_the_cylinder(tilted, m, 6, 4, sectors);
  }
}

TEST(CylinderFrame, IsTheSmallestRotationTakingZOntoTheAxis) {
  // Reference: +z gives the identity exactly; +x is reached by a quarter turn about y
  // (x -> -z, y -> y); -z by the half turn about (1, 1, 0) (x <-> y, -z); an axis tilted by 1e-3
  // from z moves the frame's x by about 1e-3 only. Every frame is orthonormal and right-handed
  // (1e-14).
  auto expect_vec = [](const Vec3& a, const Vec3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
  };
  const CylinderFrame id = cylinder_frame({0, 0, 1});
  EXPECT_EQ(id.x.x, 1.0);
  EXPECT_EQ(id.y.y, 1.0);
  EXPECT_EQ(id.x.y, 0.0);
  const CylinderFrame fx = cylinder_frame({2, 0, 0});
  expect_vec(fx.x, {0, 0, -1}, 1e-15);
  expect_vec(fx.y, {0, 1, 0}, 1e-15);
  const CylinderFrame down = cylinder_frame({0, 0, -1});
  expect_vec(down.x, {0, 1, 0}, 1e-15);
  expect_vec(down.y, {1, 0, 0}, 1e-15);
  expect_vec(cylinder_frame({1e-3, 0, 1}).x, {1, 0, -1e-3}, 1e-6);
  for (const Vec3 axis :
       {Vec3{1, 1, 0}, Vec3{-0.3, 0.5, -0.8}, Vec3{1e-4, 0, -1}, Vec3{0, -1, 0}}) {
    const CylinderFrame f = cylinder_frame(axis);
    expect_vec(f.z, (1.0 / core::norm(axis)) * axis, 1e-15);
    EXPECT_NEAR(core::dot(f.x, f.x), 1.0, 1e-14);
    EXPECT_NEAR(core::dot(f.y, f.y), 1.0, 1e-14);
    EXPECT_NEAR(core::dot(f.x, f.y), 0.0, 1e-14);
    EXPECT_NEAR(core::dot(f.x, f.z), 0.0, 1e-14);
    expect_vec(core::cross(f.x, f.y), f.z, 1e-14);
  }
}

TEST(CylinderMesh, RejectsInvalidInputWithAReason) {
  const core::CylinderShape c{{0, 0, 0}, {0, 0, 1}, 1.0, 1.0, {}};
  EXPECT_NE(error_of([&] { cylinder_mesh(c, 3, 1, 1, 1); }).find("even"), std::string::npos);
  EXPECT_NE(error_of([&] { cylinder_mesh(c, 4, 1, 1, 3); }).find("sectors"), std::string::npos);
  EXPECT_NE(error_of([&] { cylinder_mesh(c, 4, 0, 1); }).find("at least 1"), std::string::npos);
  EXPECT_NE(error_of([] {
              cylinder_mesh({{0, 0, 0}, {0, 0, 1}, 0.0, 1.0, {}}, 2, 1, 1);
            }).find("radius"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              cylinder_mesh({{0, 0, 0}, {0, 0, 0}, 1.0, 1.0, {}}, 2, 1, 1);
            }).find("axis"),
            std::string::npos);
}

TEST(TrussLine, SegmentsSplitTheChordEquallyAndCarryTheArea) {
  // Reference: 7 segments of |b - a| / 7 summing to |b - a| = sqrt(1 + 4 + 9) (1e-12 relative);
  // the ends are a and b exactly; every line carries the given area.
  const Vec3 a{1, -1, 0}, b{2, 1, 3};
  const MeshData m = truss_line(a, b, 7, 2.5e-4);
  EXPECT_NO_THROW(validate(m, "truss"));
  ASSERT_EQ(m.lines.size(), 7u);
  const double chord = std::sqrt(14.0);
  double total = 0.0;
  for (std::size_t e = 0; e < m.lines.size(); ++e) {
    const double l = core::norm(m.nodes[m.lines[e][1]] - m.nodes[m.lines[e][0]]);
    EXPECT_NEAR(l, chord / 7.0, 1e-12 * chord);
    EXPECT_EQ(m.line_area[e], 2.5e-4);
    total += l;
  }
  EXPECT_NEAR(total, chord, 1e-12 * chord);
  const Vec3 start = m.nodes[node_set(m, "start").members.at(0)];
  const Vec3 end = m.nodes[node_set(m, "end").members.at(0)];
  EXPECT_TRUE(start.x == a.x && start.y == a.y && start.z == a.z);
  EXPECT_TRUE(end.x == b.x && end.y == b.y && end.z == b.z);
  EXPECT_NE(error_of([&] { truss_line(a, a, 2, 1.0); }).find("differ"), std::string::npos);
  EXPECT_NE(error_of([&] { truss_line(a, b, 2, 0.0); }).find("area"), std::string::npos);
}

// The distinct values of coordinate d over the nodes of part `part`, sorted.
std::vector<double> bar_positions(const MeshData& m, int part, int d) {
  std::set<double> values;
  for (std::size_t e = 0; e < m.lines.size(); ++e)
    if (m.line_part[e] == part) values.insert(m.nodes[m.lines[e][0]][d]);
  return {values.begin(), values.end()};
}

TEST(RebarMat, BarsStartAtTheCoverWithEqualSpacingAndTheRightArea) {
  // A 1 x 0.6 x 0.3 block, mat at z = 0.05, spacing 0.1, cover 0.05, d = 12 mm-equivalent 0.012:
  // bars along x at y = 0.05..0.55 (6 bars of length 0.9, 9 segments of 0.1), bars along y at
  // x = 0.05..0.95 (10 bars of length 0.5, 5 segments). Total length 6 * 0.9 + 10 * 0.5 = 10.4;
  // area pi d^2 / 4. Each bar has its own nodes: 6 * 10 + 10 * 6 = 120. Tolerance 1e-12.
  RebarMat mat{{0, 0, 0}, {1, 0.6, 0.3}, 2, {0.05}, 0.1, 0.012, 0.05, 0.1};
  const MeshData m = rebar_mat(mat);
  EXPECT_NO_THROW(validate(m, "rebar"));
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"bars along x", "bars along y"}));
  EXPECT_EQ(m.lines.size(), 6u * 9u + 10u * 5u);
  EXPECT_EQ(m.nodes.size(), 120u);
  const std::vector<double> y_of_x_bars = bar_positions(m, 0, 1);
  const std::vector<double> x_of_y_bars = bar_positions(m, 1, 0);
  ASSERT_EQ(y_of_x_bars.size(), 6u);
  ASSERT_EQ(x_of_y_bars.size(), 10u);
  EXPECT_NEAR(y_of_x_bars.front(), 0.05, 1e-12);
  EXPECT_NEAR(x_of_y_bars.front(), 0.05, 1e-12);
  for (std::size_t i = 1; i < y_of_x_bars.size(); ++i)
    EXPECT_NEAR(y_of_x_bars[i] - y_of_x_bars[i - 1], 0.1, 1e-12);
  for (std::size_t i = 1; i < x_of_y_bars.size(); ++i)
    EXPECT_NEAR(x_of_y_bars[i] - x_of_y_bars[i - 1], 0.1, 1e-12);
  double total = 0.0;
  for (std::size_t e = 0; e < m.lines.size(); ++e) {
    total += core::norm(m.nodes[m.lines[e][1]] - m.nodes[m.lines[e][0]]);
    EXPECT_NEAR(m.line_area[e], std::numbers::pi * 0.012 * 0.012 / 4.0, 1e-18);
  }
  EXPECT_NEAR(total, 10.4, 1e-12);
  for (const Vec3& p : m.nodes) EXPECT_EQ(p.z, 0.05);
}

TEST(RebarMat, LeftoverWidthIsSplitEquallyBetweenTheSides) {
  // A mat normal to x (bars along y and z): across z the span between cover lines is
  // 1.0 - 2 * 0.05 = 0.9, room for 5 bars at 0.2 (0.8); the leftover 0.1 goes half to each side:
  // bars at z = 0.1, 0.3, ..., 0.9. Across y the span 0.4 holds 3 bars exactly (0.05, 0.25, 0.45).
  // Bars along z run from cover line to cover line: 0.05..0.95 in ceil(0.9 / 0.25) = 4 segments.
  RebarMat mat{{0, 0, 0}, {0.3, 0.5, 1.0}, 0, {0.15}, 0.2, 0.01, 0.05, 0.25};
  const MeshData m = rebar_mat(mat);
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"bars along y", "bars along z"}));
  const std::vector<double> z_of_y_bars = bar_positions(m, 0, 2);
  const std::vector<double> y_of_z_bars = bar_positions(m, 1, 1);
  ASSERT_EQ(z_of_y_bars.size(), 5u);
  ASSERT_EQ(y_of_z_bars.size(), 3u);
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_NEAR(z_of_y_bars[i], 0.1 + 0.2 * static_cast<double>(i), 1e-12);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(y_of_z_bars[i], 0.05 + 0.2 * static_cast<double>(i), 1e-12);
  std::size_t along_z = 0;
  for (std::size_t e = 0; e < m.lines.size(); ++e)
    if (m.line_part[e] == 1) {
      ++along_z;
      EXPECT_NEAR(core::norm(m.nodes[m.lines[e][1]] - m.nodes[m.lines[e][0]]), 0.9 / 4.0, 1e-12);
    }
  EXPECT_EQ(along_z, 3u * 4u);
  for (const Vec3& p : m.nodes) EXPECT_EQ(p.x, 0.15);
}

TEST(RebarMat, LayersRepeatTheSameMatInEachPlane) {
  // The block of the first test with mats at z = 0.05 and z = 0.25 (one near each face): every
  // layer is that test's mat, so twice its 104 trusses and 120 nodes and twice its bar length
  // 10.4; half the nodes lie in each plane, and the bars along x of both layers share part 0.
  RebarMat mat{{0, 0, 0}, {1, 0.6, 0.3}, 2, {0.05, 0.25}, 0.1, 0.012, 0.05, 0.1};
  const MeshData m = rebar_mat(mat);
  EXPECT_NO_THROW(validate(m, "rebar"));
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"bars along x", "bars along y"}));
  EXPECT_EQ(m.lines.size(), 2u * (6u * 9u + 10u * 5u));
  EXPECT_EQ(m.nodes.size(), 240u);
  std::size_t low = 0, high = 0, other = 0;
  for (const Vec3& p : m.nodes) {
    if (p.z == 0.05)
      ++low;
    else if (p.z == 0.25)
      ++high;
    else
      ++other;
  }
  EXPECT_EQ(low, 120u);
  EXPECT_EQ(high, 120u);
  EXPECT_EQ(other, 0u);
  double total = 0.0;
  std::size_t along_x = 0;
  for (std::size_t e = 0; e < m.lines.size(); ++e) {
    total += core::norm(m.nodes[m.lines[e][1]] - m.nodes[m.lines[e][0]]);
    along_x += m.line_part[e] == 0 ? 1 : 0;
  }
  EXPECT_NEAR(total, 20.8, 1e-12);
  EXPECT_EQ(along_x, 2u * 6u * 9u);
}

TEST(RebarMat, RejectsCoverSpacingAndPlaneOutsideTheBlock) {
  const RebarMat ok{{0, 0, 0}, {1, 1, 1}, 2, {0.5}, 0.1, 0.01, 0.05, 0.1};
  RebarMat bad = ok;
  bad.cover = 0.5;
  EXPECT_NE(error_of([&] { rebar_mat(bad); }).find("cover"), std::string::npos);
  bad = ok;
  bad.spacing = 0.0;
  EXPECT_NE(error_of([&] { rebar_mat(bad); }).find("spacing"), std::string::npos);
  bad = ok;
  bad.positions = {0.5, 1.5};
  EXPECT_NE(error_of([&] { rebar_mat(bad); }).find("position"), std::string::npos);
  bad.positions.clear();
  EXPECT_NE(error_of([&] { rebar_mat(bad); }).find("position"), std::string::npos);
  bad = ok;
  bad.normal_axis = 3;
  EXPECT_NE(error_of([&] { rebar_mat(bad); }).find("normal_axis"), std::string::npos);
  EXPECT_NO_THROW(rebar_mat(ok));
}

}  // namespace
}  // namespace afemp::fem

namespace afemp::fem {
namespace {

// Reference: the sphere's volume 4/3 pi R^3, approached from below by the faceted mesh (the
// surface nodes on the sphere, flat faces between them: a deficit of order (h / R)^2); a quarter
// holds exactly a quarter of the elements and volume; no element inverted or badly shaped.
// Pass: volume deficit below 0.5 % at 32 across and smaller at 64, surface nodes on the sphere
// to 1e-12 R, min scaled Jacobian above 0.6, no two nodes closer than 1e-9.
TEST(SphereMesh, CubedSphereFillsTheSphereWithWellShapedElements) {
  const core::SphereShape s{{1, 2, 3}, 2.0};
  const double exact = 4.0 / 3.0 * std::numbers::pi * 8.0;
  double previous = 1.0;
  for (int n : {32, 64}) {
    const MeshData whole = sphere_mesh(s, n, 4);
    EXPECT_NO_THROW(validate(whole, "sphere"));
    const MeshQualityReport r = mesh_quality(whole);
    const double deficit = 1.0 - r.total_volume / exact;
    std::printf("sphere, %d across: %zu hexahedra, volume deficit %.3e, min scaled Jacobian %.3f\n",
                n, whole.hexahedra.size(), deficit, r.min_scaled_jacobian);
    EXPECT_GT(deficit, 0.0);
    EXPECT_LT(deficit, n == 32 ? 0.005 : 0.5 * previous);
    previous = deficit;
    EXPECT_GT(r.min_scaled_jacobian, 0.6);
    EXPECT_EQ(r.inverted, 0u);
    for (std::int32_t k : whole.node_sets.at(0).members)
      EXPECT_NEAR(core::norm(whole.nodes[static_cast<std::size_t>(k)] - s.centre), 2.0, 2e-12);
    const MeshData quarter = sphere_mesh(s, n, 1);
    EXPECT_EQ(4 * quarter.hexahedra.size(), whole.hexahedra.size());
    EXPECT_NEAR(4.0 * mesh_quality(quarter).total_volume, r.total_volume, 1e-10 * exact);
    if (n == 32) {
      EXPECT_GT(closest_pair(whole), 1e-9);
    }
  }
  EXPECT_NE(error_of([&] { sphere_mesh(s, 30, 4); }).find("multiple of 4"), std::string::npos);
}

}  // namespace
}  // namespace afemp::fem
