// The active set of rigid planar walls in the implicit solves and the frames of the nodes it
// holds (fem/wall_constraints.hpp).
#include "fem/wall_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace afemp::fem {
namespace {

// Below this |p_w|^2 a wall's normal lies in the node's prescribed components: it cannot move
// the node, and the node is left out of its set (as the explicit wall skips it).
constexpr double kMinReach = 1e-12;

std::string node_name(const MeshData& mesh, std::size_t n) {
  std::string s = "node " + std::to_string(n);
  if (!mesh.node_labels.empty()) s += " (label " + std::to_string(mesh.node_labels[n]) + ")";
  return s;
}

}  // namespace

WallConstraints::WallConstraints(const MeshData& mesh, std::span<const PlanarWall> walls,
                                 std::vector<char> fixed, const char* who)
    : mesh_(mesh), walls_(walls.begin(), walls.end()), fixed_(std::move(fixed)) {
  core::Vec3 lo = mesh.nodes.empty() ? core::Vec3{} : mesh.nodes[0], hi = lo;
  for (const core::Vec3& x : mesh.nodes)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], x[i]);
      hi[i] = std::max(hi[i], x[i]);
    }
  length_tolerance_ = 1e-12 * core::norm(hi - lo);
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    core::WallSpec& s = walls_[w].spec;
    std::string name = "wall " + std::to_string(w);
    if (!s.where.file.empty())
      name += " (" + s.where.file + ":" + std::to_string(s.where.line) + ")";
    names_.push_back(name);
    const std::string head = std::string(who) + ": " + name;
    const double length = core::norm(s.normal);
    if (!(length > 0.0)) throw std::invalid_argument(head + " has no normal (a zero vector)");
    s.normal *= 1.0 / length;
    if (core::norm(s.velocity) != 0.0)
      throw std::invalid_argument(head +
                                  " moves (it has a velocity): the implicit solves take fixed "
                                  "walls only");
    if (s.friction != 0.0) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%g", s.friction);
      throw std::invalid_argument(head + " has friction " + buf +
                                  ": the implicit solves' walls are frictionless (stick and slip "
                                  "are not implemented there); give it friction 0");
    }
    std::vector<std::int32_t>& nodes = walls_[w].nodes;
    for (std::int32_t n : nodes)
      if (n < 0 || static_cast<std::size_t>(n) >= mesh.nodes.size())
        throw std::invalid_argument(head + " lists node " + std::to_string(n) + " of " +
                                    std::to_string(mesh.nodes.size()));
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    active_.emplace_back(walls_[w].nodes.size(), 0);
  }
  frame_of_.assign(mesh.nodes.size(), -1);
}

double WallConstraints::gap(std::size_t w, std::int32_t node,
                            const std::vector<core::Vec3>& u) const {
  const core::WallSpec& s = walls_[w].spec;
  return core::dot(s.normal, mesh_.nodes[node] + u[node] - s.point);
}

core::Vec3 WallConstraints::free_normal(std::size_t w, std::int32_t node) const {
  core::Vec3 p = walls_[w].spec.normal;
  for (int i = 0; i < 3; ++i)
    if (fixed_[3 * static_cast<std::size_t>(node) + i]) p[i] = 0.0;
  return p;
}

void WallConstraints::start(const std::vector<core::Vec3>& u) {
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t k = 0; k < walls_[w].nodes.size(); ++k) {
      const std::int32_t n = walls_[w].nodes[k];
      const core::Vec3 p = free_normal(w, n);
      active_[w][k] = core::dot(p, p) >= kMinReach && gap(w, n, u) <= length_tolerance_;
    }
  build_frames();
}

