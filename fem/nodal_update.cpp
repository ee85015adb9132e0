// The nodal half of the central-difference step (Belytschko, Liu & Moran box 6.1):
// f = sum of element forces (gathered through the incidence lists) + m g + program loads,
// v^{n+1/2} = v^{n-1/2} + dt^n f / m with dt^n = (dt^{n-1/2} + dt^{n+1/2}) / 2 (half a step
// on the first), imposed components set, rigid walls, x^{n+1} = x^n + dt v^{n+1/2}.
// Also the step itself, the stable step, the energies and dynamic relaxation's damping of the
// velocities.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

namespace {
// Nodes ahead whose element forces the gather asks for early: each node's eight sit in four
// places of element_force_ (the elements before and behind it in the mesh's two slower
// directions), and waiting for them one node at a time left the update at about 60 ns a node
// (HEX-BLOCK); 8 and 16 ahead measured the same.
constexpr std::size_t kForcePrefetch = 8;

void prefetch(const void* address) {
#if defined(__GNUC__)
  __builtin_prefetch(address);
#endif
}
}  // namespace

void FeSolver::update_nodes(double dt) {
  const double dt_force = force_step(dt);
  const Vec3 g = scene_.run.gravity;
  const bool gravity = g.x != 0.0 || g.y != 0.0 || g.z != 0.0;
  const std::size_t n = nodes_.size();
  // A program's held loads and the scene's [[loads]] at this step's start.
  const bool program_loads = !nodes_.external_force.empty();
  const bool scene_loads = !load_force_.empty();
  const bool loads = program_loads || scene_loads;
  auto load = [&](std::size_t s) {
    Vec3 f;
    if (program_loads) f += nodes_.external_force[s];
    if (scene_loads) f += load_force_[s];
    return f;
  };
  const bool rigid = !rigid_of_node_.empty();
  const bool tied = !embedded_.empty();
  std::fill(thread_sums_.begin(), thread_sums_.end(), 0.0);
  for (auto& e : thread_errors_) e.clear();
  for (core::ExactSum& s : exact_mirror_) s.clear();
  core::parallel_chunks(n, [&](std::size_t begin, std::size_t end, int t) {
    double work = 0.0;
    // The reproducible mode: each term also into the exact sum mirroring the thread's entry 1.
    double* sums = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
    auto add_work = [&](double term) {
      work += term;
      if (!exact_mirror_.empty()) book(sums, 1, term);
    };
    for (std::size_t i = begin; i < end; ++i) {
      // The element forces of a node a few ahead, so that their loads overlap this node's
      // (the sums keep their order: the same bits).
      if (i + kForcePrefetch < end)
        for (std::int64_t k = incidence_offsets_[i + kForcePrefetch];
             k < incidence_offsets_[i + kForcePrefetch + 1]; ++k)
          prefetch(
              &element_force_[static_cast<std::size_t>(incidence_[static_cast<std::size_t>(k)])]);
      const double m = nodes_.mass[i];
      if (!(m > 0.0)) continue;                       // no live element: out of the update
      if (nodes_.grid_driven[i]) continue;            // moved by the background grid (coupling/)
      if (rigid && rigid_of_node_[i] >= 0) continue;  // moved by its body (rigid_body_update.cpp)
      Vec3 f = node_force(i);
      // A host node carries the forces of the tied nodes in its elements (their masses are
      // in m): f_a += N_a f_s, the loads a program puts on them included.
      if (tied)
        for (std::int64_t k = embedded_.offsets[i]; k < embedded_.offsets[i + 1]; ++k) {
          const auto [tie, corner] = embedded_.ties[static_cast<std::size_t>(k)];
          if (!embedded_.bound(static_cast<std::size_t>(tie), hexes_)) continue;
          const auto s = static_cast<std::size_t>(embedded_.node[static_cast<std::size_t>(tie)]);
          const double w =
              embedded_.weight[static_cast<std::size_t>(tie)][static_cast<std::size_t>(corner)];
          f += w * node_force(s);
          if (loads) f += w * load(s);
        }
      Vec3& v = nodes_.velocity[i];
      v += (dt_force / m) * f;
      if (gravity) {
        v += dt_force * g;
      }
      const Vec3 f_load = loads ? load(i) : Vec3{};
      if (loads) v += (dt_force / m) * f_load;
      if (const std::uint8_t imposed = nodes_.imposed[i]) {
        for (int a = 0; a < 3; ++a)
          if (imposed & (1u << a)) {
            // The reaction impulse m (v_imposed - v) does work at the imposed velocity.
            const double target = nodes_.imposed_velocity[i][a];
            add_work(m * (target - v[a]) * target);
            v[a] = target;
          }
      }
      if (gravity) add_work(m * core::dot(g, v) * dt);
      if (loads) add_work(core::dot(f_load, v) * dt);
      if (!std::isfinite(v.x + v.y + v.z) && thread_errors_[static_cast<std::size_t>(t)].empty()) {
        thread_errors_[static_cast<std::size_t>(t)] = "node " + std::to_string(i);
        thread_error_field_[static_cast<std::size_t>(t)] = "velocity";
      }
    }
    sums[0] = work;
  });
  raise_thread_errors();
  if (reproducible()) {  // every rank moves every node: the same exact sum on each
    external_work_ += exact_threads(1).value();
    return;
  }
  for (std::size_t t = 0; t < thread_errors_.size(); ++t)
    external_work_ += thread_sums_[t * core::cache_line_doubles];
}

