// Particles at the faces of a mesh (coupling/particle_surface_contact.hpp).
#include "coupling/particle_surface_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/contact_impulse.hpp"
#include "fem/face_projection.hpp"
#include "fem/fe_solver.hpp"
#include "mpm/stencil.hpp"

namespace afemp::coupling {

namespace {

constexpr int kSweeps = 8;
using fem::corners;
using fem::kEdgeTolerance;

}  // namespace

ParticleSurfaceContacts::ParticleSurfaceContacts(const core::Scene& scene, fem::FeSolver& fe)
    : fe_(fe) {
  for (const core::ContactSpec& c : scene.contacts) {
    if (c.method != core::ContactMethod::surface) continue;
    Pair p;
    p.spec = c;
    const bool first_particles =
        scene.bodies[static_cast<std::size_t>(c.bodies[0])].discretisation ==
        core::Discretisation::particles;
    p.particles = first_particles ? c.bodies[0] : c.bodies[1];
    p.mesh = first_particles ? c.bodies[1] : c.bodies[0];
    p.selected.assign(scene.bodies.size(), 0);
    p.selected[static_cast<std::size_t>(p.mesh)] = 1;
    pairs_.push_back(std::move(p));
  }
}

double ParticleSurfaceContacts::friction_work() const {
  double w = 0.0;
  for (const Pair& p : pairs_) w += p.friction_work;
  return w;
}

void ParticleSurfaceContacts::resolve(const mpm::GridStepAccess& access) {
  const fem::FeNodes& n = fe_.nodes();
  predicted_.resize(n.size());
  for (std::size_t i = 0; i < n.size(); ++i)
    predicted_[i] = n.position[i] + access.dt * n.velocity[i];
  for (Pair& pair : pairs_) {
    mpm::with_shape(access.plan.shape,
                    [&]<class Stencil>() { resolve_pair<Stencil>(pair, access); });
  }
}

// Bin b of x along axis d (clamped to the bins), and the key of bin (i, j, k).
AFEMP_INLINE inline std::int64_t ParticleSurfaceContacts::FaceBins::bin(const Vec3& x,
                                                                        int d) const {
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x[d] - lo[d]) / size)), 0,
                                  count[static_cast<std::size_t>(d)] - 1);
}

AFEMP_INLINE inline std::int64_t ParticleSurfaceContacts::FaceBins::key(std::int64_t i,
                                                                        std::int64_t j,
                                                                        std::int64_t k) const {
  return (k * count[1] + j) * count[0] + i;
}

// The pieces it calls are forced inline (AFEMP_INLINE): compiled apart, the sums of the
// reported forces took other multiply-adds (the last bits of the history's force columns).
template <class Stencil>
void ParticleSurfaceContacts::resolve_pair(Pair& pair, const mpm::GridStepAccess& access) {
  pair.normal_force = pair.tangential_force = Vec3{};
  // The mesh's boundary faces, made again when elements erode or convert.
  if (fe_.live_hexahedra() != pair.live) {
    pair.faces = fem::boundary_faces(fe_.hexahedra(), pair.selected);
    pair.live = fe_.live_hexahedra();
  }
  if (pair.faces.nodes.empty()) return;
  const FaceBins bins = bin_faces(pair, access.grid.cell());
  find_hits<Stencil>(pair, access, bins);
  if (hits_.size() == 0) return;
  sweep_hits(pair, access.dt);
  hits_.write_back(access.grid);
  report_forces(pair, access.dt);
}

