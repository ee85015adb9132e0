// Contact between meshes (mesh_contact.hpp): node-to-face in both directions, the penalty on the
// predicted penetration (Taylor & Flanagan 1989) resolved by projected Gauss-Seidel sweeps.
#include "fem/mesh_contact.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/contact_impulse.hpp"
#include "core/parallel.hpp"
#include "fem/face_projection.hpp"
#include "fem/fe_solver.hpp"
#include "fem/surface_faces.hpp"

namespace afemp::fem {

namespace {

// The master faces of body b, turned outward (from their element's centroid), with their reach
// (the thickness of their element normal to them, its volume over the face's area; half of it
// in self-contact, where the far side of the same body is near).
void master_faces(ContactPass& pass, const SurfaceFaces& s, bool self,
                  std::span<ElementSet* const> sets, const FeNodes& nodes) {
  pass.faces = s.nodes;
  pass.face_set = s.set;
  pass.face_element = s.element;
  pass.reach.resize(s.nodes.size());
  for (std::size_t f = 0; f < s.nodes.size(); ++f) {
    const ElementSet& set = *sets[static_cast<std::size_t>(s.set[f])];
    const auto e = static_cast<std::size_t>(s.element[f]);
    const Vec3 area =
        face_area_vector(s.nodes[f], set.element_centroid(e, nodes.position), nodes.position);
    auto& q = pass.faces[f];
    const std::array<Vec3, 4> p = corners(q, nodes.position);
    if (core::dot(core::cross(p[2] - p[0], p[3] - p[1]), area) < 0.0) std::swap(q[1], q[3]);
    const double a = core::norm(area);
    const double thickness = a > 0.0 ? set.store().volume[e] / a : 0.0;
    pass.reach[f] = (self ? 0.5 : 1.0) * thickness;
  }
}

// The slave nodes of body b: the nodes of its live boundary faces (kinds with faces) and of its
// live elements of kinds without faces (trusses), ascending.
std::vector<std::int32_t> slave_nodes(int body, const SurfaceFaces& surface,
                                      std::span<ElementSet* const> sets, const FeNodes& nodes) {
  std::vector<char> on(nodes.size(), 0);
  for (const auto& f : surface.nodes)
    for (std::int32_t k : f) on[static_cast<std::size_t>(k)] = 1;
  for (const ElementSet* set : sets) {
    if (set->has_faces()) continue;
    const ElementStore& el = set->store();
    const std::span<const std::int32_t> connectivity = set->connectivity();
    const auto n = static_cast<std::size_t>(set->corners());
    for (const ElementBatch& b : el.batches)
      if (b.body == body)
        for (std::size_t e = b.begin; e < b.end; ++e)
          if (el.alive[e])
            for (std::int32_t k : connectivity.subspan(n * e, n))
              on[static_cast<std::size_t>(k)] = 1;
  }
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < on.size(); ++i)
    if (on[i] && nodes.mass[i] > 0.0) out.push_back(static_cast<std::int32_t>(i));
  return out;
}

// Bins of the faces at the current positions: cubic bins about the size of a face grown by its
// reach, each face in every bin its grown box touches.
void bin_faces(ContactPass& pass, const std::vector<Vec3>& position) {
  const std::size_t nf = pass.faces.size();
  pass.bin_offsets.clear();
  pass.bin_faces.clear();
  pass.binned = true;
  if (nf == 0) return;
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  std::vector<std::array<Vec3, 2>>& box = pass.face_box;
  box.resize(nf);
  // The faces' own boxes, and their mean extent, which sets the margin: a quarter of it.
  double extent = 0.0;
  for (std::size_t f = 0; f < nf; ++f) {
    Vec3 a{inf, inf, inf}, b{-inf, -inf, -inf};
    for (std::int32_t k : pass.faces[f]) {
      const Vec3& x = position[static_cast<std::size_t>(k)];
      for (int d = 0; d < 3; ++d) a[d] = std::min(a[d], x[d]), b[d] = std::max(b[d], x[d]);
    }
    box[f] = {a, b};
    extent += std::max({b.x - a.x, b.y - a.y, b.z - a.z});
  }
  pass.margin = 0.25 * extent / static_cast<double>(nf);
  extent = 0.0;
  for (std::size_t f = 0; f < nf; ++f) {
    Vec3& a = box[f][0];
    Vec3& b = box[f][1];
    const double r = pass.reach[f] + pass.margin;
    for (int d = 0; d < 3; ++d) {
      a[d] -= r;
      b[d] += r;
      lo[d] = std::min(lo[d], a[d]);
      hi[d] = std::max(hi[d], b[d]);
      extent += b[d] - a[d];
    }
  }
  for (std::size_t k = 0; k < pass.face_nodes.size(); ++k)
    pass.binned_position[k] = position[static_cast<std::size_t>(pass.face_nodes[k])];
  double h = extent / (3.0 * static_cast<double>(nf));
  // At most about 4 bins per face (a flat surface fills few of a box's bins).
  for (;;) {
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) cells *= std::floor((hi[d] - lo[d]) / h) + 1.0;
    if (cells <= 4.0 * static_cast<double>(nf) + 64.0) break;
    h *= 1.25;
  }
  pass.bin_min = lo;
  pass.bin_size = h;
  for (int d = 0; d < 3; ++d)
    pass.bin_count[static_cast<std::size_t>(d)] =
        static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / h)) + 1;
  const auto [nx, ny, nz] = pass.bin_count;
  auto cell = [&](const Vec3& x, int d) {
    return std::clamp(static_cast<std::int64_t>(std::floor((x[d] - lo[d]) / h)), std::int64_t{0},
                      pass.bin_count[static_cast<std::size_t>(d)] - 1);
  };
  pass.bin_offsets.assign(static_cast<std::size_t>(nx * ny * nz + 1), 0);
  for (int sweep = 0; sweep < 2; ++sweep) {
    if (sweep == 1) {
      for (std::size_t c = 1; c < pass.bin_offsets.size(); ++c)
        pass.bin_offsets[c] += pass.bin_offsets[c - 1];
      pass.bin_faces.resize(static_cast<std::size_t>(pass.bin_offsets.back()));
    }
    std::vector<std::int64_t> fill;
    if (sweep == 1) fill.assign(pass.bin_offsets.begin(), pass.bin_offsets.end() - 1);
    for (std::size_t f = 0; f < nf; ++f) {
      const std::int64_t i0 = cell(box[f][0], 0), i1 = cell(box[f][1], 0);
      const std::int64_t j0 = cell(box[f][0], 1), j1 = cell(box[f][1], 1);
      const std::int64_t k0 = cell(box[f][0], 2), k1 = cell(box[f][1], 2);
      for (std::int64_t k = k0; k <= k1; ++k)
        for (std::int64_t j = j0; j <= j1; ++j)
          for (std::int64_t i = i0; i <= i1; ++i) {
            const std::int64_t c = (k * ny + j) * nx + i;
            if (sweep == 0)
              ++pass.bin_offsets[static_cast<std::size_t>(c + 1)];
            else
              pass.bin_faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(c)]++)] =
                  static_cast<std::int32_t>(f);
          }
    }
  }
}