void FeSolver::step(double dt) {
  begin_step(dt);
  finish_step(dt);
}

void FeSolver::scale_velocities(double factor) {
  const bool rigid = !rigid_of_node_.empty();
  core::parallel_chunks(nodes_.size(), [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i) {
      if (rigid && rigid_of_node_[i] >= 0) continue;  // follows its body below
      Vec3& v = nodes_.velocity[i];
      v *= factor;
      if (const std::uint8_t imposed = nodes_.imposed[i])
        for (int a = 0; a < 3; ++a)
          if (imposed & (1u << a)) v[a] = nodes_.imposed_velocity[i][a];
    }
  });
  for (RigidBody& r : rigid_bodies_) {
    scale_motion(r, factor);
    for (std::int32_t k : r.nodes) {
      const auto i = static_cast<std::size_t>(k);
      nodes_.velocity[i] = point_velocity(r, nodes_.position[i] - r.centre);
    }
  }
}

void FeSolver::set_body_velocity(int body, const Vec3& v) {
  const bool rigid = !rigid_of_node_.empty();
  // Nodes the grid drives (shared with elements converted into particles) are set too: the grid
  // gives them their velocity at the next step, but the kinetic energy booked now (a relaxation
  // phase gives a held projectile its velocity back) is read from them.
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_.body[i] != body || (rigid && rigid_of_node_[i] >= 0)) continue;
    for (int a = 0; a < 3; ++a)
      if (!(nodes_.imposed[i] & (1u << a))) nodes_.velocity[i][a] = v[a];
  }
  if (!embedded_.empty()) follow_hosts(embedded_, nodes_, hexes_);
  for (RigidBody& r : rigid_bodies_) {
    if (r.body != body) continue;
    for (int a = 0; a < 3; ++a)
      if (!r.fixed[static_cast<std::size_t>(a)]) r.velocity[a] = v[a];
    r.angular_momentum = r.angular_velocity = Vec3{};
    for (std::int32_t k : r.nodes) {
      const auto i = static_cast<std::size_t>(k);
      nodes_.velocity[i] = point_velocity(r, nodes_.position[i] - r.centre);
    }
  }
}