// Outward normals and the boxes of the faces at the predicted positions; each face holds a
// particle up to half its own size behind it (its reach). Bins of the size of the largest grown
// face; a face in each bin its box touches (bin_entries_, sorted).
ParticleSurfaceContacts::FaceBins ParticleSurfaceContacts::bin_faces(Pair& pair, double cell) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::size_t nf = pair.faces.nodes.size();
  pair.outward.resize(nf);
  std::vector<std::array<Vec3, 2>>& box = face_box_;
  std::vector<double>& reach = face_reach_;
  box.resize(nf);
  reach.resize(nf);
  double largest = 0.0;
  FaceBins bins;
  Vec3& lo = bins.lo;
  Vec3& hi = bins.hi;
  lo = Vec3{inf, inf, inf};
  hi = Vec3{-inf, -inf, -inf};
  for (std::size_t f = 0; f < nf; ++f) {
    pair.outward[f] = fem::face_area_vector(pair.faces, f, fe_.hexahedra(), predicted_);
    const std::array<Vec3, 4> q = corners(pair.faces.nodes[f], predicted_);
    Vec3 a = q[0], b = q[0];
    for (const Vec3& x : q)
      for (int d = 0; d < 3; ++d) {
        a[d] = std::min(a[d], x[d]);
        b[d] = std::max(b[d], x[d]);
      }
    reach[f] = 0.5 * std::max(core::norm(q[2] - q[0]), core::norm(q[3] - q[1]));
    const double grow = reach[f] + cell;  // a particle's half width is at most about a cell
    Vec3 grown{grow, grow, grow};
    // A flat parallelogram (a rigid body's or an undeformed mesh's face) maps linearly: the
    // projection of a point that it holds falls in the face stretched by the edge tolerance,
    // and the point lies along the constant normal from there, at most the reach and a half
    // width away. Its box is that stretched face's, grown along each axis only by the normal's
    // part there (a support under a slab tests the particles above it, not those a face's size
    // beside it). A twisted face keeps the box grown every way.
    const Vec3 twist = q[0] - q[1] + q[2] - q[3];
    const double size = 2.0 * reach[f];
    const double area = core::norm(pair.outward[f]);
    if (core::norm(twist) <= 1e-9 * size && area > 0.0) {
      const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
      const Vec3 normal = (1.0 / area) * pair.outward[f];
      const double slack = 1e-6 * size;  // round-off of the projection's two steps
      constexpr double stretch = 1.0 + kEdgeTolerance;
      for (int d = 0; d < 3; ++d) {
        a[d] = b[d] = centre[d];
        for (const Vec3& x : q) {
          a[d] = std::min(a[d], centre[d] + stretch * (x[d] - centre[d]));
          b[d] = std::max(b[d], centre[d] + stretch * (x[d] - centre[d]));
        }
        grown[d] = std::min(grow, grow * std::abs(normal[d]) + slack);
      }
    }
    for (int d = 0; d < 3; ++d) {
      a[d] -= grown[d];
      b[d] += grown[d];
      lo[d] = std::min(lo[d], a[d]);
      hi[d] = std::max(hi[d], b[d]);
      largest = std::max(largest, b[d] - a[d]);
    }
    box[f] = {a, b};
  }
  bins.size = largest;
  for (int d = 0; d < 3; ++d)
    bins.count[static_cast<std::size_t>(d)] = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(std::ceil((hi[d] - lo[d]) / bins.size)));
  std::vector<std::pair<std::int64_t, std::int32_t>>& entries = bin_entries_;
  entries.clear();
  for (std::size_t f = 0; f < nf; ++f)
    for (std::int64_t k = bins.bin(box[f][0], 2); k <= bins.bin(box[f][1], 2); ++k)
      for (std::int64_t j = bins.bin(box[f][0], 1); j <= bins.bin(box[f][1], 1); ++j)
        for (std::int64_t i = bins.bin(box[f][0], 0); i <= bins.bin(box[f][1], 0); ++i)
          entries.emplace_back(bins.key(i, j, k), static_cast<std::int32_t>(f));
  std::sort(entries.begin(), entries.end());
  return bins;
}