void build_passes(MeshContact& c, const core::Scene& scene, std::span<ElementSet* const> sets,
                  const FeNodes& nodes) {
  const int a = c.spec.bodies[0], b = c.spec.bodies[1];
  // Whether the body's elements are of a kind with faces (a master; its slaves have normals).
  const auto faced = [&](int body) {
    for (const ElementSet* set : sets)
      if (set->has_faces())
        for (const ElementBatch& batch : set->store().batches)
          if (batch.body == body) return true;
    return false;
  };
  // Each body's boundary faces, found once (a body of trusses has none).
  auto surface_of = [&](int body) {
    std::vector<char> selected(scene.bodies.size(), 0);
    selected[static_cast<std::size_t>(body)] = 1;
    return boundary_faces(sets, selected);
  };
  const SurfaceFaces surface_a = surface_of(a);
  const SurfaceFaces surface_b = a == b ? SurfaceFaces{} : surface_of(b);
  auto surface = [&](int body) -> const SurfaceFaces& { return body == a ? surface_a : surface_b; };
  std::vector<ContactPass> passes;
  auto add = [&](int slave, int master, bool first) {
    ContactPass p;
    p.slaves_first_body = first;
    p.slaves = slave_nodes(slave, surface(slave), sets, nodes);
    master_faces(p, surface(master), a == b, sets, nodes);
    if (faced(slave)) {
      ContactPass own;
      master_faces(own, surface(slave), false, sets, nodes);
      p.slave_faces = std::move(own.faces);
    }
    passes.push_back(std::move(p));
  };
  if (a == b) {
    add(a, a, true);
  } else {
    if (faced(b)) add(a, b, true);
    if (faced(a)) add(b, a, false);
  }
  for (ContactPass& p : passes) {
    std::vector<char> on(nodes.size(), 0);
    for (const auto& f : p.faces)
      for (std::int32_t k : f) on[static_cast<std::size_t>(k)] = 1;
    for (std::size_t k = 0; k < on.size(); ++k)
      if (on[k]) p.face_nodes.push_back(static_cast<std::int32_t>(k));
    p.binned_position.resize(p.face_nodes.size());
    // Each slave's own faces, for its normal.
    if (!p.slave_faces.empty()) {
      std::vector<std::int32_t> index(nodes.size(), -1);
      for (std::size_t k = 0; k < p.slaves.size(); ++k)
        index[static_cast<std::size_t>(p.slaves[k])] = static_cast<std::int32_t>(k);
      p.slave_face_offsets.assign(p.slaves.size() + 1, 0);
      for (const auto& f : p.slave_faces)
        for (std::int32_t k : f)
          if (index[static_cast<std::size_t>(k)] >= 0)
            ++p.slave_face_offsets[static_cast<std::size_t>(index[static_cast<std::size_t>(k)]) +
                                   1];
      for (std::size_t k = 0; k < p.slaves.size(); ++k)
        p.slave_face_offsets[k + 1] += p.slave_face_offsets[k];
      p.slave_face_list.resize(static_cast<std::size_t>(p.slave_face_offsets.back()));
      std::vector<std::int32_t> fill(p.slave_face_offsets.begin(), p.slave_face_offsets.end() - 1);
      for (std::size_t f = 0; f < p.slave_faces.size(); ++f)
        for (std::int32_t k : p.slave_faces[f])
          if (const std::int32_t s = index[static_cast<std::size_t>(k)]; s >= 0)
            p.slave_face_list[static_cast<std::size_t>(fill[static_cast<std::size_t>(s)]++)] =
                static_cast<std::int32_t>(f);
    }
  }
  if (c.passes.empty()) {
    c.passes = std::move(passes);
    for (ContactPass& p : c.passes) {
      p.last_face.assign(nodes.size(), -1);
      if (!p.slave_faces.empty()) p.slave_normal.assign(nodes.size(), Vec3{});
    }
    return;
  }
  // A slave's last face follows it to the new list (faces compared by their sorted node ids).
  for (std::size_t k = 0; k < passes.size(); ++k) {
    ContactPass& old = c.passes[k];
    ContactPass& now = passes[k];
    using Key = std::array<std::int32_t, 4>;
    std::vector<std::pair<Key, std::int32_t>> index(now.faces.size());
    for (std::size_t f = 0; f < now.faces.size(); ++f) {
      Key key = now.faces[f];
      std::sort(key.begin(), key.end());
      index[f] = {key, static_cast<std::int32_t>(f)};
    }
    std::sort(index.begin(), index.end());
    for (std::int32_t& last : old.last_face) {
      if (last < 0) continue;
      Key key = old.faces[static_cast<std::size_t>(last)];
      std::sort(key.begin(), key.end());
      const auto it =
          std::lower_bound(index.begin(), index.end(), std::make_pair(key, std::int32_t{-1}));
      last = (it != index.end() && it->first == key) ? it->second : -1;
    }
    now.last_face = std::move(old.last_face);
    now.slave_normal = std::move(old.slave_normal);
  }
  c.passes = std::move(passes);
}

