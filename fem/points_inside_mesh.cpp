// Points inside a body's hexahedra (fem/points_inside_mesh.hpp).
#include "fem/points_inside_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "fem/mesh.hpp"

namespace afemp::fem {

namespace {

using core::Vec3;
using Corners = std::array<Vec3, 8>;

// In natural coordinates: a point within it of a face lies on the face.
constexpr double kOnFace = 1e-6;

struct Box {
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(const Vec3& p) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  }
  bool holds(const Vec3& p) const {
    for (int d = 0; d < 3; ++d)
      if (p[d] < lo[d] || p[d] > hi[d]) return false;
    return true;
  }
};

// The natural coordinates xi of p in the element with corners x (the node order of
// kHexNatural), by Newton's method from the centre: x(xi) = sum_a N_a(xi) x_a with
// N_a = (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a) / 8. False when it does not converge or the
// map is singular on the way (p far outside a distorted element).
bool natural_coordinates(const Corners& x, const Vec3& p, std::array<double, 3>& xi) {
  xi = {0.0, 0.0, 0.0};
  for (int iteration = 0; iteration < 30; ++iteration) {
    Vec3 r = -1.0 * p;
    std::array<Vec3, 3> g{};  // dx / dxi_j
    for (std::size_t a = 0; a < 8; ++a) {
      const double* s = kHexNatural[a];
      const double f0 = 1.0 + s[0] * xi[0], f1 = 1.0 + s[1] * xi[1], f2 = 1.0 + s[2] * xi[2];
      r += (0.125 * f0 * f1 * f2) * x[a];
      g[0] += (0.125 * s[0] * f1 * f2) * x[a];
      g[1] += (0.125 * f0 * s[1] * f2) * x[a];
      g[2] += (0.125 * f0 * f1 * s[2]) * x[a];
    }
    const double det = core::dot(g[0], core::cross(g[1], g[2]));
    if (!(std::abs(det) > 0.0)) return false;
    // Cramer's rule for J d = r, J's columns g.
    const std::array<double, 3> d = {core::dot(r, core::cross(g[1], g[2])) / det,
                                     core::dot(g[0], core::cross(r, g[2])) / det,
                                     core::dot(g[0], core::cross(g[1], r)) / det};
    double step = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      xi[k] -= d[k];
      step = std::max(step, std::abs(d[k]));
      if (!(std::abs(xi[k]) < 4.0)) return false;  // far outside: no need to converge
    }
    if (step < 1e-12) return true;
  }
  return false;
}

// A uniform grid of cells over the elements' boxes, each cell listing the elements whose box
// meets it.
class CellHash {
 public:
  CellHash(const std::vector<Box>& boxes, const Box& all, double cell) : lo_(all.lo), cell_(cell) {
    std::size_t cells = 1;
    for (int d = 0; d < 3; ++d) {
      n_[static_cast<std::size_t>(d)] =
          std::max<long>(1, static_cast<long>(std::ceil((all.hi[d] - all.lo[d]) / cell_)));
      cells *= static_cast<std::size_t>(n_[static_cast<std::size_t>(d)]);
    }
    offsets_.assign(cells + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::int64_t> fill(offsets_.begin(), offsets_.end() - 1);
      for (std::size_t e = 0; e < boxes.size(); ++e) {
        const auto lo = index(boxes[e].lo), hi = index(boxes[e].hi);
        for (long k = lo[2]; k <= hi[2]; ++k)
          for (long j = lo[1]; j <= hi[1]; ++j)
            for (long i = lo[0]; i <= hi[0]; ++i) {
              const std::size_t c = flat({i, j, k});
              if (pass == 0)
                ++offsets_[c + 1];
              else
                items_[static_cast<std::size_t>(fill[c]++)] = static_cast<std::int32_t>(e);
            }
      }
      if (pass == 0) {
        for (std::size_t c = 0; c < cells; ++c) offsets_[c + 1] += offsets_[c];
        items_.resize(static_cast<std::size_t>(offsets_.back()));
      }
    }
  }
  // The elements listed in the cell of p (p inside the boxes' union).
  std::span<const std::int32_t> at(const Vec3& p) const {
    const std::size_t c = flat(index(p));
    return {items_.data() + offsets_[c], static_cast<std::size_t>(offsets_[c + 1] - offsets_[c])};
  }

