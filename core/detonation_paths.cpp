// Lighting times along paths through the explosive (core/detonation_paths.hpp): Lazy Theta*
// (Nash, Koenig & Tovey 2010, Algorithm 2) on voxels of the explosive.
#include "core/detonation_paths.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

#include "afemp/errors.hpp"
#include "core/programmed_burn.hpp"

namespace afemp::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Each point stands for a cube of edge s (a particle's domain; for an element, a cube of its
// volume) and the explosive is their union: a voxel is explosive when its centre lies in one,
// with a tenth of an edge to spare against round-off and uneven element sizes. Voxels are s / 2,
// so their centres never sit on the cubes' faces.
constexpr double kHalfCube = 0.55;
constexpr std::size_t kMaxVoxels = 50'000'000;

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// Voxels of edge s / 2 over the explosive points' box; D = the detonation velocity of the
// nearest point whose cube holds the centre, 0 where none does (no explosive: the wave cannot
// pass).
struct Voxels {
  Vec3 origin{};
  double s = 0.0;
  std::int64_t n[3] = {0, 0, 0};
  std::vector<double> D;

  std::size_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::size_t>((k * n[1] + j) * n[0] + i);
  }
  void coords(std::size_t v, std::int64_t c[3]) const {
    const auto q = static_cast<std::int64_t>(v);
    c[0] = q % n[0];
    c[1] = (q / n[0]) % n[1];
    c[2] = q / (n[0] * n[1]);
  }
  Vec3 centre(std::size_t v) const {
    std::int64_t c[3];
    coords(v, c);
    return origin + Vec3{(static_cast<double>(c[0]) + 0.5) * s,
                         (static_cast<double>(c[1]) + 0.5) * s,
                         (static_cast<double>(c[2]) + 0.5) * s};
  }
  // The voxel holding y, or false outside the box.
  bool find(const Vec3& y, std::size_t& v) const {
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = static_cast<std::int64_t>(std::floor((y[a] - origin[a]) / s));
      if (c[a] < 0 || c[a] >= n[a]) return false;
    }
    v = index(c[0], c[1], c[2]);
    return true;
  }
  double at(const Vec3& y) const {
    std::size_t v = 0;
    return find(y, v) ? D[v] : 0.0;
  }
};

Voxels make_voxels(std::span<const Vec3> x, std::span<const double> D, double spacing) {
  Voxels vox;
  const double s = 0.5 * spacing;
  vox.s = s;
  Vec3 lo = x.front(), hi = x.front();
  for (const Vec3& p : x)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  std::size_t total = 1;
  for (int a = 0; a < 3; ++a) {
    vox.origin[a] = lo[a] - 2.0 * s;
    vox.n[a] = static_cast<std::int64_t>(std::ceil((hi[a] - lo[a]) / s)) + 4;
    total *= static_cast<std::size_t>(vox.n[a]);
  }
  if (total > kMaxVoxels)
    throw std::runtime_error("shadowed detonation: the explosive spans " + std::to_string(total) +
                             " voxels of half its point spacing " + number(spacing) +
                             ", more than the " + std::to_string(kMaxVoxels) +
                             " the path search takes; use shadow = false");
  vox.D.assign(total, 0.0);
  std::vector<double> d2(total, kInf);
  const double r = kHalfCube * spacing;
  for (std::size_t i = 0; i < x.size(); ++i) {
    std::int64_t a0[3], a1[3];
    for (int a = 0; a < 3; ++a) {
      a0[a] = std::max<std::int64_t>(
          0, static_cast<std::int64_t>(std::floor((x[i][a] - r - vox.origin[a]) / s)));
      a1[a] = std::min<std::int64_t>(
          vox.n[a] - 1, static_cast<std::int64_t>(std::floor((x[i][a] + r - vox.origin[a]) / s)));
    }
    for (std::int64_t k = a0[2]; k <= a1[2]; ++k)
      for (std::int64_t j = a0[1]; j <= a1[1]; ++j)
        for (std::int64_t ii = a0[0]; ii <= a1[0]; ++ii) {
          const std::size_t v = vox.index(ii, j, k);
          const Vec3 d = vox.centre(v) - x[i];
          if (std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) > r) continue;
          const double dd = dot(d, d);
          if (dd < d2[v]) {
            d2[v] = dd;
            vox.D[v] = D[i];
          }
        }
  }
  return vox;
}