// New bins once a face node has moved by the margin since the last ones (the check split over
// the threads).
void refresh_bins(ContactPass& pass, const std::vector<Vec3>& x, std::size_t threads) {
  bool stale = !pass.binned;
  if (!stale) {
    std::vector<char> moved(threads, 0);
    const double limit = pass.margin * pass.margin;
    core::parallel_chunks(pass.face_nodes.size(), [&](std::size_t begin, std::size_t end, int t) {
      for (std::size_t k = begin; k < end; ++k) {
        const Vec3 d = x[static_cast<std::size_t>(pass.face_nodes[k])] - pass.binned_position[k];
        if (core::dot(d, d) > limit) {
          moved[static_cast<std::size_t>(t)] = 1;
          break;
        }
      }
    });
    stale = std::find(moved.begin(), moved.end(), 1) != moved.end();
  }
  if (stale) bin_faces(pass, x);
}

// The slaves' own normals: the sums of their faces' area vectors.
void slave_normals(ContactPass& pass, const std::vector<Vec3>& x) {
  core::parallel_chunks(pass.slaves.size(), [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t k = begin; k < end; ++k) {
      Vec3 n;
      for (std::int32_t q = pass.slave_face_offsets[k]; q < pass.slave_face_offsets[k + 1]; ++q) {
        const std::array<Vec3, 4> p =
            corners(pass.slave_faces[static_cast<std::size_t>(
                        pass.slave_face_list[static_cast<std::size_t>(q)])],
                    x);
        n += 0.5 * core::cross(p[2] - p[0], p[3] - p[1]);
      }
      pass.slave_normal[static_cast<std::size_t>(pass.slaves[k])] = n;
    }
  });
}

