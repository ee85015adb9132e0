// Grid momentum update and boundary conditions (Ma 2005, eq 2-32): v = p / m, a = f / m,
// v^{k+1} = v + a dt, with the components a face constrains set to zero in both v and a
// (fixed: all three; symmetric: the normal one), as MPM3D does (p = 0, f = 0 there). A wall
// face holds the normal component of v and of v^{k+1} only where it points into the wall,
// so material leaves it freely: a unilateral, frictionless rigid wall on the grid. An absorbing
// face damps its nodes' updated velocity (absorbing_faces.hpp).
#include <algorithm>

#include "core/parallel.hpp"
#include "mpm/face_constraints.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

namespace {

// Eq 2-32 at one node with its conditions: v = p / m and v_new = v + dt f / m. A wall holds a
// node whose start velocity v points into it (rigid-body contact as in Bardenhagen et al.
// 2000: corrected after P2G and again after integration). Zeroing only v_new let the FLIP
// increment v_new - v hand the particles an impulse -m v the strain (computed with v held at
// 0) never saw: +11..14 % energy in the elastic bar. A node still driven into the wall
// (v_new) stops there. Returns the wall components held this step.
unsigned integrate(const Vec3& momentum, const Vec3& force, double inv_m, double dt,
                   const NodeConstraint& c, Vec3& v, Vec3& v_new) {
  v = inv_m * momentum;
  Vec3 a = inv_m * force;
  constrain(v, c.mask_for(v));
  constrain(a, c.always);
  v_new = v + dt * a;
  if (!c.any()) return 0;
  const unsigned wall = (c.mask_for(v) | c.mask_for(v_new)) & ~c.always;
  constrain(v_new, wall);
  return wall;
}

}  // namespace

void MpmSolver::apply_velocity_conditions(std::vector<Vec3>& field, bool divide_by_mass) {
  core::BackgroundGrid& g = grid_;
  const FaceConstraints constraints(g);
  const std::size_t stride = g.slot_count();
  const int fields = g.field_count();
#pragma omp parallel if (core::worth_threads(g.slot_count()))
  g.for_each_slot([&](std::size_t slot, const std::array<int, 3>& node) {
    const NodeConstraint c = constraints(node);
    for (int f = 0; f < fields; ++f) {
      const std::size_t s = slot + static_cast<std::size_t>(f) * stride;
      const double m = g.mass[s];
      if (m <= 0.0) {
        field[s] = {};
        continue;
      }
      if (divide_by_mass) field[s] *= 1.0 / m;
      if (c.any()) constrain(field[s], c.mask_for(field[s]));
    }
  });
}

void MpmSolver::grid_velocity() {
  core::BackgroundGrid& g = grid_;
  const std::size_t slots = g.field_slot_count();
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
  for (std::size_t s = 0; s < slots; ++s) g.velocity[s] = g.momentum[s];
  apply_velocity_conditions(g.velocity, true);
}

double MpmSolver::far_field(const std::array<int, 3>& node, int field, unsigned faces, double m,
                            double dt, const Vec3& v, Vec3& v_new) {
  const core::BackgroundGrid& g = grid_;
  const double h = g.cell();
  const Vec3 x =
      g.settings().min + h * Vec3{static_cast<double>(node[0]), static_cast<double>(node[1]),
                                  static_cast<double>(node[2])};
  double work = 0.0;
  for (int face = 0; face < 6; ++face) {
    if (!((faces >> face) & 1u)) continue;
    const AbsorbingFace& af = absorbing_[static_cast<std::size_t>(face)];
    const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    const std::array<int, 3> n = g.nodes();
    // The node's share of the face plane: half a cell along an axis where it sits on an edge.
    auto share = [&](int axis) {
      const int i = node[static_cast<std::size_t>(axis)],
                last = n[static_cast<std::size_t>(axis)] - 1;
      return i < 0 || i > last ? 0.0 : i == 0 || i == last ? 0.5 * h : h;
    };
    const Vec3 d = x - af.centre;
    const double r = core::norm(d);
    FarFieldNode fn;
    fn.sign = face % 2 == 1 ? 1.0 : -1.0;
    fn.area = share(b) * share(c);
    fn.static_pressure = face_pressure_;
    if (fn.area == 0.0) continue;  // a halo node beside the face (uGIMP): outside its plane
    // cos(theta) of the outgoing ray with the face normal; kept away from grazing rays, which
    // a face through the centre would meet (a symmetric face is the place for those).
    const double cosine = r > 0.0 ? std::max(fn.sign * d[a] / r, 0.1) : 1.0;
    fn.impedance = af.impedance / cosine;
    fn.rate = r > 0.0 ? af.c_longitudinal / r : 0.0;
    double& lag = far_lag_[static_cast<std::size_t>(face)][far_lag_index(face, node, field)];
    work += far_field_update(fn, m, dt, v[a], v_new[a], lag);
  }
  return work;
}

