// Points inside a body's hexahedra, for the run's check for bodies that come to overlap with no
// contact between them (core/contact_warnings.hpp): a cell hash over the live elements' boxes,
// then, for each point in a candidate's box, the element's trilinear map inverted by Newton's
// method (natural coordinates within [-1, 1]^3). Points on the body's outer surface (bodies
// that touch) do not count; points on a face, edge or corner between its elements do.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "afemp/tensor.hpp"
#include "fem/hexahedron_set.hpp"

namespace afemp::fem {

// How many of `points` lie inside the live hexahedra of body `body`, whose nodes are at
// `node_position`.
std::size_t points_inside(const HexElements& hexes, std::span<const core::Vec3> node_position,
                          int body, std::span<const core::Vec3> points);

// Where a point lies in a body's hexahedra: the element (an index into the hexahedra) and the
// point's natural coordinates there, or element -1 when no live element of the body holds it.
struct HostPoint {
  std::int32_t element = -1;
  std::array<double, 3> xi{};
};
// For each of `points`: the live hexahedron of body `body` that holds it (the lowest-numbered
// of those whose faces it lies on), found as points_inside finds them.
std::vector<HostPoint> locate_points(const HexElements& hexes,
                                     std::span<const core::Vec3> node_position, int body,
                                     std::span<const core::Vec3> points);

}  // namespace afemp::fem