// A set's node lists as the search reads them (gathered once per search: no virtual call per
// face).
struct SetNodes {
  std::span<const std::int32_t> nodes;
  std::size_t corners = 0;
};

// Whether face f is near the slave at xs: the node projects inside it (within the edge
// tolerance; pr) and lies less than the face's reach behind it, the face is not the slave's
// own nor (self-contact) of an element the slave belongs to, and the surfaces face each other
// (facing: the slave has faces). The face holds the node when it lies behind. Inlined, as
// the search it was written in.
AFEMP_INLINE inline bool face_near(const ContactPass& pass, std::span<const SetNodes> elements,
                                   const std::vector<Vec3>& x, bool self, bool facing,
                                   std::int32_t slave, const Vec3& xs, std::int32_t f,
                                   Projection& pr) {
  const auto& q = pass.faces[static_cast<std::size_t>(f)];
  const auto& box = pass.face_box[static_cast<std::size_t>(f)];
  if (xs.x < box[0].x || xs.x > box[1].x || xs.y < box[0].y || xs.y > box[1].y || xs.z < box[0].z ||
      xs.z > box[1].z)
    return false;
  if (q[0] == slave || q[1] == slave || q[2] == slave || q[3] == slave) return false;
  if (self) {  // not the faces of an element the node belongs to
    const SetNodes& el =
        elements[static_cast<std::size_t>(pass.face_set[static_cast<std::size_t>(f)])];
    const auto e = static_cast<std::size_t>(pass.face_element[static_cast<std::size_t>(f)]);
    for (std::int32_t n : el.nodes.subspan(el.corners * e, el.corners))
      if (n == slave) return false;
  }
  if (!project(corners(q, x), xs, pr)) return false;
  if (facing && !(core::dot(pr.normal, pass.slave_normal[static_cast<std::size_t>(slave)]) < 0.0))
    return false;
  constexpr double lim = 1.0 + kEdgeTolerance;
  return -pr.gap < pass.reach[static_cast<std::size_t>(f)] && std::abs(pr.xi) <= lim &&
         std::abs(pr.eta) <= lim;
}