std::size_t MpmSolver::far_lag_index(int face, const std::array<int, 3>& node, int field) const {
  const int a = face / 2;
  const auto b = static_cast<std::size_t>((a + 1) % 3), c = static_cast<std::size_t>((a + 2) % 3);
  const std::array<int, 3> n = grid_.nodes();
  const std::size_t per_field = static_cast<std::size_t>(n[b]) * static_cast<std::size_t>(n[c]);
  return static_cast<std::size_t>(field) * per_field +
         static_cast<std::size_t>(node[b]) * static_cast<std::size_t>(n[c]) +
         static_cast<std::size_t>(node[c]);
}

void MpmSolver::share_far_field_lags() {
  // Each lag and a flag that a rank booked it, summed over the ranks: one rank adds the lag
  // (the others zeros, so the sum is its bits), and a lag no rank holds stays as it was, as
  // on every rank before.
  std::vector<double>& values = far_lag_shared_;
  std::array<std::size_t, 7> start{};
  for (std::size_t face = 0; face < 6; ++face) {
    start[face + 1] = start[face] + (absorbing_[face].far ? 2 * far_lag_[face].size() : 0);
  }
  if (start[6] == 0) return;
  values.assign(start[6], 0.0);
  const core::BackgroundGrid& g = grid_;
  const FaceConstraints constraints(g, &absorbing_);
  const std::size_t stride = g.slot_count();
  g.for_each_slot([&](std::size_t slot, const std::array<int, 3>& node) {
    const NodeConstraint c = constraints(node);
    if (!c.far || !books_node(slot)) return;
    for (int face = 0; face < 6; ++face) {
      if (!((c.far >> face) & 1u)) continue;
      const auto f6 = static_cast<std::size_t>(face);
      const std::size_t size = far_lag_[f6].size();
      bool on_plane = true;  // not a halo node beside the face (uGIMP), which holds no lag
      for (int axis : {(face / 2 + 1) % 3, (face / 2 + 2) % 3}) {
        const auto u = static_cast<std::size_t>(axis);
        on_plane = on_plane && node[u] >= 0 && node[u] < g.nodes()[u];
      }
      if (!on_plane) continue;
      for (int f = 0; f < g.field_count(); ++f) {
        if (!(g.mass[slot + static_cast<std::size_t>(f) * stride] > 0.0)) continue;
        const std::size_t k = far_lag_index(face, node, f);
        values[start[f6] + k] = far_lag_[f6][k];
        values[start[f6] + size + k] = 1.0;
      }
    }
  });
  ranks_->sum_in_rank_order(values);
  for (std::size_t face = 0; face < 6; ++face) {
    const std::size_t size = far_lag_[face].size();
    for (std::size_t k = 0; k < size && start[face + 1] > start[face]; ++k)
      if (values[start[face] + size + k] > 0.0) far_lag_[face][k] = values[start[face] + k];
  }
}