// True when the segment a -> b runs through explosive of detonation velocity Dleg, sampled every
// half voxel; samples within `skip` of a are not checked.
bool line_of_sight(const Voxels& vox, const Vec3& a, const Vec3& b, double Dleg, double skip) {
  const Vec3 ab = b - a;
  const double L = norm(ab);
  const int n = std::max(1, static_cast<int>(std::ceil(L / (0.5 * vox.s))));
  for (int k = 1; k <= n; ++k) {
    const double f = static_cast<double>(k) / n;
    if (f * L < skip) continue;
    if (vox.at(a + f * ab) != Dleg) return false;
  }
  return true;
}

// The lighting times of the points from one shadowed detonation.
void shadowed(const Voxels& vox, std::span<const Vec3> x, std::span<const double> D,
              const DetonationSpec& det, std::vector<double>& t) {
  const std::size_t nv = vox.D.size();
  const double s = vox.s;
  std::vector<double> g(nv, kInf), vt(nv, kInf);  // arrival; the path's last corner's time
  std::vector<Vec3> vp(nv);                       // the path's last corner
  std::vector<char> from_det(nv, 0), closed(nv, 0);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;

  // Seeds: the explosive voxels the detonation touches (or the nearest, for a detonation on
  // the surface), each lit straight from the detonation's point nearest to it.
  double nearest = kInf;
  for (std::size_t v = 0; v < nv; ++v)
    if (vox.D[v] > 0.0) {
      const Vec3 c = vox.centre(v);
      nearest = std::min(nearest, norm(c - nearest_point(det, c)));
    }
  const double reach = std::max(std::sqrt(3.0) / 2.0 * s, nearest * (1.0 + 1e-12));
  // Legs straight from the detonation are not checked near it: it may lie just outside.
  const double skip = nearest + 2.0 * s;
  for (std::size_t v = 0; v < nv; ++v) {
    if (vox.D[v] <= 0.0) continue;
    const Vec3 c = vox.centre(v);
    const Vec3 foot = nearest_point(det, c);
    const double d = norm(c - foot);
    if (d > reach) continue;
    g[v] = det.time + d / vox.D[v];
    vp[v] = foot;
    vt[v] = det.time;
    from_det[v] = 1;
    open.emplace(g[v], v);
  }

  auto leg = [&](std::size_t a, std::size_t b) {  // between neighbouring voxels
    return norm(vox.centre(a) - vox.centre(b)) * 0.5 * (1.0 / vox.D[a] + 1.0 / vox.D[b]);
  };
  auto for_neighbours = [&](std::size_t v, auto&& f) {
    std::int64_t c[3];
    vox.coords(v, c);
    for (std::int64_t dk = -1; dk <= 1; ++dk)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t di = -1; di <= 1; ++di) {
          if (di == 0 && dj == 0 && dk == 0) continue;
          const std::int64_t i = c[0] + di, j = c[1] + dj, k = c[2] + dk;
          if (i < 0 || j < 0 || k < 0 || i >= vox.n[0] || j >= vox.n[1] || k >= vox.n[2]) continue;
          const std::size_t w = vox.index(i, j, k);
          if (vox.D[w] > 0.0) f(w);
        }
  };

  while (!open.empty()) {
    const auto [gv, v] = open.top();
    open.pop();
    if (closed[v] || gv > g[v]) continue;
    const Vec3 cv = vox.centre(v);
    // Lazy Theta*'s SetVertex: the straight leg from the corner was assumed; where it is
    // blocked, the path comes from the best expanded neighbour instead.
    if (!line_of_sight(vox, vp[v], cv, vox.D[v], from_det[v] ? skip : 0.0)) {
      g[v] = kInf;
      for_neighbours(v, [&](std::size_t w) {
        if (!closed[w]) return;
        const double cand = g[w] + leg(w, v);
        if (cand < g[v]) {
          g[v] = cand;
          vp[v] = vox.centre(w);
          vt[v] = g[w];
          from_det[v] = 0;
        }
      });
      if (g[v] == kInf) continue;
    }
    closed[v] = 1;
    for_neighbours(v, [&](std::size_t w) {
      if (closed[w]) return;
      if (vox.D[w] == vox.D[v]) {
        const double cand = vt[v] + norm(vox.centre(w) - vp[v]) / vox.D[w];
        if (cand < g[w]) {
          g[w] = cand;
          vp[w] = vp[v];
          vt[w] = vt[v];
          from_det[w] = from_det[v];
          open.emplace(cand, w);
        }
      } else {  // another explosive: the path turns where the two meet
        const double cand = g[v] + leg(v, w);
        if (cand < g[w]) {
          g[w] = cand;
          vp[w] = cv;
          vt[w] = g[v];
          from_det[w] = 0;
          open.emplace(cand, w);
        }
      }
    });
  }

  for (std::size_t i = 0; i < x.size(); ++i) {
    std::size_t v = 0;
    if (!vox.find(x[i], v) || g[v] == kInf) continue;
    double ti = g[v] + norm(x[i] - vox.centre(v)) / D[i];
    if (vox.D[v] == D[i]) {
      const Vec3 foot = nearest_point(det, x[i]);
      if (from_det[v] && line_of_sight(vox, foot, x[i], D[i], skip))
        ti = det.time + norm(x[i] - foot) / D[i];  // in sight of the detonation: straight
      else if (line_of_sight(vox, vp[v], x[i], D[i], from_det[v] ? skip : 0.0))
        ti = vt[v] + norm(x[i] - vp[v]) / D[i];
    }
    t[i] = std::min(t[i], ti);
  }
}

}  // namespace