// The face that holds the slave (-1: none) and its projection there (bp): the face it met
// last while that one still holds it; else the nearest face in its bin (a node just past the
// edge of a side face is nearer the front face it has not crossed). Inlined, as face_near.
AFEMP_INLINE inline std::int32_t holding_face(const ContactPass& pass,
                                              std::span<const SetNodes> elements,
                                              const std::vector<Vec3>& x, bool self, bool facing,
                                              std::int32_t slave, Projection& bp) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto s = static_cast<std::size_t>(slave);
  const Vec3& xs = x[s];
  std::int64_t ijk[3];
  bool outside = false;
  for (int d = 0; d < 3; ++d) {
    const double u = std::floor((xs[d] - pass.bin_min[d]) / pass.bin_size);
    outside =
        outside || u < 0.0 || u >= static_cast<double>(pass.bin_count[static_cast<std::size_t>(d)]);
    ijk[d] = static_cast<std::int64_t>(u);
  }
  std::int32_t best = -1;
  Projection pr;
  const std::int32_t last = pass.last_face[s];
  if (last >= 0 && face_near(pass, elements, x, self, facing, slave, xs, last, pr) &&
      pr.gap < 0.0) {
    best = last;
    bp = pr;
  } else if (!outside) {
    const std::int64_t cell = (ijk[2] * pass.bin_count[1] + ijk[1]) * pass.bin_count[0] + ijk[0];
    // Nearest by the distance to the face itself (the projection clamped to it); on a tie (a
    // node on the edge two faces share), the face it projects into.
    double distance = inf, overshoot = inf;
    for (std::int64_t q = pass.bin_offsets[static_cast<std::size_t>(cell)];
         q < pass.bin_offsets[static_cast<std::size_t>(cell + 1)]; ++q) {
      const std::int32_t f = pass.bin_faces[static_cast<std::size_t>(q)];
      if (!face_near(pass, elements, x, self, facing, slave, xs, f, pr)) continue;
      const double out = std::max({std::abs(pr.xi) - 1.0, std::abs(pr.eta) - 1.0, 0.0});
      double d = std::abs(pr.gap);
      if (out > 0.0)
        d = core::norm(xs - face_point(corners(pass.faces[static_cast<std::size_t>(f)], x),
                                       std::clamp(pr.xi, -1.0, 1.0), std::clamp(pr.eta, -1.0, 1.0))
                                .x);
      const double tie = 1e-9 * pass.reach[static_cast<std::size_t>(f)];
      if (d < distance - tie || (d <= distance + tie && out < overshoot)) {
        distance = d;
        overshoot = out;
        best = f;
        bp = pr;
      }
    }
    if (best >= 0 && !(bp.gap < 0.0)) best = -1;
  }
  return best;
}

}  // namespace

MeshContact make_mesh_contact(const core::ContactSpec& spec, const core::Scene& scene,
                              std::span<ElementSet* const> sets, const FeNodes& nodes) {
  MeshContact c;
  c.spec = spec;
  build_passes(c, scene, sets, nodes);
  c.thread_hits.resize(static_cast<std::size_t>(core::thread_count()));
  return c;
}

void rebuild_surfaces(MeshContact& c, const core::Scene& scene, std::span<ElementSet* const> sets,
                      const FeNodes& nodes) {
  build_passes(c, scene, sets, nodes);
}

// Pass by pass: the bins, the slaves' normals, then each slave's holding face in parallel.
void find_contacts(MeshContact& c, const FeNodes& nodes, std::span<ElementSet* const> sets,
                   const std::vector<Vec3>& x) {
  c.hits.clear();
  const bool self = c.spec.bodies[0] == c.spec.bodies[1];
  // Self-contact skips the faces of the slave's own elements: their node lists.
  std::vector<SetNodes> elements;
  if (self)
    for (const ElementSet* set : sets)
      elements.push_back({set->connectivity(), static_cast<std::size_t>(set->corners())});
  for (ContactPass& pass : c.passes) {
    if (pass.faces.empty()) continue;
    refresh_bins(pass, x, c.thread_hits.size());
    const bool facing = !pass.slave_faces.empty();
    if (facing) slave_normals(pass, x);
    for (auto& h : c.thread_hits) h.clear();
    core::parallel_chunks(pass.slaves.size(), [&](std::size_t begin, std::size_t end, int t) {
      std::vector<ContactHit>& hits = c.thread_hits[static_cast<std::size_t>(t)];
      for (std::size_t k = begin; k < end; ++k) {
        const std::int32_t slave = pass.slaves[k];
        const auto s = static_cast<std::size_t>(slave);
        if (!(nodes.mass[s] > 0.0)) continue;
        Projection bp;
        const std::int32_t best = holding_face(pass, elements, x, self, facing, slave, bp);
        pass.last_face[s] = best;
        if (best < 0) continue;
        // The projection may lie just past an edge: share the impulse by the clamped point.
        const double xi = std::clamp(bp.xi, -1.0, 1.0), eta = std::clamp(bp.eta, -1.0, 1.0);
        ContactHit hit;
        hit.slave = slave;
        hit.face = pass.faces[static_cast<std::size_t>(best)];
        hit.shape = face_point(corners(hit.face, x), xi, eta).n;
        hit.normal = bp.normal;
        hit.first_body = pass.slaves_first_body;
        hits.push_back(hit);
      }
    });
    // In slave order whatever the thread count: the sweeps see the same sequence.
    for (const auto& hits : c.thread_hits) c.hits.insert(c.hits.end(), hits.begin(), hits.end());
  }
}

}  // namespace afemp::fem