void FeSolver::hold_body(int body, bool hold) {
  if (!hold) {
    std::vector<HeldNode> kept;
    for (const HeldNode& h : held_) {
      if (nodes_.body[h.node] != body) {
        kept.push_back(h);
        continue;
      }
      nodes_.imposed[h.node] = h.imposed;
      nodes_.imposed_velocity[h.node] = h.velocity;
    }
    held_.swap(kept);
    return;
  }
  const bool rigid = !rigid_of_node_.empty();
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_.body[i] != body || (rigid && rigid_of_node_[i] >= 0) ||
        (!nodes_.grid_driven.empty() && nodes_.grid_driven[i]))
      continue;
    held_.push_back({static_cast<std::uint32_t>(i), nodes_.imposed[i], nodes_.imposed_velocity[i]});
    nodes_.imposed[i] = 7;
    nodes_.imposed_velocity[i] = nodes_.velocity[i] = Vec3{};
  }
}

void FeSolver::apply_velocity_curves(double t) {
  for (const VelocityCurve& vc : velocity_curves_) {
    const double f = core::curve_factor(vc.curve, t);
    for (const auto& [n, a] : vc.components) nodes_.imposed_velocity[n][a] = f * vc.velocity[a];
  }
}

std::vector<Vec3> FeSolver::imposed_travel(double t0, double t1) const {
  std::vector<Vec3> travel(nodes_.size());
  for (std::size_t n = 0; n < nodes_.size(); ++n)
    for (int a = 0; a < 3; ++a)
      if (nodes_.imposed[n] & (1u << a)) travel[n][a] = nodes_.imposed_velocity[n][a] * (t1 - t0);
  for (const VelocityCurve& vc : velocity_curves_) {
    // The factor is linear between the curve's points and constant beyond its ends: the
    // trapezoidal rule over [t0, t1] cut at the points is exact.
    std::vector<double> at{t0};
    for (const auto& point : vc.curve)
      if (point[0] > t0 && point[0] < t1) at.push_back(point[0]);
    at.push_back(t1);
    double integral = 0.0;
    for (std::size_t k = 1; k < at.size(); ++k)
      integral += 0.5 * (at[k] - at[k - 1]) *
                  (core::curve_factor(vc.curve, at[k - 1]) + core::curve_factor(vc.curve, at[k]));
    for (const auto& [n, a] : vc.components) travel[n][a] = vc.velocity[a] * integral;
  }
  return travel;
}

void FeSolver::begin_step(double dt) {
  // A curved prescribed velocity takes its value at the step's mid-time, the time of the
  // v^{n+1/2} that moves the nodes.
  if (!velocity_curves_.empty()) apply_velocity_curves(time_ + 0.5 * dt);
  // Loads, as gravity, at the step's start: the force that changes v^{n-1/2} into v^{n+1/2}.
  if (!nodal_loads_.empty()) apply_loads(time_);
  run_stage(FeStageKind::nodal_update, [&] {
    for (std::int32_t k : contact_nodes_)
      velocity_start_[static_cast<std::size_t>(k)] = nodes_.velocity[static_cast<std::size_t>(k)];
    for (std::size_t k = 0; k < absorbing_nodes_.size(); ++k)
      absorbing_start_[k] = nodes_.velocity[absorbing_nodes_[k].node];
    for (WallState& w : walls_) {
      w.start.resize(w.nodes.size());
      for (std::size_t k = 0; k < w.nodes.size(); ++k)
        w.start[k] = nodes_.velocity[static_cast<std::size_t>(w.nodes[k])];
    }
    update_nodes(dt);
    if (!nodal_loads_.empty()) book_load_change(dt);
    if (!absorbing_nodes_.empty()) absorb(dt);
  });
  run_stage(FeStageKind::rigid_bodies, [&] { advance_rigid_bodies(dt); });
  run_stage(FeStageKind::mesh_contact, [&] { resolve_contacts(dt); });
  run_stage(FeStageKind::rigid_walls, [&] { apply_walls(dt); });
}

