// The reproducible mode of the MPM step ([run] reproducible = true; docs/parallel.md, "The
// reproducible mode"). A node's sum of its particles' terms is otherwise added in the order the
// particles lie in memory and, on ranks, rank by rank: another rank count or another order
// gives another rounding. Here each term is turned into 128-bit fixed point (core/exact_sum.hpp)
// and the terms added as integers, whose sum does not depend on their order; the energies,
// works and forces summed over particles or nodes are kept exactly (ExactSum, after Neal
// 2015). What a particle or a node then computes from those sums is the same bits on any rank
// and thread count, and so is every history column.
//
// The fixed point's scale: per array and per scatter, from a bound on the terms over every
// rank's particles (the largest mass, momentum, internal and body force, mass gradient a
// particle can give a node), so that the largest term is near 2^62 and a term is cut below
// 2^-61 of the bound; a term 2^54 past its bound stops the run (core::to_fixed). The mesh points
// on the grid (grid_points.hpp: the couplings' FE nodes) add their terms into the same sums,
// their bounds raising the scales, before the sums are made whole.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {
namespace {

// The largest magnitude of a symmetric tensor's components.
double largest_component(const core::SymTensor& s) {
  return std::max({std::fabs(s.xx), std::fabs(s.yy), std::fabs(s.zz), std::fabs(s.xy),
                   std::fabs(s.yz), std::fabs(s.xz)});
}

double largest_component(const Vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

}  // namespace

void MpmSolver::start_fixed_scatter(FixedScatter what) {
  const Particles& p = particles_;
  const core::BackgroundGrid& g = grid_;
  const double h = g.cell();
  // A weight is at most 1 and a weight's gradient at most 1 / h a component for every shape
  // the mode takes (the linear hat, uGIMP, the B-splines); 2 / h leaves room, and the
  // total-Lagrangian map of the gradients (F^-T) is inside the 2^54 a term may pass its bound by.
  const double grad = 2.0 / h;
  const bool affine = plan_.transfer == core::Transfer::apic && !p.affine.empty();
  const double gravity = largest_component(scene_.run.gravity);
  const double ambient = ambient_pressure_;
  double bound[4] = {0.0, 0.0, 0.0, 0.0};  // mass, momentum, force, mass gradient
  const auto n = static_cast<std::int64_t>(p.size());
  double b0 = 0.0, b1 = 0.0, b2 = 0.0;
#pragma omp parallel for schedule(static) \
    reduction(max                         \
              : b0, b1, b2) if (core::worth_threads(p.size()))
  for (std::int64_t q = 0; q < n; ++q) {
    const auto i = static_cast<std::size_t>(q);
    const double m = p.mass[i];
    b0 = std::max(b0, m);
    // m S (v_p + C_p (x_I - x_p)) with |x_I - x_p| at most 2 cells a component.
    double c = 0.0;
    if (affine)
      for (const auto& row : p.affine[i].m)
        for (const double e : row) c = std::max(c, std::fabs(e));
    b1 = std::max(b1, m * (largest_component(p.velocity[i]) + 6.0 * h * c));
    // -V (sigma - (q - p_amb) I) grad S + m S g, three terms a component; a load's m a S.
    const double s = largest_component(p.stress[i]) + std::fabs(p.bulk_q[i] - ambient);
    b2 = std::max({b2, 3.0 * p.volume[i] * s * grad + m * gravity, largest_particle_load(i)});
  }
  // The mesh points' terms (grid_points.hpp: the couplings' FE nodes), from every point.
  FixedBounds points;
  if (points_) points_->raise_fixed_bounds(access(), points);
  bound[0] = std::max(b0, points.mass);
  bound[1] = std::max(b1, points.momentum);
  bound[2] = std::max(b2, points.force);
  bound[3] = std::max(b0 * grad, points.gradient);
  if (ranks_)
    for (double& b : bound) b = ranks_->max_over_ranks(b);
  FixedNodes& f = fixed_;
  const std::size_t slots = g.field_slot_count();
  const bool mass_momentum =
      what == FixedScatter::mass_momentum_force || what == FixedScatter::mass_momentum;
  const bool force = what == FixedScatter::mass_momentum_force || what == FixedScatter::force;
  if (mass_momentum) {
    f.mass_scale = core::fixed_scale(bound[0]);
    f.momentum_scale = core::fixed_scale(bound[1]);
    f.mass.assign(slots, 0);
    f.momentum.assign(3 * slots, 0);
  }
  if (force) {
    f.force_scale = core::fixed_scale(bound[2]);
    f.force.assign(3 * slots, 0);
  }
  if (what == FixedScatter::remap) {
    f.momentum_scale = core::fixed_scale(bound[1]);
    f.remap.assign(3 * slots, 0);
  }
  if (what == FixedScatter::gradient) {
    f.gradient_scale = core::fixed_scale(bound[3]);
    f.gradient.assign(3 * slots, 0);
  }
  fixed_ok_.assign(static_cast<std::size_t>(core::thread_count()), 1);
  f.points_ok = true;
}

void MpmSolver::finish_fixed_scatter(FixedScatter what) {
  core::BackgroundGrid& g = grid_;
  FixedNodes& f = fixed_;
  const bool mass_momentum =
      what == FixedScatter::mass_momentum_force || what == FixedScatter::mass_momentum;
  const bool force = what == FixedScatter::mass_momentum_force || what == FixedScatter::force;
  const char* array = what == FixedScatter::remap      ? "remapped momentum"
                      : what == FixedScatter::gradient ? "mass gradient"
                                                       : "mass, momentum or force";
  stop_past_fixed_bound(!f.points_ok                                            ? 2
                        : std::count(fixed_ok_.begin(), fixed_ok_.end(), 0) > 0 ? 1
                                                                                : 0,
                        "the grid's nodal sums", array, "stress, force or velocity");
  // The self-updating points' share of a field (grid_points.hpp), scattered with the sums.
  const bool share = shared_.any && what != FixedScatter::remap && what != FixedScatter::gradient;
  if (ranks_) {
    std::array<core::NodalArray, 6> arrays;
    std::size_t n = 0;
    auto add = [&](std::vector<core::Fixed>& v, int per_slot) {
      arrays[n++] = {reinterpret_cast<double*>(v.data()), 2 * per_slot, false, true};
    };
    if (mass_momentum) {
      add(f.mass, 1);
      add(f.momentum, 3);
    }
    if (force) add(f.force, 3);
    if (what == FixedScatter::remap) add(f.remap, 3);
    if (what == FixedScatter::gradient) add(f.gradient, 3);
    if (share && mass_momentum) {
      add(f.share_mass, 1);
      add(f.share_start, 3);
    }
    if (share && force) add(f.share_updated, 3);
    sum_shared_blocks(std::span<const core::NodalArray>(arrays.data(), n));
  }
  const std::size_t slots = g.field_slot_count();
  auto vector_of = [](const std::vector<core::Fixed>& v, std::size_t s,
                      const core::FixedScale& scale) {
    return Vec3{core::from_fixed(v[3 * s], scale), core::from_fixed(v[3 * s + 1], scale),
                core::from_fixed(v[3 * s + 2], scale)};
  };
#pragma omp parallel for schedule(static) if (core::worth_threads(slots))
  for (std::size_t s = 0; s < slots; ++s) {
    if (mass_momentum) {
      g.mass[s] = core::from_fixed(f.mass[s], f.mass_scale);
      g.momentum[s] = vector_of(f.momentum, s, f.momentum_scale);
    }
    if (force) g.force[s] = vector_of(f.force, s, f.force_scale);
    if (what == FixedScatter::remap) g.velocity_remap[s] = vector_of(f.remap, s, f.momentum_scale);
    if (what == FixedScatter::gradient)
      g.mass_gradient[s] = vector_of(f.gradient, s, f.gradient_scale);
    if (share && mass_momentum) {
      shared_.mass[s] = core::from_fixed(f.share_mass[s], f.mass_scale);
      shared_.start[s] = vector_of(f.share_start, s, f.momentum_scale);
    }
    if (share && force) shared_.updated[s] = vector_of(f.share_updated, s, f.force_scale);
  }
}

void MpmSolver::stop_past_fixed_bound(int passed, const char* sums, const char* array,
                                      const char* runaway) const {
  // A term past its bound on any rank stops every rank, the same step, each naming what did
  // (1: a particle's, 2: a mesh node's term, on some rank; the larger wins).
  double bad = passed;
  if (ranks_) bad = ranks_->max_over_ranks(bad);
  if (!(bad > 0.0)) return;
  const bool node = bad > 1.0;
  throw core::SimulationError(
      steps_, time_, sums, array,
      std::string(node ? "a mesh node's" : "a particle's") +
          " term passed 2^54 times the bound its fixed-point sum was scaled by ([run] "
          "reproducible = true): a non-finite or runaway " +
          runaway + "; the run without the reproducible mode would show which " +
          (node ? "node" : "particle"));
}

core::ExactSum* MpmSolver::exact_thread_sums(std::size_t per) {
  const auto nt = static_cast<std::size_t>(core::thread_count());
  if (exact_threads_.size() < nt * per) exact_threads_.resize(nt * per);
  for (core::ExactSum& s : exact_threads_) s.clear();
  return exact_threads_.data();
}

void MpmSolver::add_exact_thread_sums(std::size_t per, core::ExactSum* into) {
  const auto nt = static_cast<std::size_t>(core::thread_count());
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t k = 0; k < per; ++k) into[k] += exact_threads_[t * per + k];
}