namespace afemp::fem {

namespace {

// The gap a pair's sweeps aim at, set at the first sweep from its predicted gap and the
// penalty s: (1 - s) of the predicted penetration is left to the next steps. A penetration
// already there at x^n (a surface exposed by erosion or conversion over a node that was inside
// the lost elements, what the sweeps or the penalty s < 1 left) recedes by a tenth a step, but
// by no more than 1e-4 of the face's diagonal: pushing a deep one out within a fixed number of
// steps would give the pair a speed of depth / dt, which grows as distorted elements shrink the
// step (a blunt projectile plugging a 12 mm steel plate gained 1e9 N mm that way and inverted
// an element). A deep one is thus kept and shrinks as the node moves out, as LS-DYNA's
// IGNORE = 1 tracks initial penetrations. Inlined, as the sweep it was written in.
AFEMP_INLINE inline double initial_target(const ContactHit& h, const std::vector<Vec3>& position,
                                          std::size_t slave, const Vec3& n, double gap, double s) {
  Vec3 x_now;
  for (int a = 0; a < 4; ++a)
    x_now += h.shape[static_cast<std::size_t>(a)] *
             position[static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)])];
  const double now = std::min(core::dot(n, position[slave] - x_now), 0.0);
  const double diagonal = core::norm(position[static_cast<std::size_t>(h.face[0])] -
                                     position[static_cast<std::size_t>(h.face[2])]);
  const double recede = std::min(-0.1 * now, 1e-4 * diagonal);
  return std::min((1.0 - s) * std::min(gap, 0.0), now + recede);
}

}  // namespace

// The contact step between meshes: search at the predicted positions, the sweeps, the rigid
// bodies' share, the forces and the energy.
void FeSolver::resolve_contacts(double dt) {
  search_mesh_contacts(dt);
  sweep_mesh_contacts(dt);
  settle_rigid_mesh_contacts(dt);
  const double dt_force = force_step(dt);
  report_mesh_contact_forces(dt_force);
  book_sliding_energy(dt, dt_force);
}

// Predicted end-of-step positions of the contact bodies' nodes, and the pairs there.
void FeSolver::search_mesh_contacts(double dt) {
  for (std::int32_t k : contact_nodes_) {
    const auto i = static_cast<std::size_t>(k);
    predicted_[i] = nodes_.position[i] + dt * nodes_.velocity[i];
    contact_impulse_[i] = Vec3{};
  }
  const auto search = std::chrono::steady_clock::now();
  for (MeshContact& c : contacts_) find_contacts(c, nodes_, sets_, predicted_);
  contact_search_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - search).count();
}