void FeSolver::finish_step(double dt) {
  // Positions after every velocity condition, so the walls see the final v^{n+1/2}. Rigid
  // nodes follow their body's motion exactly (no later stage changes their velocities: walls,
  // constraints, absorbing boundaries and grid contact leave rigid bodies out).
  if (!rigid_bodies_.empty()) run_stage(FeStageKind::rigid_bodies, [&] { move_rigid_bodies(dt); });
  const std::size_t n = nodes_.size();
  const bool rigid = !rigid_of_node_.empty();
  core::parallel_chunks(n, [&](std::size_t begin, std::size_t end, int) {
    for (std::size_t i = begin; i < end; ++i)
      if (nodes_.mass[i] > 0.0 && !nodes_.grid_driven[i] && !(rigid && rigid_of_node_[i] >= 0))
        nodes_.position[i] += dt * nodes_.velocity[i];
  });
  if (!embedded_.empty()) follow_hosts(embedded_, nodes_, hexes_);
  for (ElementSet* set : sets_) run_stage(set->stage(), [&] { set->update(*this, dt); });
  if (ranks_) share_element_results();
  time_ += dt;
  ++steps_;
  previous_dt_ = dt;
  // Elements left the mesh (eroded or converted): the node masses follow, in the erosion
  // stage, or in the conversion stage where no body erodes.
  if (erosion_this_step_)
    run_stage(
        plan_.index(FeStageKind::erosion) >= 0 ? FeStageKind::erosion : FeStageKind::conversion,
        [&] { finish_erosion(); });
}

double FeSolver::element_step_limit() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const ElementSet* set : sets_) {
    const ElementStore& el = set->store();
    for (std::size_t e = 0; e < el.size(); ++e)
      if (el.alive[e]) dt = std::min(dt, el.critical_dt[e]);
  }
  return scene_.run.element_time_step_factor * dt;
}

double FeSolver::stable_time_step() const {
  if (scene_.run.fixed_time_step > 0.0) return scene_.run.fixed_time_step;
  const double dt = element_step_limit();
  if (!std::isfinite(dt))
    throw core::SimulationError(steps_, time_, "mesh", "time step",
                                "no live element is left to set the time step");
  return dt;
}

FeSolver::SmallestStep FeSolver::smallest_step() const {
  double dt = std::numeric_limits<double>::infinity();
  SmallestStep out;
  for (const ElementSet* set : sets_) {
    const ElementStore& el = set->store();
    for (const ElementBatch& b : el.batches)
      for (std::size_t e = b.begin; e < b.end; ++e)
        if (el.alive[e] && el.critical_dt[e] < dt) {
          dt = el.critical_dt[e];
          out = {set, &b, e};
        }
  }
  return out;
}

std::string FeSolver::element_name(const SmallestStep& s) const {
  return std::string(s.set->kind()) + " " + std::to_string(s.element - s.batch->begin) +
         " of body " + scene_.bodies[static_cast<std::size_t>(s.batch->body)].name;
}

std::string FeSolver::smallest_step_element() const {
  const SmallestStep s = smallest_step();
  return s.set == nullptr ? "none" : element_name(s);
}

std::string FeSolver::time_step_setter() const {
  const SmallestStep s = smallest_step();
  if (s.set == nullptr) return "";
  const ElementStore& el = s.set->store();
  char why[160];
  std::snprintf(why, sizeof why, " (critical step %.4g; volume %.3g of its initial)",
                el.critical_dt[s.element], el.volume[s.element] / el.volume0[s.element]);
  return element_name(s) + why;
}

core::Energies FeSolver::nodal_energies() const {
  core::Energies out;
  out.bodies.resize(scene_.bodies.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const double m = nodes_.mass[i];
    if (!(m > 0.0)) continue;
    const Vec3& v = nodes_.velocity[i];
    const double kinetic = 0.5 * m * core::dot(v, v);
    out.kinetic += kinetic;
    core::BodySums& b = out.bodies[static_cast<std::size_t>(nodes_.body[i])];
    b.mass += m;
    b.momentum += m * v;
    b.kinetic += kinetic;
  }
  if (!embedded_.empty()) book_embedded_bodies(embedded_, nodes_, hexes_, out.bodies);
  out.sliding = sliding_energy_;
  for (const MeshContact& c : contacts_) out.friction += c.friction_work;
  out.wall = wall_energy_;
  out.external_work = external_work_;
  return out;
}

