// Boundary faces and node normals of hexahedral meshes (surface_faces.hpp). A face is on the
// boundary when exactly one live hexahedron has it: the faces are compared by their sorted
// node ids once per mesh (link_faces), and each later search is one sweep of the live flags;
// its area vector is half the cross product of its diagonals, turned to point away from its
// element's centroid, and each of its nodes adds it. The faces of all sets are gathered set
// after set (boundary_faces over the sets).
#include "fem/surface_faces.hpp"

#include <algorithm>
#include <tuple>

namespace afemp::fem {

namespace {

// The six faces of a hexahedron in the node order of core::CellKind::hexahedron.
constexpr int hex_faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

}  // namespace

namespace {

struct Links {
  std::vector<std::array<std::int32_t, 6>> across;
  std::vector<std::int32_t> shared_offsets{0}, shared_faces;
};

// Faces compared by their sorted node ids: one sort of all faces, once per mesh.
Links find_links(const HexElements& hexes) {
  using Key = std::array<std::int32_t, 4>;
  std::vector<std::pair<Key, std::int32_t>> all;  // sorted ids, 6 e + face
  all.reserve(6 * hexes.size());
  for (std::size_t e = 0; e < hexes.size(); ++e)
    for (int f = 0; f < 6; ++f) {
      Key key;
      for (int a = 0; a < 4; ++a)
        key[static_cast<std::size_t>(a)] =
            hexes.nodes[e][static_cast<std::size_t>(hex_faces[f][a])];
      std::sort(key.begin(), key.end());
      all.emplace_back(key, static_cast<std::int32_t>(6 * e) + f);
    }
  std::sort(all.begin(), all.end());
  Links out;
  out.across.assign(hexes.size(), {-1, -1, -1, -1, -1, -1});
  auto at = [&](std::int32_t ef) -> std::int32_t& {
    return out.across[static_cast<std::size_t>(ef / 6)][static_cast<std::size_t>(ef % 6)];
  };
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i + 1;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    if (j - i == 2) {
      at(all[i].second) = all[i + 1].second / 6;
      at(all[i + 1].second) = all[i].second / 6;
    } else if (j - i > 2) {
      const auto g = static_cast<std::int32_t>(out.shared_offsets.size() - 1);
      for (std::size_t k = i; k < j; ++k) {
        at(all[k].second) = -2 - g;
        out.shared_faces.push_back(all[k].second);
      }
      out.shared_offsets.push_back(static_cast<std::int32_t>(out.shared_faces.size()));
    }
    i = j;
  }
  return out;
}

void sweep(const HexElements& hexes, const std::vector<char>& selected,
           const std::vector<std::array<std::int32_t, 6>>& across,
           const std::vector<std::int32_t>& shared_offsets,
           const std::vector<std::int32_t>& shared_faces, std::int32_t set, SurfaceFaces& out) {
  // The elements that count: live ones of the selected bodies.
  std::vector<char> counts(hexes.size(), 0);
  for (const fem::ElementBatch& b : hexes.batches)
    if (selected[static_cast<std::size_t>(b.body)])
      for (std::size_t e = b.begin; e < b.end; ++e) counts[e] = hexes.alive[e] ? 1 : 0;
  for (std::size_t e = 0; e < hexes.size(); ++e) {
    if (!counts[e]) continue;
    for (int f = 0; f < 6; ++f) {
      const std::int32_t other = across[e][static_cast<std::size_t>(f)];
      bool boundary = other == -1 || (other >= 0 && !counts[static_cast<std::size_t>(other)]);
      if (other <= -2) {  // exactly one counting element of the group has it
        const auto g = static_cast<std::size_t>(-2 - other);
        int n = 0;
        for (std::int32_t k = shared_offsets[g]; k < shared_offsets[g + 1]; ++k)
          n += counts[static_cast<std::size_t>(shared_faces[static_cast<std::size_t>(k)] / 6)];
        boundary = n == 1;
      }
      if (!boundary) continue;
      out.nodes.push_back({hexes.nodes[e][static_cast<std::size_t>(hex_faces[f][0])],
                           hexes.nodes[e][static_cast<std::size_t>(hex_faces[f][1])],
                           hexes.nodes[e][static_cast<std::size_t>(hex_faces[f][2])],
                           hexes.nodes[e][static_cast<std::size_t>(hex_faces[f][3])]});
      out.element.push_back(static_cast<std::int32_t>(e));
      out.set.push_back(set);
    }
  }
}

}  // namespace

void link_faces(HexElements& hexes) {
  Links l = find_links(hexes);
  hexes.across = std::move(l.across);
  hexes.shared_offsets = std::move(l.shared_offsets);
  hexes.shared_faces = std::move(l.shared_faces);
}

void boundary_faces(const HexElements& hexes, const std::vector<char>& selected, std::int32_t set,
                    SurfaceFaces& faces) {
  if (hexes.across.size() == hexes.size() && !hexes.shared_offsets.empty()) {
    sweep(hexes, selected, hexes.across, hexes.shared_offsets, hexes.shared_faces, set, faces);
    return;
  }
  const Links l = find_links(hexes);  // elements assembled by hand, not linked
  sweep(hexes, selected, l.across, l.shared_offsets, l.shared_faces, set, faces);
}

SurfaceFaces boundary_faces(const HexElements& hexes, const std::vector<char>& selected) {
  SurfaceFaces faces;
  boundary_faces(hexes, selected, 0, faces);
  return faces;
}

SurfaceFaces boundary_faces(std::span<ElementSet* const> sets, const std::vector<char>& selected) {
  SurfaceFaces faces;
  for (std::size_t i = 0; i < sets.size(); ++i)
    sets[i]->boundary_faces(selected, static_cast<std::int32_t>(i), faces);
  return faces;
}

void HexahedronSet::boundary_faces(const std::vector<char>& selected, std::int32_t set,
                                   SurfaceFaces& faces) const {
  fem::boundary_faces(*this, selected, set, faces);
}

core::Vec3 face_area_vector(const std::array<std::int32_t, 4>& q, const core::Vec3& centroid,
                            const std::vector<core::Vec3>& x) {
  auto at = [&](int a) { return x[static_cast<std::size_t>(q[static_cast<std::size_t>(a)])]; };
  core::Vec3 area = 0.5 * core::cross(at(2) - at(0), at(3) - at(1));
  const core::Vec3 centre = 0.25 * (at(0) + at(1) + at(2) + at(3));
  return core::dot(area, centre - centroid) < 0.0 ? -1.0 * area : area;
}

core::Vec3 face_area_vector(const SurfaceFaces& faces, std::size_t f, const HexElements& hexes,
                            const std::vector<core::Vec3>& x) {
  return face_area_vector(
      faces.nodes[f], mean_position(hexes.nodes[static_cast<std::size_t>(faces.element[f])], x), x);
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