std::vector<double> lighting_times(std::span<const Vec3> x, std::span<const double> D,
                                   double spacing, std::span<const DetonationSpec> detonations) {
  std::vector<double> t(x.size(), kInf);
  if (x.empty()) return t;
  for (std::size_t i = 0; i < x.size(); ++i) t[i] = lighting_time(x[i], detonations, D[i]);
  if (std::none_of(detonations.begin(), detonations.end(),
                   [](const DetonationSpec& d) { return d.shadow; }))
    return t;
  Voxels vox;
  try {
    vox = make_voxels(x, D, spacing);
  } catch (const std::runtime_error& e) {
    for (const DetonationSpec& d : detonations)
      if (d.shadow) throw InputError(d.where, "shadow", e.what());
  }
  for (const DetonationSpec& d : detonations) {
    if (!d.shadow) continue;
    double nearest = kInf;
    for (const Vec3& p : x) nearest = std::min(nearest, norm(p - nearest_point(d, p)));
    if (nearest > 2.0 * spacing)
      throw InputError(d.where, "shadow",
                       "this detonation lies " + number(nearest) +
                           " from the nearest explosive point (the points are " + number(spacing) +
                           " apart); a shadowed detonation travels through explosive only and "
                           "must lie in or on it (within two point spacings)");
    shadowed(vox, x, D, d, t);
  }
  return t;
}

std::vector<double> explosive_lighting_times(std::span<const Vec3> x, std::span<const double> D,
                                             std::span<const std::int32_t> body, double spacing,
                                             const Scene& scene) {
  std::vector<double> t = lighting_times(x, D, spacing, scene.detonations);
  std::size_t unlit = 0, first = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] == kInf && unlit++ == 0) first = i;
  if (unlit == 0) return t;
  const DetonationSpec* shadow = nullptr;
  for (const DetonationSpec& d : scene.detonations)
    if (d.shadow && shadow == nullptr) shadow = &d;
  const BodySpec& b = scene.bodies[static_cast<std::size_t>(body[first])];
  const std::string where =
      "(" + number(x[first].x) + ", " + number(x[first].y) + ", " + number(x[first].z) + ")";
  throw InputError(shadow != nullptr ? shadow->where : b.where, "shadow",
                   std::to_string(unlit) + " point(s) of the high explosive \"" + b.name +
                       "\" are never lit, the first at " + where +
                       ": a shadowed detonation travels through explosive only, and these points "
                       "are cut off from every detonation by inert bodies or gaps; add a "
                       "detonation that reaches them, or use shadow = false (straight lines)");
}

}  // namespace afemp::core