 private:
  std::array<long, 3> index(const Vec3& p) const {
    std::array<long, 3> ijk;
    for (int d = 0; d < 3; ++d) {
      const auto u = static_cast<std::size_t>(d);
      ijk[u] = std::clamp(static_cast<long>(std::floor((p[d] - lo_[d]) / cell_)), 0L, n_[u] - 1);
    }
    return ijk;
  }
  std::size_t flat(const std::array<long, 3>& ijk) const {
    return static_cast<std::size_t>((ijk[2] * n_[1] + ijk[1]) * n_[0] + ijk[0]);
  }

  Vec3 lo_;
  double cell_;
  std::array<long, 3> n_{};
  std::vector<std::int64_t> offsets_;
  std::vector<std::int32_t> items_;
};

// The live hexahedra of one body: their corners, boxes (reaching a little past their faces, so
// that a point on a face between two elements is in both) and a cell hash over the boxes.
class BodyElements {
 public:
  BodyElements(const HexElements& hexes, std::span<const Vec3> node_position, int body) {
    double edges = 0.0;
    for (const ElementBatch& b : hexes.batches) {
      if (b.body != body) continue;
      for (std::size_t e = b.begin; e < b.end; ++e) {
        if (!hexes.alive[e]) continue;
        Corners x;
        Box box;
        for (std::size_t a = 0; a < 8; ++a) {
          x[a] = node_position[static_cast<std::size_t>(hexes.nodes[e][a])];
          box.add(x[a]);
        }
        double edge = 0.0;
        for (int d = 0; d < 3; ++d) edge = std::max(edge, box.hi[d] - box.lo[d]);
        for (int d = 0; d < 3; ++d) {
          box.lo[d] -= kOnFace * edge;
          box.hi[d] += kOnFace * edge;
        }
        all_.add(box.lo);
        all_.add(box.hi);
        edges += edge;
        corners_.push_back(x);
        boxes_.push_back(box);
        element_.push_back(static_cast<std::int32_t>(e));
      }
    }
    if (corners_.empty()) return;
    // Cells of the elements' mean size, coarser where that would make far more cells than
    // elements (a thin shell).
    double cell = edges / static_cast<double>(corners_.size());
    auto cells = [&] {
      double n = 1.0;
      for (int d = 0; d < 3; ++d) n *= std::max(1.0, std::ceil((all_.hi[d] - all_.lo[d]) / cell));
      return n;
    };
    while (cells() > 8.0 * static_cast<double>(corners_.size()) + 64.0) cell *= 2.0;
    hash_.emplace(boxes_, all_, cell);
  }

  // f(element, xi) for each element that holds p (natural coordinates within the face
  // tolerance), in the hash's order.
  template <class F>
  void for_each_holder(const Vec3& p, F&& f) const {
    if (!hash_ || !all_.holds(p)) return;
    for (const std::int32_t k : hash_->at(p)) {
      const auto i = static_cast<std::size_t>(k);
      std::array<double, 3> xi;
      if (!boxes_[i].holds(p) || !natural_coordinates(corners_[i], p, xi)) continue;
      bool in = true;
      for (const double c : xi) in = in && std::abs(c) <= 1.0 + kOnFace;
      if (in) f(element_[i], xi);
    }
  }

 private:
  std::vector<Corners> corners_;
  std::vector<Box> boxes_;
  std::vector<std::int32_t> element_;
  Box all_;
  std::optional<CellHash> hash_;
};

}  // namespace

std::size_t points_inside(const HexElements& hexes, std::span<const Vec3> node_position, int body,
                          std::span<const Vec3> points) {
  const BodyElements elements(hexes, node_position, body);
  std::size_t inside = 0;
  for (const Vec3& p : points) {
    // The elements that hold p, and how many of its coordinates lie on a face: inside the body
    // when they surround it (one element, or two across a face, four round an edge, eight round
    // a corner), on its surface when fewer do.
    int held = 0, on_faces = 0;
    elements.for_each_holder(p, [&](std::int32_t, const std::array<double, 3>& xi) {
      int faces = 0;
      for (const double c : xi) faces += std::abs(c) >= 1.0 - kOnFace ? 1 : 0;
      ++held;
      on_faces = std::max(on_faces, faces);
    });
    if (held > 0 && held >= (1 << on_faces)) ++inside;
  }
  return inside;
}

std::vector<HostPoint> locate_points(const HexElements& hexes, std::span<const Vec3> node_position,
                                     int body, std::span<const Vec3> points) {
  const BodyElements elements(hexes, node_position, body);
  std::vector<HostPoint> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    elements.for_each_holder(points[i], [&](std::int32_t e, const std::array<double, 3>& xi) {
      // The lowest-numbered holder (a point on a face between elements lies in each).
      if (out[i].element < 0 || e < out[i].element) out[i] = {e, xi};
    });
  return out;
}

}  // namespace afemp::fem