// The nearest face of x's bin that holds a particle of half width r at x (by the distance to
// the face itself): it projects inside the face and its boundary lies behind it, less than the
// face's reach. Fills best's face, shape functions and normal; false when none holds it.
// Inlined, as the hit search it was written in.
AFEMP_INLINE inline bool ParticleSurfaceContacts::nearest_face(const Pair& pair,
                                                               const FaceBins& bins, const Vec3& x,
                                                               double r, Hit& best) const {
  const std::int64_t b = bins.key(bins.bin(x, 0), bins.bin(x, 1), bins.bin(x, 2));
  const auto by_bin = [](const std::pair<std::int64_t, std::int32_t>& e, std::int64_t bin) {
    return e.first < bin;
  };
  const auto first = std::lower_bound(bin_entries_.begin(), bin_entries_.end(), b, by_bin);
  double distance = std::numeric_limits<double>::infinity();
  bool found = false;
  for (auto it = first; it != bin_entries_.end() && it->first == b; ++it) {
    const auto f = static_cast<std::size_t>(it->second);
    const auto& bx = face_box_[f];
    if (x.x < bx[0].x || x.x > bx[1].x || x.y < bx[0].y || x.y > bx[1].y || x.z < bx[0].z ||
        x.z > bx[1].z)
      continue;
    fem::Projection pr;
    if (!fem::project(corners(pair.faces.nodes[f], predicted_), x, pr)) continue;
    constexpr double lim = 1.0 + kEdgeTolerance;
    if (std::abs(pr.xi) > lim || std::abs(pr.eta) > lim) continue;
    const double sign = core::dot(pr.normal, pair.outward[f]) < 0.0 ? -1.0 : 1.0;
    const double gap = sign * pr.gap - r;
    if (!(gap < 0.0) || -gap > face_reach_[f] + r) continue;
    if (std::abs(gap) < distance) {
      distance = std::abs(gap);
      best.face = pair.faces.nodes[f];
      best.shape = fem::face_point(corners(best.face, predicted_), std::clamp(pr.xi, -1.0, 1.0),
                                   std::clamp(pr.eta, -1.0, 1.0))
                       .n;
      best.normal = sign * pr.normal;
      found = true;
    }
  }
  return found;
}

// Hits: each particle of the body whose predicted boundary lies behind a face, at its
// predicted position (this step's grid velocity at it), with its live stencil nodes and
// weights; on ranks, every rank's (collective).
template <class Stencil>
AFEMP_INLINE inline void ParticleSurfaceContacts::find_hits(const Pair& pair,
                                                            const mpm::GridStepAccess& access,
                                                            const FaceBins& bins) {
  constexpr int K = Stencil::nodes;
  core::BackgroundGrid& g = access.grid;
  const mpm::Particles& p = access.particles;
  const double dt = access.dt;
  hits_.begin(K);
  slots_.resize(K);
  weights_.resize(K);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != pair.particles) continue;
    const Vec3& x0 = p.position[i];
    const double travel = dt * core::norm(p.velocity[i]) + g.cell();
    bool outside = false;
    for (int d = 0; d < 3; ++d)
      outside = outside || x0[d] < bins.lo[d] - travel || x0[d] > bins.hi[d] + travel;
    if (outside) continue;
    const Stencil st(g, p, i, x0);
    typename Stencil::Slots slot;
    st.slots(g, slot);
    const std::size_t field = access.field_offset(p.body[i]);
    Vec3 v;
    for (int k = 0; k < K; ++k)
      v += st.w(k) *
           g.velocity_new[static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]) + field];
    const Vec3 x = x0 + dt * v;
    const double r = mpm::particle_half_width(p.volume[i]);
    Hit best;
    if (!nearest_face(pair, bins, x, r, best)) continue;
    best.id = p.id[i];
    best.position = x0;
    best.radius = r;
    for (int k = 0; k < K; ++k) {
      const auto s = static_cast<std::int64_t>(slot[static_cast<std::size_t>(k)] + field);
      const bool live = st.w(k) > 0.0 && g.mass[static_cast<std::size_t>(s)] > 0.0;
      slots_[static_cast<std::size_t>(k)] = live ? s : -1;
      weights_[static_cast<std::size_t>(k)] = live ? st.w(k) : 0.0;
    }
    hits_.add(best, slots_, weights_);
  }
  hits_.finish(g, access.ranks);
}

