// Hexahedron shape measures and the mesh summary (fem/mesh_quality.hpp). The volume integrates
// det J with 2x2x2 Gauss points, exact for the trilinear map (det J has degree 2 in each natural
// coordinate); a split into tetrahedra is not, once a face is warped.
#include "fem/mesh_quality.hpp"

#include <algorithm>
#include <cmath>

namespace afemp::fem {

namespace {

// The node that differs from node a in natural coordinate d only.
constexpr int hex_neighbour(int a, int d) {
  for (int b = 0; b < 8; ++b) {
    bool match = kHexNatural[b][d] != kHexNatural[a][d];
    for (int e = 0; e < 3; ++e)
      if (e != d) match = match && kHexNatural[b][e] == kHexNatural[a][e];
    if (match) return b;
  }
  return -1;
}

constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                               {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kFaces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                              {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

double triple(const core::Vec3& a, const core::Vec3& b, const core::Vec3& c) {
  return core::dot(a, core::cross(b, c));
}

double exact_volume(const std::array<core::Vec3, 8>& x) {
  const double g = 1.0 / std::sqrt(3.0);
  double volume = 0.0;
  for (int p = 0; p < 8; ++p) {
    const double xi[3] = {kHexNatural[p][0] * g, kHexNatural[p][1] * g, kHexNatural[p][2] * g};
    core::Vec3 column[3];  // dx/dxi_d
    for (int a = 0; a < 8; ++a) {
      const double f[3] = {1.0 + kHexNatural[a][0] * xi[0], 1.0 + kHexNatural[a][1] * xi[1],
                           1.0 + kHexNatural[a][2] * xi[2]};
      column[0] += (kHexNatural[a][0] * f[1] * f[2] / 8.0) * x[a];
      column[1] += (kHexNatural[a][1] * f[0] * f[2] / 8.0) * x[a];
      column[2] += (kHexNatural[a][2] * f[0] * f[1] / 8.0) * x[a];
    }
    volume += triple(column[0], column[1], column[2]);  // unit Gauss weights
  }
  return volume;
}

}  // namespace

ElementQuality hexahedron_quality(const std::array<core::Vec3, 8>& x) {
  ElementQuality q;
  q.min_scaled_jacobian = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 8; ++a) {
    // Edge d points from node a the way natural coordinate d increases: the corner Jacobian's
    // columns, up to a factor 1/2 that cancels.
    core::Vec3 e[3];
    double lengths = 1.0;
    for (int d = 0; d < 3; ++d) {
      e[d] = (-kHexNatural[a][d]) * (x[hex_neighbour(a, d)] - x[a]);
      lengths *= core::norm(e[d]);
    }
    const double scaled = lengths > 0.0 ? triple(e[0], e[1], e[2]) / lengths : 0.0;
    q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, scaled);
  }
  double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
  for (const auto& edge : kEdges) {
    const double l = core::norm(x[edge[1]] - x[edge[0]]);
    shortest = std::min(shortest, l);
    longest = std::max(longest, l);
  }
  q.aspect_ratio = longest / shortest;
  double largest_face = 0.0;
  for (const auto& f : kFaces)
    largest_face =
        std::max(largest_face, 0.5 * core::norm(core::cross(x[f[2]] - x[f[0]], x[f[3]] - x[f[1]])));
  q.volume = exact_volume(x);
  q.characteristic_length = largest_face > 0.0 ? q.volume / largest_face : 0.0;
  return q;
}

MeshQualityReport mesh_quality(const MeshData& mesh) {
  MeshQualityReport r;
  r.hexahedra = mesh.hexahedra.size();
  r.lines = mesh.lines.size();
  for (std::size_t e = 0; e < mesh.hexahedra.size(); ++e) {
    std::array<core::Vec3, 8> x;
    for (int a = 0; a < 8; ++a) x[a] = mesh.nodes[mesh.hexahedra[e][a]];
    const ElementQuality q = hexahedron_quality(x);
    const auto index = static_cast<std::int32_t>(e);
    if (q.min_scaled_jacobian < r.min_scaled_jacobian) {
      r.min_scaled_jacobian = q.min_scaled_jacobian;
      r.worst_jacobian_element = index;
    }
    if (q.aspect_ratio > r.max_aspect_ratio) {
      r.max_aspect_ratio = q.aspect_ratio;
      r.worst_aspect_element = index;
    }
    if (q.characteristic_length < r.min_characteristic_length) {
      r.min_characteristic_length = q.characteristic_length;
      r.smallest_element = index;
    }
    if (q.min_scaled_jacobian <= 0.0) ++r.inverted;
    r.total_volume += q.volume;
  }
  for (std::size_t e = 0; e < mesh.lines.size(); ++e) {
    const double l = core::norm(mesh.nodes[mesh.lines[e][1]] - mesh.nodes[mesh.lines[e][0]]);
    if (l < r.min_line_length) {
      r.min_line_length = l;
      r.shortest_line = static_cast<std::int32_t>(e);
    }
  }
  return r;
}

}  // namespace afemp::fem