core::Energies FeSolver::energies() const {
  if (reproducible()) return reproducible_energies();
  core::Energies out = nodal_energies();
  // The elements' part: on MPI ranks each rank's own elements and the running sums of its
  // element stages, added over the ranks in rank order below.
  for_each_live_element([&](const ElementStore& el, const ElementBatch& b, std::size_t p0) {
    double internal = 0.0;
    for (int g = 0; g < b.points_per_element; ++g)
      internal += el.point_mass[p0 + static_cast<std::size_t>(g)] *
                  el.energy[p0 + static_cast<std::size_t>(g)];
    out.internal += internal;
    out.bodies[static_cast<std::size_t>(b.body)].internal += internal;
  });
  out.plastic = plastic_work_;
  out.viscous = viscous_work_;
  out.hourglass = hourglass_work_;
  out.stabilisation = stabilisation_work_;
  out.internal += stabilisation_work_;
  for (std::size_t b = 0; b < body_stabilisation_.size(); ++b)
    out.bodies[b].internal += body_stabilisation_[b];
  out.eroded = eroded_energy_;
  if (ranks_) sum_element_energies(out);
  return out;
}

void FeSolver::set_grid_driven(const std::vector<std::uint8_t>& driven) {
  nodes_.grid_driven = driven;
  for (WallState& w : walls_)
    std::erase_if(w.nodes,
                  [&](std::int32_t k) { return driven[static_cast<std::size_t>(k)] != 0; });
}

std::vector<ErosionEvent> FeSolver::take_erosion_events() {
  std::vector<ErosionEvent> out;
  out.swap(events_);
  if (ranks_) return gather_erosion_events(std::move(out));  // collective: rank 0's are all
  sort_erosion_events(out);
  return out;
}

std::size_t FeSolver::live_hexahedra() const {
  return hexes_.live();
}
std::size_t FeSolver::live_trusses() const {
  return trusses_.live();
}

std::size_t FeSolver::bytes() const {
  auto v = [](const auto& x) { return capacity_bytes(x); };
  std::size_t b = v(nodes_.position) + v(nodes_.initial_position) + v(nodes_.velocity) +
                  v(nodes_.mass) + v(nodes_.body) + v(nodes_.imposed) + v(nodes_.imposed_velocity) +
                  v(nodes_.grid_driven);
  for (const ElementSet* set : sets_) b += set->bytes();
  return b + v(element_force_) + v(incidence_) + v(incidence_offsets_);
}

std::size_t ElementStore::bytes() const {
  std::size_t total = capacity_bytes(mass) + capacity_bytes(volume0) + capacity_bytes(volume) +
                      capacity_bytes(critical_dt) + capacity_bytes(alive);
  for_each_point_field(*this, [&total](const PointField&, const auto& a, std::size_t) {
    total += capacity_bytes(a);
  });
  return total;
}

void FeSolver::raise_thread_errors() const {
  for (std::size_t t = 0; t < thread_errors_.size(); ++t) {
    if (thread_errors_[t].empty()) continue;
    const std::string field = thread_error_field_[t];
    raise(thread_errors_[t], thread_error_field_[t],
          field == "jacobian" ? "the element inverted (set an erosion criterion on the body to "
                                "remove such elements instead of stopping)"
                              : "not a finite number");
  }
}

void FeSolver::raise(const std::string& entity, const char* field,
                     const std::string& detail) const {
  throw core::SimulationError(steps_ + 1, time_, entity, field, detail);
}

}  // namespace afemp::fem