void WallConstraints::build_frames() {
  for (std::size_t f = 0; f < frames_.size(); ++f) frame_of_[frame_node_[f]] = -1;
  frames_.clear();
  frame_node_.clear();
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t k = 0; k < walls_[w].nodes.size(); ++k) {
      if (!active_[w][k]) continue;
      const std::int32_t n = walls_[w].nodes[k];
      if (frame_of_[n] < 0) {
        frame_of_[n] = static_cast<int>(frames_.size());
        frames_.emplace_back();
        frame_node_.push_back(n);
      }
      NodeFrame& f = frames_[static_cast<std::size_t>(frame_of_[n])];
      if (f.held == 3)
        throw std::runtime_error("walls: " + node_name(mesh_, static_cast<std::size_t>(n)) +
                                 " is on more than three walls at once");
      f.wall[f.held++] = static_cast<int>(w);  // the nodes of a wall are unique
    }
  for (std::size_t fi = 0; fi < frames_.size(); ++fi) {
    NodeFrame& f = frames_[fi];
    const std::int32_t n = frame_node_[fi];
    int free[3], free_count = 0;
    for (int i = 0; i < 3; ++i) {
      f.basis[i] = core::Vec3{};
      f.basis[i][i] = 1.0;
      if (!fixed_[3 * static_cast<std::size_t>(n) + i]) free[free_count++] = i;
    }
    // Gram-Schmidt on the walls' free normals, then on the free axes (the one least in the
    // span so far first) for the rest of the free components.
    core::Vec3 axes[3];
    int count = 0;
    auto residual = [&](const core::Vec3& v) {
      core::Vec3 r = v;
      for (int j = 0; j < count; ++j) r -= core::dot(v, axes[j]) * axes[j];
      return r;
    };
    for (int j = 0; j < f.held; ++j) {
      const core::Vec3 p = free_normal(static_cast<std::size_t>(f.wall[j]), n);
      const core::Vec3 r = residual(p);
      if (count == free_count || core::norm(r) <= 1e-6 * core::norm(p))
        throw std::runtime_error(
            "walls: " + node_name(mesh_, static_cast<std::size_t>(n)) + " is on " +
            names_[static_cast<std::size_t>(f.wall[0])] + " and " +
            names_[static_cast<std::size_t>(f.wall[j])] +
            ", whose normals leave it no independent direction to hold (parallel walls, or "
            "more walls than its free components)");
      axes[count++] = (1.0 / core::norm(r)) * r;
      for (int i = 0; i <= j; ++i) f.a[j][i] = core::dot(p, axes[i]);
    }
    while (count < free_count) {
      core::Vec3 best;
      for (int c = 0; c < free_count; ++c) {
        core::Vec3 e;
        e[free[c]] = 1.0;
        const core::Vec3 r = residual(e);
        if (core::norm(r) > core::norm(best)) best = r;
      }
      axes[count++] = (1.0 / core::norm(best)) * best;
    }
    for (int c = 0; c < free_count; ++c) f.basis[free[c]] = axes[c];
    for (int j = 0; j < f.held; ++j) f.slot[j] = free[j];
  }
}

void WallConstraints::project(std::vector<core::Vec3>& u) const {
  for (std::size_t fi = 0; fi < frames_.size(); ++fi) {
    const NodeFrame& f = frames_[fi];
    const std::int32_t n = frame_node_[fi];
    // n_w . (u + sum_j y_j h_j) = n_w . u - gap_w, and n_w . h_j = a[w][j]: forward
    // substitution.
    double y[3];
    for (int w = 0; w < f.held; ++w) {
      double rhs = -gap(static_cast<std::size_t>(f.wall[w]), n, u);
      for (int j = 0; j < w; ++j) rhs -= f.a[w][j] * y[j];
      y[w] = rhs / f.a[w][w];
    }
    for (int j = 0; j < f.held; ++j) u[n] += y[j] * f.basis[f.slot[j]];
  }
}

void WallConstraints::stop(std::vector<core::Vec3>& v, std::vector<core::Vec3>& a) const {
  for (std::size_t fi = 0; fi < frames_.size(); ++fi) {
    const NodeFrame& f = frames_[fi];
    const std::int32_t n = frame_node_[fi];
    for (int j = 0; j < f.held; ++j) {
      const core::Vec3& h = f.basis[f.slot[j]];
      v[n] -= core::dot(h, v[n]) * h;
      a[n] -= core::dot(h, a[n]) * h;
    }
  }
}

std::vector<std::pair<std::int32_t, core::Vec3>> WallConstraints::supports() const {
  std::vector<std::pair<std::int32_t, core::Vec3>> out;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t k = 0; k < walls_[w].nodes.size(); ++k)
      if (active_[w][k]) out.emplace_back(walls_[w].nodes[k], walls_[w].spec.normal);
  return out;
}

int WallConstraints::contacts() const {
  int count = 0;
  for (const std::vector<char>& a : active_)
    count += static_cast<int>(std::count(a.begin(), a.end(), 1));
  return count;
}