Energies MpmSolver::reproducible_energies() const {
  // energies() with every sum exact: per thread, then over the threads, the running works
  // and the ranks.
  const Particles& p = particles_;
  const std::size_t nb = scene_.bodies.size();
  const std::size_t width = 2 + 6 * nb;  // as energies(): kinetic, internal, per body 6
  const bool affine = plan_.transfer == core::Transfer::apic;
  const int nt = core::thread_count();
  std::vector<core::ExactSum> partial(width * static_cast<std::size_t>(nt));
#pragma omp parallel num_threads(nt) if (core::worth_threads(p.size()))
  {
    const int t = core::thread_index();
    const auto [b, e] = core::static_range(p.size(), t, core::team_size());
    core::ExactSum* acc = partial.data() + width * static_cast<std::size_t>(t);
    for (std::size_t i = b; i < e; ++i) {
      const Vec3& v = p.velocity[i];
      const double m = p.mass[i];
      const double kinetic = particle_kinetic_energy(i, affine);
      const double internal = m * p.energy[i];
      acc[0].add(kinetic);
      acc[1].add(internal);
      core::ExactSum* body = acc + 2 + 6 * static_cast<std::size_t>(p.body[i]);
      body[0].add(m);
      body[1].add(m * v.x);
      body[2].add(m * v.y);
      body[3].add(m * v.z);
      body[4].add(kinetic);
      body[5].add(internal);
    }
  }
  std::vector<core::ExactSum> sums(width + exact_.size());
  for (int t = 0; t < nt; ++t)
    for (std::size_t k = 0; k < width; ++k)
      sums[k] += partial[width * static_cast<std::size_t>(t) + k];
  std::copy(exact_.begin(), exact_.end(), sums.begin() + static_cast<std::ptrdiff_t>(width));
  const std::vector<double> v = core::exact_values(ranks_, sums);
  Energies out;
  out.kinetic = v[0];
  out.internal = v[1];
  out.bodies.resize(nb);
  for (std::size_t k = 0; k < nb; ++k) {
    const double* b = v.data() + 2 + 6 * k;
    out.bodies[k].mass = b[0];
    out.bodies[k].momentum = Vec3{b[1], b[2], b[3]};
    out.bodies[k].kinetic = b[4];
    out.bodies[k].internal = b[5];
  }
  out.plastic = v[width + exact_plastic];
  out.viscous = v[width + exact_viscous];
  out.external_work = v[width + exact_external];
  out.contact = v[width + exact_contact];
  out.outflow = v[width + exact_outflow_energy];
  out.outflow_mass = v[width + exact_outflow_mass];
  const double* taken = v.data() + width + exact_outflow_momentum;
  out.outflow_momentum = Vec3{taken[0], taken[1], taken[2]};
  out.sliding = wall_sliding_;
  out.friction = wall_friction_;
  return out;
}

}  // namespace afemp::mpm
