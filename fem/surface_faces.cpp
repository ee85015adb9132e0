// Boundary faces and node normals of hexahedral meshes (surface_faces.hpp). A face is on the
// boundary when exactly one live hexahedron has it (faces compared by their sorted node ids);
// its area vector is half the cross product of its diagonals, turned to point away from its
// hexahedron's centroid, and each of its nodes adds it.
#include "fem/surface_faces.hpp"

#include <algorithm>
#include <tuple>

namespace afemp::fem {

namespace {

// The six faces of a hexahedron in the node order of core::CellKind::hexahedron.
constexpr int hex_faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

}  // namespace

SurfaceFaces boundary_faces(const HexElements& hexes, const std::vector<char>& selected) {
  using Key = std::array<std::int32_t, 4>;
  std::vector<std::tuple<Key, Key, std::int32_t>> all;  // sorted ids, face, element
  for (const fem::ElementBatch& b : hexes.batches) {
    if (!selected[static_cast<std::size_t>(b.body)]) continue;
    for (std::size_t e = b.begin; e < b.end; ++e) {
      if (!hexes.alive[e]) continue;
      for (const auto& f : hex_faces) {
        Key face{hexes.nodes[e][static_cast<std::size_t>(f[0])],
                 hexes.nodes[e][static_cast<std::size_t>(f[1])],
                 hexes.nodes[e][static_cast<std::size_t>(f[2])],
                 hexes.nodes[e][static_cast<std::size_t>(f[3])]};
        Key key = face;
        std::sort(key.begin(), key.end());
        all.emplace_back(key, face, static_cast<std::int32_t>(e));
      }
    }
  }
  std::sort(all.begin(), all.end());
  SurfaceFaces out;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && std::get<0>(all[j]) == std::get<0>(all[i])) ++j;
    if (j - i == 1) {
      out.nodes.push_back(std::get<1>(all[i]));
      out.element.push_back(std::get<2>(all[i]));
    }
    i = j;
  }
  return out;
}

core::Vec3 face_area_vector(const SurfaceFaces& faces, std::size_t f, const HexElements& hexes,
                            const std::vector<core::Vec3>& x) {
  const auto& n = faces.nodes[f];
  auto at = [&](int a) { return x[static_cast<std::size_t>(n[static_cast<std::size_t>(a)])]; };
  core::Vec3 area = 0.5 * core::cross(at(2) - at(0), at(3) - at(1));
  core::Vec3 centroid, centre = 0.25 * (at(0) + at(1) + at(2) + at(3));
  for (std::int32_t k : hexes.nodes[static_cast<std::size_t>(faces.element[f])])
    centroid += 0.125 * x[static_cast<std::size_t>(k)];
  return core::dot(area, centre - centroid) < 0.0 ? -1.0 * area : area;
}

void surface_normals(const SurfaceFaces& faces, const HexElements& hexes,
                     const std::vector<core::Vec3>& x, std::vector<core::Vec3>& normal) {
  normal.assign(x.size(), core::Vec3{});
  for (std::size_t f = 0; f < faces.nodes.size(); ++f) {
    const core::Vec3 area = face_area_vector(faces, f, hexes, x);
    for (std::int32_t k : faces.nodes[f]) normal[static_cast<std::size_t>(k)] += area;
  }
  for (core::Vec3& v : normal) {
    const double l = core::norm(v);
    if (l > 0.0) v = (1.0 / l) * v;
  }
}

}  // namespace afemp::fem