// Projected Gauss-Seidel (core/contact_impulse.hpp): each pair in turn takes the impulse that
// brings its predicted gap to the target (none with s = 1), its total normal impulse kept
// >= 0, then friction.
void FeSolver::sweep_mesh_contacts(double dt) {
  // Inverse mass of node i along unit direction n: its free components' share of 1/m (imposed
  // components take no impulse), or the rigid body's at that point.
  auto inverse_mass = [&](std::size_t i, const Vec3& n) {
    if (!rigid_of_node_.empty() && rigid_of_node_[i] >= 0) {
      const RigidBody& r = rigid_bodies_[static_cast<std::size_t>(rigid_of_node_[i])];
      return rigid_inverse_mass(r, nodes_.position[i] - r.centre, n);
    }
    double share = 1.0;
    if (const std::uint8_t imposed = nodes_.imposed[i])
      for (int a = 0; a < 3; ++a)
        if (imposed & (1u << a)) share -= n[a] * n[a];
    return share / nodes_.mass[i];
  };
  // Node i takes an impulse: a free node's free components change by J / m, a rigid node
  // moves along with its body's response at that point (settled after the sweeps).
  auto push = [&](std::size_t i, double w, const Vec3& n, const Vec3& impulse) {
    if (!rigid_of_node_.empty() && rigid_of_node_[i] >= 0) {
      nodes_.velocity[i] += w * core::dot(impulse, n) * n;
      contact_impulse_[i] += impulse;
      return;
    }
    Vec3 j = impulse;
    if (const std::uint8_t imposed = nodes_.imposed[i])
      for (int a = 0; a < 3; ++a)
        if (imposed & (1u << a)) j[a] = 0.0;
    nodes_.velocity[i] += (1.0 / nodes_.mass[i]) * j;
    contact_impulse_[i] += j;
  };
  constexpr int kSweeps = 8;
  for (int sweep = 0; sweep < kSweeps; ++sweep)
    for (MeshContact& c : contacts_) {
      const double s = c.spec.penalty, mu = c.spec.friction;
      // Both passes constrain the same interface: each takes half of what is left per sweep,
      // so the load is shared between them (the symmetric two-pass treatment) instead of
      // going to the first.
      const double share = c.passes.size() == 2 ? 0.5 : 1.0;
      for (ContactHit& h : c.hits) {
        const auto sl = static_cast<std::size_t>(h.slave);
        const Vec3& n = h.normal;
        const double ws = inverse_mass(sl, n);
        double w = ws;
        Vec3 x_face, v_face;
        std::array<double, 4> wa{};
        for (int a = 0; a < 4; ++a) {
          const auto q = static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)]);
          const double na = h.shape[static_cast<std::size_t>(a)];
          wa[static_cast<std::size_t>(a)] = inverse_mass(q, n);
          w += na * na * wa[static_cast<std::size_t>(a)];
          x_face += na * (nodes_.position[q] + dt * nodes_.velocity[q]);
          v_face += na * nodes_.velocity[q];
        }
        if (!(w > 0.0)) continue;  // two rigid bodies held fast: nothing can move
        const double gap = core::dot(n, nodes_.position[sl] + dt * nodes_.velocity[sl] - x_face);
        if (sweep == 0) h.target = initial_target(h, nodes_.position, sl, n, gap, s);
        const double dp =
            core::add_normal_impulse(h.normal_impulse, share * (h.target - gap), dt, w);
        Vec3 impulse = dp * n;
        if (mu > 0.0)  // the slip with the normal change the slave takes
          impulse += core::add_friction_impulse(h.tangential_impulse, h.normal_impulse, mu,
                                                nodes_.velocity[sl] + (dp * w) * n - v_face, n, w);
        push(sl, ws, n, impulse);
        for (int a = 0; a < 4; ++a)
          push(static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)]),
               wa[static_cast<std::size_t>(a)], n, -h.shape[static_cast<std::size_t>(a)] * impulse);
      }
    }
}

// Rigid bodies take the impulses their nodes got, and their nodes follow the bodies again.
void FeSolver::settle_rigid_mesh_contacts(double dt) {
  for (RigidBody& r : rigid_bodies_) {
    Vec3 impulse, angular;
    for (std::int32_t k : r.nodes) {
      const Vec3& j = contact_impulse_[static_cast<std::size_t>(k)];
      impulse += j;
      angular += core::cross(nodes_.position[static_cast<std::size_t>(k)] - r.centre, j);
    }
    const Vec3 before = r.velocity;
    external_work_ += add_impulse(r, impulse, angular);
    // Gravity's work was taken on the body's velocity before the impulse.
    external_work_ += r.mass * core::dot(scene_.run.gravity, r.velocity - before) * dt;
    for (std::int32_t k : r.nodes)
      nodes_.velocity[static_cast<std::size_t>(k)] =
          point_velocity(r, nodes_.position[static_cast<std::size_t>(k)] - r.centre);
  }
}

// Resultants (impulse over the force step), and friction's work (the tangential impulse on
// the relative slip left).
void FeSolver::report_mesh_contact_forces(double dt_force) {
  for (MeshContact& c : contacts_) {
    c.normal_force = Vec3{};
    c.tangential_force = Vec3{};
    c.normal_sum = c.tangential_sum = 0.0;
    for (const ContactHit& h : c.hits) {
      c.normal_sum += h.normal_impulse / dt_force;
      c.tangential_sum += core::norm(h.tangential_impulse) / dt_force;
      const double sign = h.first_body || c.spec.bodies[0] == c.spec.bodies[1] ? 1.0 : -1.0;
      c.normal_force += (sign * h.normal_impulse / dt_force) * h.normal;
      c.tangential_force += (sign / dt_force) * h.tangential_impulse;
      if (c.spec.friction > 0.0) {
        Vec3 v_face;
        for (int a = 0; a < 4; ++a)
          v_face += h.shape[static_cast<std::size_t>(a)] *
                    nodes_.velocity[static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)])];
        c.friction_work -=
            core::slip_work(h.tangential_impulse,
                            nodes_.velocity[static_cast<std::size_t>(h.slave)] - v_face, h.normal);
      }
    }
  }
}