// The face point of a hit at the predicted positions, and its velocity.
AFEMP_INLINE inline void ParticleSurfaceContacts::face_state(const Hit& h, double dt, Vec3& x_face,
                                                             Vec3& v_face) const {
  const fem::FeNodes& nodes = fe_.nodes();
  x_face = v_face = Vec3{};
  for (int a = 0; a < 4; ++a) {
    const auto q = static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)]);
    const double na = h.shape[static_cast<std::size_t>(a)];
    x_face += na * (nodes.position[q] + dt * nodes.velocity[q]);
    v_face += na * nodes.velocity[q];
  }
}

// Projected Gauss-Seidel sweeps in id order (core/contact_impulse.hpp): J n spread over the
// particle's grid nodes by their weights (the grid's face constraints kept), -N_a J n on the
// face's nodes.
void ParticleSurfaceContacts::sweep_hits(const Pair& pair, double dt) {
  const fem::FeNodes& nodes = fe_.nodes();
  const double s_pen = pair.spec.penalty, mu = pair.spec.friction;
  for (int sweep = 0; sweep < kSweeps; ++sweep)
    for (std::size_t c = 0; c < hits_.size(); ++c) {
      Hit& h = hits_[c];
      const Vec3& nrm = h.normal;
      if (sweep == 0) {  // the inverse masses hold through the sweeps
        h.w = hits_.particle_inverse_mass(c);
        for (int a = 0; a < 4; ++a) {
          const auto q = static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)]);
          const double na = h.shape[static_cast<std::size_t>(a)];
          h.w_face[static_cast<std::size_t>(a)] = fe_.contact_inverse_mass(q, nrm);
          h.w += na * na * h.w_face[static_cast<std::size_t>(a)];
        }
      }
      const double w = h.w;
      const std::array<double, 4>& wa = h.w_face;
      if (!(w > 0.0)) continue;
      const Vec3 xp = h.position;
      Vec3 x_face, v_face;
      face_state(h, dt, x_face, v_face);
      const Vec3 vp = hits_.particle_velocity(c);  // nothing is pushed before the friction reads it
      const double gap = core::dot(nrm, xp + dt * vp - x_face) - h.radius;
      if (sweep == 0) {
        Vec3 x_now;
        for (int a = 0; a < 4; ++a)
          x_now += h.shape[static_cast<std::size_t>(a)] *
                   nodes.position[static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)])];
        const double now = core::dot(nrm, xp - x_now) - h.radius;
        h.target = std::min((1.0 - s_pen) * std::min(gap, 0.0), 0.9 * std::min(now, 0.0));
      }
      const double dj = core::add_normal_impulse(h.normal_impulse, h.target - gap, dt, w);
      Vec3 impulse = dj * nrm;
      // The slip of the relative velocity before the normal impulse (which would change only
      // its normal part) and the stick impulse within mu J.
      if (mu > 0.0)
        impulse += core::add_friction_impulse(h.tangential_impulse, h.normal_impulse, mu,
                                              vp - v_face, nrm, w);
      hits_.push(c, impulse);
      for (int a = 0; a < 4; ++a)
        fe_.push_contact_impulse(static_cast<std::size_t>(h.face[static_cast<std::size_t>(a)]),
                                 wa[static_cast<std::size_t>(a)], nrm,
                                 -h.shape[static_cast<std::size_t>(a)] * impulse);
    }
}

// Resultants on the particle body (impulse over the step) and friction's work (the
// tangential impulse against the slip it left): whole on every rank, which swept every hit.
void ParticleSurfaceContacts::report_forces(Pair& pair, double dt) const {
  for (std::size_t c = 0; c < hits_.size(); ++c) {
    const Hit& h = hits_[c];
    pair.normal_force += (h.normal_impulse / dt) * h.normal;
    pair.tangential_force += (1.0 / dt) * h.tangential_impulse;
    if (pair.spec.friction > 0.0) {
      Vec3 x_face, v_face;
      face_state(h, dt, x_face, v_face);
      pair.friction_work -=
          core::slip_work(h.tangential_impulse, hits_.particle_velocity(c) - v_face, h.normal);
    }
  }
}

}  // namespace afemp::coupling
