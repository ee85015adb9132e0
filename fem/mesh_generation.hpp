// Structured meshes generated from the scene's shapes: boxes of hexahedra, O-grid cylinders
// (a blended square core inside a ring, so no element is degenerate at the axis), truss lines and
// two-way rebar mats of 2-node trusses. Bad sizes or counts throw std::invalid_argument.
#pragma once

#include <array>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/scene.hpp"
#include "fem/mesh.hpp"

namespace afemp::fem {

// An axis-aligned box divided into divisions[d] equal hexahedra along axis d, all in one part
// "mesh" (callers rename part_names[0]). Node sets "xmin", "xmax", "ymin", "ymax", "zmin" and
// "zmax" hold the nodes of each face.
MeshData box_mesh(const core::BoxShape& box, std::array<int, 3> divisions);

// A box with its node planes at lines[d] along axis d (increasing, at least two each; the box
// runs from the first to the last): a graded box, finer where the planes lie closer.
MeshData box_mesh(const std::array<std::vector<double>, 3>& lines);

// The node planes of an axis from lo to hi graded as [end, elements] segments, each divided
// evenly (the scene's graded box axes, core::MeshDensity::graded).
std::vector<double> graded_lines(double lo, const std::vector<std::array<double, 2>>& segments);

// The right-handed orthonormal frame (x, y, z = axis) in which a cylinder's cross-section is
// laid out: the global frame turned by the smallest rotation that takes the global z onto the
// axis (the identity for an axis along +z). Where that rotation is undefined, for an axis within
// 1e-6 of -z, it is the half turn about (1, 1, 0): x and y swap, so that a quarter (below) along
// -z occupies x >= 0, y >= 0 as one along +z does.
struct CylinderFrame {
  core::Vec3 x, y, z;
};
CylinderFrame cylinder_frame(const core::Vec3& axis);

// An O-grid cylinder: a square core of n_core x n_core hexahedra, its sides bowed outward so that
// its corners open to 120 degrees, surrounded by a ring n_ring elements thick that blends the
// core's boundary into the circle; 4 n_core elements round the circumference and n_axial along
// the axis. The core's half-width is chosen from n_core / n_ring (between 0.35 R and 0.6 R) so
// that core and ring elements are of similar size.
//
// `sectors` keeps 1 (a quarter: local angles 0..90 degrees), 2 (a half: 0..180) or 4 (the whole
// cylinder) of the cross-section, measured in cylinder_frame(c.axis); a quarter or half is exactly
// that part of the whole mesh, and needs an even n_core (the cut planes run along the core's
// midlines). For an axis along +z or -z the quarter occupies x >= 0, y >= 0.
//
// With an ogive nose (c.nose.crh > 0, core/ogive_nose.hpp; it needs a meplat > 0) the layers of
// nodes past the shank are the cross-section scaled by r(t) / R, so that the "top" disc is the
// meplat. The layers stay equally spaced along the axis, so the nose's elements narrow towards
// the tip: their width there is about meplat / (2 R) of the shank's, and the stable time step
// falls with it.
//
// One part "mesh". Node sets: "base" (the disc at c.base), "top" (the disc at c.base + length
// axis), "surface" (the curved surface); for sectors 1 and 2 "cut_0", the nodes on the plane
// through the axis and the local x (local y = 0), and for sector 1 also "cut_1", the nodes on the
// plane through the axis and the local y (local x = 0).
MeshData cylinder_mesh(const core::CylinderShape& c, int n_core, int n_ring, int n_axial,
                       int sectors = 4);

// A sphere of hexahedra (a cubed sphere): a cube core of half-width R / 2 divided into
// n/2 x n/2 x n/2 elements, its lattice point q (|q|_inf = m) moved to R/2 q ((1 - m/2) +
// m^2 / (2 |q|)), bowed halfway to a sphere at its surface, and on each of its faces a shell of n/4
// layers along the rays from the core's surface to the sphere (layer t of the ray from core point
// c: (1 - t) c + t R c/|c|), so every element layer follows the sphere and the surface nodes lie on
// it. n, the elements across the diameter, is a multiple of 4. `sectors` keeps 1 (the quarter x >=
// 0, y >= 0 about the centre), 2 (y >= 0) or 4 (the whole sphere). One part "mesh"; node sets
// "surface", and for the cuts "cut_0" (y = 0) and "cut_1" (x = 0).
MeshData sphere_mesh(const core::SphereShape& s, int n, int sectors = 4);

// A straight truss from a to b in `segments` equal 2-node lines of cross-section `area`, one
// part "mesh"; node sets "start" (the node at a) and "end" (at b).
MeshData truss_line(core::Vec3 a, core::Vec3 b, int segments, double area);

// Straight bars in the two in-plane directions of a plane normal to a coordinate axis.
struct RebarMat {
  core::Vec3 min, max;            // the box the mat spans (the concrete block)
  int normal_axis = 2;            // 0, 1, 2: the mat lies in a plane normal to this axis
  std::vector<double> positions;  // the planes' coordinates along normal_axis: one mat each
  double spacing = 0.0;           // between neighbouring parallel bars (axis to axis)
  double diameter = 0.0;          // of a bar; the truss area is pi d^2 / 4
  double cover = 0.0;             // from the box faces to the outermost bars' axes, in the plane
  double segment_length = 0.0;    // target truss length: a bar of length L gets ceil(L / this)
};

// Bars along each in-plane axis, that axis's part "bars along x" (y, z); the part of the lower
// axis comes first. Across a direction the bars lie between the cover lines, as many as the
// spacing allows, the leftover distance split equally between the two sides; along its length a
// bar runs from cover line to cover line. The two directions of a mat lie in the same plane,
// and crossing bars share no node: they are separate trusses, to be tied to the concrete, not to
// each other. Each entry of `positions` adds one such mat (a layer near each face of a slab);
// a part holds its direction's bars of every layer, layer by layer in the given order.
MeshData rebar_mat(const RebarMat& mat);

}  // namespace afemp::fem