// The sliding energy is minus the contact impulses' work, booked like the element forces' in
// the central difference: J / dt^n acting over the motion dt^{n-1/2} v^{n-1/2} +
// dt^{n+1/2} v^{n+1/2}, halved (on the first step the mean of v^0 and v^{1/2}:
// motion_before_step). The holds' work is external work.
// Gravity's work in the nodal update was taken on the velocities before the corrections: it
// follows the change J / m (rigid bodies: settle_rigid_mesh_contacts).
void FeSolver::book_sliding_energy(double dt, double dt_force) {
  const Vec3 g = scene_.run.gravity;
  const double before_dt = motion_before_step(dt);
  double work = 0.0, gravity = 0.0;
  for (std::int32_t k : contact_nodes_) {
    const auto i = static_cast<std::size_t>(k);
    work +=
        core::dot(contact_impulse_[i], before_dt * velocity_start_[i] + dt * nodes_.velocity[i]);
    if (rigid_of_node_.empty() || rigid_of_node_[i] < 0)
      gravity += core::dot(g, contact_impulse_[i]);
  }
  sliding_energy_ -= steps_ == 0 ? work / (before_dt + dt) : work / (2.0 * dt_force);
  external_work_ += gravity * dt;
}

double FeSolver::contact_inverse_mass(std::size_t i, const Vec3& n) const {
  if (!rigid_of_node_.empty() && rigid_of_node_[i] >= 0) {
    const RigidBody& r = rigid_bodies_[static_cast<std::size_t>(rigid_of_node_[i])];
    return rigid_inverse_mass(r, nodes_.position[i] - r.centre, n);
  }
  if (!(nodes_.mass[i] > 0.0)) return 0.0;
  double share = 1.0;
  if (const std::uint8_t imposed = nodes_.imposed[i])
    for (int a = 0; a < 3; ++a)
      if (imposed & (1u << a)) share -= n[a] * n[a];
  return share / nodes_.mass[i];
}

void FeSolver::push_contact_impulse(std::size_t i, double w, const Vec3& n, const Vec3& impulse) {
  if (!rigid_of_node_.empty() && rigid_of_node_[i] >= 0) {
    nodes_.velocity[i] += w * core::dot(impulse, n) * n;
    outside_impulse_.resize(nodes_.size());
    outside_impulse_[i] += impulse;
    return;
  }
  if (!(nodes_.mass[i] > 0.0)) return;
  Vec3 j = impulse;
  if (const std::uint8_t imposed = nodes_.imposed[i])
    for (int a = 0; a < 3; ++a)
      if (imposed & (1u << a)) j[a] = 0.0;
  nodes_.velocity[i] += (1.0 / nodes_.mass[i]) * j;
  outside_free_impulse_ += j;
}

void FeSolver::settle_contact_impulses(double dt) {
  // Gravity's work in the nodal update was taken on the velocities before the pushes.
  external_work_ += core::dot(scene_.run.gravity, outside_free_impulse_) * dt;
  outside_free_impulse_ = Vec3{};
  if (outside_impulse_.empty()) return;
  for (RigidBody& r : rigid_bodies_) {
    Vec3 impulse, angular;
    for (std::int32_t k : r.nodes) {
      Vec3& j = outside_impulse_[static_cast<std::size_t>(k)];
      impulse += j;
      angular += core::cross(nodes_.position[static_cast<std::size_t>(k)] - r.centre, j);
      j = Vec3{};
    }
    if (impulse.x == 0.0 && impulse.y == 0.0 && impulse.z == 0.0 && angular.x == 0.0 &&
        angular.y == 0.0 && angular.z == 0.0)
      continue;
    const Vec3 before = r.velocity;
    external_work_ += add_impulse(r, impulse, angular);
    external_work_ += r.mass * core::dot(scene_.run.gravity, r.velocity - before) * dt;
    for (std::int32_t k : r.nodes)
      nodes_.velocity[static_cast<std::size_t>(k)] =
          point_velocity(r, nodes_.position[static_cast<std::size_t>(k)] - r.centre);
  }
}

}  // namespace afemp::fem