void MpmSolver::grid_momentum_update(double dt) {
  core::BackgroundGrid& g = grid_;
  const FaceConstraints constraints(g, &absorbing_);
  // Far-field faces keep a lag per node of their plane and velocity field (zero at the start).
  for (int face = 0; face < 6; ++face) {
    if (!absorbing_[static_cast<std::size_t>(face)].far) continue;
    const int a = face / 2;
    const std::size_t size =
        static_cast<std::size_t>(g.field_count()) *
        static_cast<std::size_t>(g.nodes()[static_cast<std::size_t>((a + 1) % 3)]) *
        static_cast<std::size_t>(g.nodes()[static_cast<std::size_t>((a + 2) % 3)]);
    if (far_lag_[static_cast<std::size_t>(face)].size() != size)
      far_lag_[static_cast<std::size_t>(face)].assign(size, 0.0);
  }
  const Vec3 gravity = scene_.run.gravity;
  const bool body_force = plan_.gravity;
  const int nt = core::thread_count();
  thread_sums_.assign(static_cast<std::size_t>(nt) * core::cache_line_doubles, 0.0);
  core::ExactSum* exact = reproducible() ? exact_thread_sums(1) : nullptr;
  wall_contact_.assign(g.field_slot_count(), 0);
  const std::size_t stride = g.slot_count();
  const int fields = g.field_count();
  const bool shared = shared_.any;
#pragma omp parallel num_threads(nt) if (core::worth_threads(g.slot_count()))
  {
    // Body-force work f_ext . (v + v_new) / 2 dt, and the absorbing and far-field faces'
    // (negative where they take energy out); summed exactly too in the reproducible mode.
    double work = 0.0;
    core::ExactSum* exact_work =
        exact ? exact + static_cast<std::size_t>(core::thread_index()) : nullptr;
    auto book_work = [&](double term) {
      work += term;
      if (exact_work) exact_work->add(term);
    };

    g.for_each_slot([&](std::size_t slot, const std::array<int, 3>& node) {
      const NodeConstraint c = constraints(node);
      // On ranks, a node of a shared block is updated on every rank that holds it and its work
      // booked by the block's owner alone.
      const double booked = books_node(slot) ? 1.0 : 0.0;
      for (int f = 0; f < fields; ++f) {  // each velocity field on its own (contact after)
        const std::size_t s = slot + static_cast<std::size_t>(f) * stride;
        const double m = g.mass[s];
        if (m <= 0.0) {
          g.velocity[s] = {};
          g.velocity_new[s] = {};
          continue;
        }
        Vec3 v, v_new;
        const unsigned wall = integrate(g.momentum[s], g.force[s], 1.0 / m, dt, c, v, v_new);
        // The components held this step are kept for the MUSL remap, which must hold them
        // too (remap_to_grid).
        if (c.any()) wall_contact_[s] = static_cast<std::uint8_t>(wall);
        g.velocity[s] = v;
        g.velocity_new[s] = v_new;
        // An absorbing face damps the stored velocity; the gravity work and the shared-field
        // shift below take the undamped one, as before the damping.
        if (c.damped) book_work(booked * absorb(m, c.damping, dt, v, g.velocity_new[s]));
        if (c.far) book_work(booked * far_field(node, f, c.far, m, dt, v, g.velocity_new[s]));
        // A field of self-updating points only: their owner counted its gravity work.
        const bool counted =
            !field_self_updated_.empty() && field_self_updated_[static_cast<std::size_t>(f)];
        if (!shared || !(shared_.mass[s] > 0.0)) {
          if (body_force && !counted)
            book_work(booked * 0.5 * dt * m * core::dot(gravity, v + v_new));
          continue;
        }
        // Contact nodes share this field with particles or bonded nodes of their body: the
        // particles' own part (the field less the nodes' mass, momentum and force) is
        // integrated too, and the shift from the field's velocities to it stored for the
        // particles' update (apply_shared_shifts). Its gravity work is the part's alone.
        const double mo = m - shared_.mass[s];
        Vec3 start, updated;
        if (mo > SelfUpdatedShare::fraction * m) {
          Vec3 vo, vo_new;
          integrate(g.momentum[s] - shared_.start[s], g.force[s] - shared_.updated[s], 1.0 / mo, dt,
                    c, vo, vo_new);
          start = vo - v;
          updated = vo_new - v_new;
          if (body_force) book_work(booked * 0.5 * dt * mo * core::dot(gravity, vo + vo_new));
        }
        shared_.start[s] = start;
        shared_.updated[s] = updated;
      }
    });
    thread_sums_[static_cast<std::size_t>(core::thread_index()) * core::cache_line_doubles] = work;
  }
  for (int t = 0; t < nt; ++t)
    external_work_ += thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
  if (exact) add_exact_thread_sums(1, exact_.data() + exact_external);
  if (ranks_) share_far_field_lags();
  if (!load_acceleration_.empty()) book_particle_load_work(dt);
}

}  // namespace afemp::mpm