void WallConstraints::transform(const std::int32_t* nodes, int count, double* k) const {
  const int size = 3 * count;
  for (int a = 0; a < count; ++a) {
    const NodeFrame* f = frame(static_cast<std::size_t>(nodes[a]));
    if (!f) continue;
    // Rows 3a .. 3a + 2 become basis[i] . rows, then the columns likewise (k stays symmetric).
    for (int c = 0; c < size; ++c) {
      const double r[3] = {k[size * (3 * a) + c], k[size * (3 * a + 1) + c],
                           k[size * (3 * a + 2) + c]};
      for (int i = 0; i < 3; ++i)
        k[size * (3 * a + i) + c] =
            f->basis[i].x * r[0] + f->basis[i].y * r[1] + f->basis[i].z * r[2];
    }
    for (int row = 0; row < size; ++row) {
      double* kr = k + size * row + 3 * a;
      const double r[3] = {kr[0], kr[1], kr[2]};
      for (int i = 0; i < 3; ++i)
        kr[i] = f->basis[i].x * r[0] + f->basis[i].y * r[1] + f->basis[i].z * r[2];
    }
  }
  for (int a = 0; a < count; ++a) {
    const NodeFrame* f = frame(static_cast<std::size_t>(nodes[a]));
    if (!f) continue;
    for (int j = 0; j < f->held; ++j) {
      const int q = 3 * a + f->slot[j];
      for (int p = 0; p < size; ++p)
        if (p != q) k[size * p + q] = k[size * q + p] = 0.0;
    }
  }
}

std::array<double, 3> WallConstraints::multipliers(const NodeFrame& f,
                                                   const core::Vec3& residual) const {
  // sum_w a[w][j] lambda_w = -h_j . r: back substitution (a is lower triangular).
  std::array<double, 3> lambda{};
  for (int j = f.held - 1; j >= 0; --j) {
    double rhs = -core::dot(f.basis[f.slot[j]], residual);
    for (int w = j + 1; w < f.held; ++w) rhs -= f.a[w][j] * lambda[w];
    lambda[j] = rhs / f.a[j][j];
  }
  return lambda;
}

std::vector<core::Vec3> WallConstraints::forces(const std::vector<core::Vec3>& residual) const {
  std::vector<core::Vec3> out(walls_.size());
  for (std::size_t fi = 0; fi < frames_.size(); ++fi) {
    const NodeFrame& f = frames_[fi];
    const std::array<double, 3> lambda = multipliers(f, residual[frame_node_[fi]]);
    for (int j = 0; j < f.held; ++j) {
      const auto w = static_cast<std::size_t>(f.wall[j]);
      out[w] += lambda[j] * walls_[w].spec.normal;
    }
  }
  return out;
}

bool WallConstraints::update(const std::vector<core::Vec3>& u,
                             const std::vector<core::Vec3>& residual, double force_tolerance,
                             std::string& change) {
  bool changed = false;
  auto note = [&](std::size_t w, std::int32_t n, const char* what) {
    if (!changed) change = node_name(mesh_, static_cast<std::size_t>(n)) + what + names_[w];
    changed = true;
  };
  std::vector<std::array<double, 3>> lambda(frames_.size());
  for (std::size_t fi = 0; fi < frames_.size(); ++fi)
    lambda[fi] = multipliers(frames_[fi], residual[frame_node_[fi]]);
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t k = 0; k < walls_[w].nodes.size(); ++k) {
      const std::int32_t n = walls_[w].nodes[k];
      if (active_[w][k]) {
        const auto fi = static_cast<std::size_t>(frame_of_[n]);
        const NodeFrame& f = frames_[fi];
        for (int j = 0; j < f.held; ++j)
          if (f.wall[j] == static_cast<int>(w) && lambda[fi][j] < -force_tolerance) {
            active_[w][k] = 0;
            note(w, n, " leaves ");
          }
      } else {
        const core::Vec3 p = free_normal(w, n);
        if (core::dot(p, p) >= kMinReach && gap(w, n, u) < -length_tolerance_) {
          active_[w][k] = 1;
          note(w, n, " crosses ");
        }
      }
    }
  if (changed) build_frames();
  return changed;
}

}  // namespace afemp::fem
