// The MPM step as a chain of stages (Ma 2005, §2.2.4): the plan decides which run and in
// what order; this file holds the loop over the plan, the time step and the bookkeeping.
#include "mpm/mpm_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "afemp/errors.hpp"
#include "core/detonation_paths.hpp"
#include "core/materials/user_strength_chunk.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"

namespace afemp::mpm {

MpmSolver::MpmSolver(const core::Scene& scene, Particles particles)
    : scene_(scene),
      plan_(build_step_plan(scene)),
      particles_(std::move(particles)),
      // uGIMP and the B-splines reach a node beyond the particle's cell on each side.
      grid_(scene.mpm.grid, scene.mpm.shape == core::ShapeFunction::linear ? 0 : 1) {
  for (const auto& m : scene.materials) materials_.push_back(&m);
  axisymmetric_ = scene.mpm.grid.axisymmetric;
  grid_.enable_remap_field(scene.mpm.scheme == core::UpdateScheme::MUSL ||
                           scene.mpm.scheme == core::UpdateScheme::USAVG);
  // Grid contact: one velocity field per contact body and one shared by the rest.
  const int fields = plan_.velocity_fields;
  multi_field_ = fields > 1;
  field_of_body_ = plan_.field_of_body;
  law_.assign(static_cast<std::size_t>(fields * fields), PairLaw{});
  contact_of_pair_.assign(static_cast<std::size_t>(fields * fields), 0);
  for (const core::ContactSpec& c : scene.contacts) {
    if (c.method != core::ContactMethod::grid) continue;
    const int a = field_of_body_[static_cast<std::size_t>(c.bodies[0])];
    const int b = field_of_body_[static_cast<std::size_t>(c.bodies[1])];
    const PairLaw law{true, c.friction, c.distance_factor};
    law_[static_cast<std::size_t>(a * fields + b)] = law;
    law_[static_cast<std::size_t>(b * fields + a)] = law;
    const int k = static_cast<int>(grid_contact_force_.size());
    contact_of_pair_[static_cast<std::size_t>(a * fields + b)] = 1 + k;
    contact_of_pair_[static_cast<std::size_t>(b * fields + a)] = -1 - k;
    grid_contact_force_.emplace_back();
  }
  field_in_contact_.assign(static_cast<std::size_t>(fields), 0);
  for (int a = 0; a < fields; ++a)
    for (int b = 0; b < fields; ++b)
      if (law_[static_cast<std::size_t>(a * fields + b)].contact)
        field_in_contact_[static_cast<std::size_t>(a)] = 1;
  grid_.set_fields(fields, core::has_grid_contact(scene));
  // The strain tensor is integrated only for scenes that write it: it is the largest array
  // the strain sweep streams, and nothing in the physics reads it.
  if (plan_.strain) particles_.keep(&Particles::strain, SymTensor{});
  // uGIMP: each particle's domain is the cube of its initial volume, at most one cell
  // (a domain wider than a cell would reach a fourth node per axis). The B-splines do not need
  // it for their weights; the affine transfer's kinetic energy reads it (energies()).
  if (plan_.shape != core::ShapeFunction::linear) {
    particles_.keep(&Particles::half_width, 0.0);
    for (std::size_t i = 0; i < particles_.size(); ++i)
      particles_.half_width[i] = gimp_half_width(particles_.volume[i]);
  }
  if (!fused_kinematics()) velocity_gradient_.resize(particles_.size());  // the pass's output
  // CPDI: each particle's domain starts as the cube of its volume, unless the caller gave the
  // particles domains of their own.
  if (plan_.shape == core::ShapeFunction::cpdi1) {
    const bool given = particles_.domain.size() == particles_.size();
    particles_.keep(&Particles::domain, core::Mat3{});
    if (!given)
      for (std::size_t i = 0; i < particles_.size(); ++i) start_domain(i);
  }
  if (plan_.shape == core::ShapeFunction::cpdi2) {
    const bool given = particles_.corners.size() == particles_.size();
    particles_.keep(&Particles::corners, std::array<Vec3, 8>{});
    if (!given)
      for (std::size_t i = 0; i < particles_.size(); ++i) start_domain(i);
  }
  // Total-Lagrangian: the particles' reference is where they start, F = I, unless the caller
  // gave them a reference and a deformation of their own.
  // A hyperelastic material's particles carry F as well, from I.
  if (plan_.total_lagrangian) {
    const bool given = particles_.reference_position.size() == particles_.size();
    particles_.keep(&Particles::reference_position, Vec3{});
    if (!given) particles_.reference_position = particles_.position;
  }
  if (plan_.deformation_gradient) {
    const bool given = particles_.deformation_gradient.size() == particles_.size();
    particles_.keep(&Particles::deformation_gradient, core::Mat3{});
    if (!given)
      for (core::Mat3& f : particles_.deformation_gradient) f = identity_matrix();
  }
  // Splitting: each particle's lengths start as the edge of the cube of its volume.
  if (plan_.splitting) {
    particles_.keep(&Particles::length, Vec3{});
    particles_.keep(&Particles::length0, Vec3{});
    for (std::size_t i = 0; i < particles_.size(); ++i) start_lengths(i);
  }
  // APIC: particles start with C_p = 0 (each body starts at a uniform velocity) unless the
  // caller gave them an affine velocity of their own.
  if (plan_.transfer == core::Transfer::apic) particles_.keep(&Particles::affine, core::Mat3{});
  // User strength models' history variables: the scene's count per point, initial values
  // by material (the generators leave them out).
  const std::size_t hc = core::history_count(scene);
  if (particles_.history_count != hc) {
    particles_.history_count = hc;
    particles_.history.assign(particles_.size() * hc, 0.0);
    for (std::size_t i = 0; i < particles_.size(); ++i)
      core::initial_history(scene.materials[static_cast<std::size_t>(particles_.material[i])],
                            particles_.history.data() + i * hc, hc);
  }
  for (const core::BodySpec& b : scene.bodies) {
    bulk_viscosity_.push_back(core::bulk_viscosity_of(scene, b));
    // Only particle bodies and hexahedra (whose elements may become particles) have it.
    if (b.discretisation != core::Discretisation::trusses &&
        (bulk_viscosity_.back().linear > 0.0 || bulk_viscosity_.back().quadratic > 0.0))
      viscous_ = true;
  }
  stage_counts_.assign(plan_.stages.size(), 0);
  stage_seconds_.assign(plan_.stages.size(), 0.0);
  for (std::size_t f = 0; f < 6; ++f)
    outflow_[f] = scene.mpm.grid.faces[f] == core::FaceCondition::outflow;
  splits_.assign(scene.bodies.size(), 0);
  if (scene.mpm.splitting)
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      splits_[b] = scene.mpm.splitting->bodies.empty() ||
                   std::find(scene.mpm.splitting->bodies.begin(), scene.mpm.splitting->bodies.end(),
                             static_cast<int>(b)) != scene.mpm.splitting->bodies.end();
  setup_explosives();
  if (scene.mpm.grid.has_face(core::FaceCondition::outflow)) {
    particles_.keep(&Particles::plastic_heat, 0.0);
    particles_.keep(&Particles::viscous_heat, 0.0);
  }
  setup_absorbing_faces();
  setup_particle_loads();
  if (const std::optional<core::FarField>& far = scene.mpm.grid.far_field)
    (far->absolute_stress ? face_pressure_ : ambient_pressure_) = far->pressure;
  // Walls that name particle bodies act on them here (particle_wall_contact.cpp).
  wall_bodies_.assign(scene.walls.size(), {});
  wall_force_.assign(scene.walls.size(), Vec3{});
  for (std::size_t w = 0; w < scene.walls.size(); ++w)
    for (int b : scene.walls[w].bodies) {
      if (scene.bodies[static_cast<std::size_t>(b)].discretisation !=
          core::Discretisation::particles)
        continue;
      if (wall_bodies_[w].empty()) wall_bodies_[w].assign(scene.bodies.size(), 0);
      wall_bodies_[w][static_cast<std::size_t>(b)] = 1;
    }
  reorder_particles();
  signal_speed_ = max_signal_parts();
}

namespace {
std::pair<double, double> signal_maxima(const Particles& p,
                                        const std::vector<const core::Material*>& materials);
}  // namespace

void MpmSolver::add_particles(const Particles& more) {
  if (more.size() == 0) return;
  Particles& p = particles_;
  // On ranks every rank passes the same particles: the ids follow the largest over the ranks
  // (one process's), and each rank keeps those in its own blocks.
  std::int32_t next_id = next_particle_id();
  if (ranks_) next_id = static_cast<std::int32_t>(ranks_->max_over_ranks(next_id));
  const std::size_t n0 = p.size();
  p.reserve(n0 + more.size());
  for (std::size_t k = 0; k < more.size(); ++k) {
    const std::int32_t id = next_id++;
    if (!field_self_updated_.empty())
      field_self_updated_[static_cast<std::size_t>(
          field_of_body_[static_cast<std::size_t>(more.body[k])])] = 0;
    if (ranks_) {  // a point outside the grid goes to rank 0, whose binning then stops the run
      const auto c = grid_.cell_of(more.position[k]);
      if ((grid_.inside(c) ? partition_.rank_of(grid_.block_of_cell(c)) : 0) != ranks_->rank())
        continue;
    }
    const std::size_t i = p.size();
    p.push_back(more.position[k], more.velocity[k], more.mass[k], more.volume[k],
                more.temperature[k], more.body[k], more.material[k]);
    p.id[i] = id;
    // What the source points hold (AddRule::carry); the fields they lack keep their rest value.
    for_each_particle_field([&](const ParticleField& field, auto member) {
      auto& to = p.*member;
      const auto& from = more.*member;
      if (field.add == AddRule::carry && p.has(field) && more.has(field)) to[i] = from[k];
    });
    double* history = p.history.data() + i * p.history_count;
    if (more.history_count == p.history_count)
      std::copy_n(more.history.data() + k * p.history_count, p.history_count, history);
    else
      core::initial_history(*materials_[static_cast<std::size_t>(p.material[i])], history,
                            p.history_count);
    if (!p.half_width.empty()) p.half_width[i] = gimp_half_width(p.volume[i]);
    if (!p.length.empty()) start_lengths(i);
    start_domain(i);
    if (!p.deformation_gradient.empty()) p.deformation_gradient[i] = identity_matrix();
  }
  if (!fused_kinematics()) velocity_gradient_.resize(p.size());
  reorder_particles();
  if (!ranks_) {
    signal_speed_ = std::max(signal_speed_, max_signal_speed());
    return;
  }
  whole_count_ += more.size();
  // The stable step on ranks comes from the largest wave speed and speed over the ranks: raised
  // as one process raises its sum, the same on every rank.
  const auto [wave, flow] = signal_maxima(particles_, materials_);
  const double before = ranks_->max_over_ranks(signal_wave_) + ranks_->max_over_ranks(signal_flow_);
  const double w = ranks_->max_over_ranks(wave), f = ranks_->max_over_ranks(flow);
  if (w + f > before) {
    signal_wave_ = w;
    signal_flow_ = f;
    signal_speed_ = w + f;
  }
}

// Detonation products start with the EOS's detonation energy E0 (per unit reference volume):
// e = E0 / rho0. A high explosive's particles light at their distance (straight, or around
// inert bodies for a shadowed detonation) from the nearest detonation over D
// (core/detonation_paths.hpp) and start unburnt.
void MpmSolver::setup_explosives() {
  Particles& p = particles_;
  bool explosive = false;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const core::Material& m = *materials_[static_cast<std::size_t>(p.material[i])];
    if (p.energy[i] == 0.0) p.energy[i] = m.initial_energy();
    explosive = explosive || m.is_explosive();
  }
  if (!explosive) return;
  p.keep(&Particles::light_time, 0.0);
  p.keep(&Particles::burn, 1.0);
  std::vector<std::size_t> which;
  std::vector<Vec3> x;
  std::vector<double> D;
  std::vector<std::int32_t> body;
  double spacing = 0.0;  // the particles' largest edge: the voxels of a shadowed detonation
  for (std::size_t i = 0; i < p.size(); ++i) {
    const core::Material& m = *materials_[static_cast<std::size_t>(p.material[i])];
    if (!m.is_explosive()) continue;
    which.push_back(i);
    x.push_back(p.position[i]);
    D.push_back(m.burn->detonation_velocity);
    body.push_back(p.body[i]);
    spacing = std::max(spacing, particle_edge(i));
    p.burn[i] = 0.0;
  }
  const std::vector<double> t = core::explosive_lighting_times(x, D, body, spacing, scene_);
  for (std::size_t k = 0; k < which.size(); ++k) p.light_time[which[k]] = t[k];
}

std::int32_t MpmSolver::next_particle_id() const {
  std::int32_t next = 0;
  for (std::int32_t id : particles_.id) next = std::max(next, id + 1);
  return next;
}

double MpmSolver::stable_time_step() const {
  if (scene_.run.fixed_time_step > 0.0) return scene_.run.fixed_time_step;
  const double speed =
      ranks_ ? ranks_->max_over_ranks(signal_wave_) + ranks_->max_over_ranks(signal_flow_)
             : signal_speed_;
  return scene_.run.time_step_factor * grid_.cell() / speed;
}

void MpmSolver::step(double dt) {
  using clock = std::chrono::steady_clock;
  step_dt_ = dt;
  if (steps_ > 0 && steps_ % reorder_interval == 0) {
    const auto t0 = clock::now();
    reorder_particles();
    reorder_seconds_ += std::chrono::duration<double>(clock::now() - t0).count();
  }
  for (std::size_t i = 0; i < plan_.stages.size(); ++i) {
    const auto t0 = clock::now();
    switch (plan_.stages[i].kind) {
      case StageKind::outflow:
        remove_outflow();
        break;
      case StageKind::split_particles:
        split_particles();
        break;
      case StageKind::bin_particles:
        bin_particles();
        break;
      case StageKind::p2g_mass_momentum:
        particle_to_grid(true, false);
        break;
      case StageKind::p2g_force:
        particle_to_grid(false, true);
        break;
      case StageKind::p2g_mass_momentum_force:
        particle_to_grid(true, true);
        break;
      case StageKind::grid_velocity:
        grid_velocity();
        break;
      case StageKind::grid_momentum_update:
        grid_momentum_update(dt);
        break;
      case StageKind::g2p_velocity_position:
        grid_to_particle(dt, true);
        break;
      case StageKind::g2p_velocity:
        grid_to_particle(dt, false);
        break;
      case StageKind::p2g_remap:
        remap_to_grid();
        break;
      case StageKind::strain_stress_start:
        strain_stress_update(dt, StrainPart::start_half);
        break;
      case StageKind::strain_stress_update:
      case StageKind::g2p_velocity_strain_stress:
        strain_stress_update(dt, plan_.scheme == core::UpdateScheme::USAVG ? StrainPart::end_half
                                                                           : StrainPart::whole);
        break;
      case StageKind::contact_surfaces:
        contact_surfaces();
        break;
      case StageKind::contact_start:
        grid_contact(ContactPass::start);
        break;
      case StageKind::grid_contact:
        grid_contact(ContactPass::update);
        break;
      case StageKind::contact_remap:
        grid_contact(ContactPass::remap);
        break;
      case StageKind::particle_walls:
        particle_wall_contact(dt);
        break;
    }
    ++stage_counts_[i];
    stage_seconds_[i] += std::chrono::duration<double>(clock::now() - t0).count();
  }
  time_ += dt;
  ++steps_;
  if (ranks_) {
    const auto t0 = clock::now();
    migrate_particles();
    migration_seconds_ += std::chrono::duration<double>(clock::now() - t0).count();
    if (balance_.cost != core::RankBalance::Cost::off && steps_ % balance_.every == 0)
      balance_ranks();
  }
}

void MpmSolver::scale_velocities(double factor) {
  Particles& p = particles_;
  const bool affine = plan_.transfer == core::Transfer::apic;
#pragma omp parallel for schedule(static) if (core::worth_threads(p.size()))
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] *= factor;
    if (affine)
      for (auto& row : p.affine[i].m)
        for (double& c : row) c *= factor;
  }
}

void MpmSolver::set_body_velocity(int body, const Vec3& v) {
  Particles& p = particles_;
  const bool affine = plan_.transfer == core::Transfer::apic;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) continue;
    p.velocity[i] = v;
    if (affine) p.affine[i] = {};
  }
}

namespace {

// The largest wave speed c_p and the largest speed |v_p| over the particles.
std::pair<double, double> signal_maxima(const Particles& p,
                                        const std::vector<const core::Material*>& materials) {
  double wave = 0.0, speed2 = 0.0;
#pragma omp parallel for schedule(static) \
    reduction(max                         \
              : wave, speed2) if (core::worth_threads(p.size()))
  for (std::size_t i = 0; i < p.size(); ++i) {
    const core::Material& m = *materials[static_cast<std::size_t>(p.material[i])];
    core::PointState st{p.stress[i], p.plastic_strain[i], p.temperature[i], p.energy[i],
                        p.mass[i] / p.volume[i]};
    wave = std::max(wave, core::wave_speed(m, st));
    speed2 = std::max(speed2, core::dot(p.velocity[i], p.velocity[i]));
  }
  return {wave, std::sqrt(speed2)};
}

}  // namespace

double MpmSolver::max_signal_speed() const {
  const auto [wave, speed] = signal_maxima(particles_, materials_);
  return wave + speed;
}

double MpmSolver::max_signal_parts() {
  std::tie(signal_wave_, signal_flow_) = signal_maxima(particles_, materials_);
  return signal_wave_ + signal_flow_;
}

std::string MpmSolver::time_step_setter() const {
  const Particles& p = particles_;
  std::size_t fastest = p.size();
  double fastest_wave = 0.0, fastest_speed = -1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const core::Material& m = *materials_[static_cast<std::size_t>(p.material[i])];
    const core::PointState st{p.stress[i], p.plastic_strain[i], p.temperature[i], p.energy[i],
                              p.mass[i] / p.volume[i]};
    const double wave = core::wave_speed(m, st);
    const double speed = core::norm(p.velocity[i]);
    if (wave + speed > fastest_wave + fastest_speed) {
      fastest = i;
      fastest_wave = wave;
      fastest_speed = speed;
    }
  }
  char buf[256] = "";
  if (fastest != p.size()) {
    const Vec3& x = p.position[fastest];
    std::snprintf(buf, sizeof buf,
                  "particle %d of body '%s' at (%.4g, %.4g, %.4g) (wave speed %.4g + speed %.4g "
                  "over the cell %.4g)",
                  p.id[fastest],
                  scene_.bodies[static_cast<std::size_t>(p.body[fastest])].name.c_str(), x.x, x.y,
                  x.z, fastest_wave, fastest_speed, grid_.cell());
  }
  if (ranks_ == nullptr) return buf;
  // On ranks (collective): the fastest over every rank's, described by the lowest rank that
  // holds it, its text sent to every rank.
  const double mine = fastest == p.size() ? -1.0 : fastest_wave + fastest_speed;
  const double best = ranks_->max_over_ranks(mine);
  const int me = ranks_->rank();
  const int teller = static_cast<int>(-ranks_->max_over_ranks(mine == best ? -me : -1e9));
  const std::string mine_text = me == teller ? std::string(buf) : std::string();
  const std::vector<std::byte> told =
      ranks_->gather(core::bytes_of(mine_text))[static_cast<std::size_t>(teller)];
  const std::string text(reinterpret_cast<const char*>(told.data()), told.size());
  return text;
}

double MpmSolver::particle_kinetic_energy(std::size_t i, bool affine) const {
  const Particles& p = particles_;
  const Vec3& v = p.velocity[i];
  const double m = p.mass[i];
  double kinetic = 0.5 * m * core::dot(v, v);
  // APIC: the affine part of the velocity carries kinetic energy too. Over the particle's cube
  // of half-width l the field v_p + C_p (x - x_p) holds 1/2 m (|v_p|^2 + l^2 / 3 |C_p|^2) (the
  // cube's second moment is l^2 / 3 per axis).
  if (affine) {
    const double l = p.half_width[i] * grid_.cell();
    const core::Mat3& c = p.affine[i];
    double sum = 0.0;
    for (int r = 0; r < 3; ++r)
      for (int a = 0; a < 3; ++a) sum += c.m[r][a] * c.m[r][a];
    kinetic += 0.5 * m * (l * l / 3.0) * sum;
  }
  return kinetic;
}

Energies MpmSolver::energies() const {
  if (reproducible()) return reproducible_energies();
  const Particles& p = particles_;
  const std::size_t nb = scene_.bodies.size();
  const std::size_t width = 2 + 6 * nb;  // kinetic, internal, then per body: mass, momentum,
                                         // kinetic, internal
  const int nt = core::thread_count();
  const bool affine = plan_.transfer == core::Transfer::apic;
  std::vector<double> partial(width * static_cast<std::size_t>(nt), 0.0);
#pragma omp parallel num_threads(nt) if (core::worth_threads(p.size()))
  {
    const int t = core::thread_index();
    const auto [b, e] = core::static_range(p.size(), t, core::team_size());
    double* acc = partial.data() + width * static_cast<std::size_t>(t);
    for (std::size_t i = b; i < e; ++i) {
      const Vec3& v = p.velocity[i];
      const double m = p.mass[i];
      const double kinetic = particle_kinetic_energy(i, affine);
      acc[0] += kinetic;
      acc[1] += m * p.energy[i];
      double* body = acc + 2 + 6 * static_cast<std::size_t>(p.body[i]);
      body[0] += m;
      body[1] += m * v.x;
      body[2] += m * v.y;
      body[3] += m * v.z;
      body[4] += kinetic;
      body[5] += m * p.energy[i];
    }
  }
  Energies out;
  out.bodies.resize(nb);
  for (int t = 0; t < nt; ++t) {
    const double* acc = partial.data() + width * static_cast<std::size_t>(t);
    out.kinetic += acc[0];
    out.internal += acc[1];
    for (std::size_t k = 0; k < nb; ++k) {
      const double* body = acc + 2 + 6 * k;
      out.bodies[k].mass += body[0];
      out.bodies[k].momentum += Vec3{body[1], body[2], body[3]};
      out.bodies[k].kinetic += body[4];
      out.bodies[k].internal += body[5];
    }
  }
  out.plastic = plastic_work_;
  out.viscous = viscous_work_;
  out.external_work = external_work_;
  out.outflow = outflow_energy_;
  out.outflow_mass = outflow_mass_;
  out.outflow_momentum = outflow_momentum_;
  // Axisymmetric: a ring's momentum across the axis sums to zero (its particles' x velocity is
  // radial), so the bodies' and the outflow's x and y momenta are zero, not the sums of v_r.
  if (axisymmetric_) {
    for (BodySums& b : out.bodies) b.momentum.x = b.momentum.y = 0.0;
    out.outflow_momentum.x = out.outflow_momentum.y = 0.0;
  }
  // On ranks: every rank's sums and accumulators added in rank order (a particle wall's sliding
  // and friction are whole on every rank: particle_wall_contact.cpp).
  if (ranks_) {
    std::vector<double> sums{out.kinetic,
                             out.internal,
                             out.plastic,
                             out.viscous,
                             out.external_work,
                             contact_energy_,
                             out.outflow,
                             out.outflow_mass,
                             out.outflow_momentum.x,
                             out.outflow_momentum.y,
                             out.outflow_momentum.z};
    constexpr std::size_t whole = 11;
    for (const BodySums& b : out.bodies)
      sums.insert(sums.end(),
                  {b.mass, b.momentum.x, b.momentum.y, b.momentum.z, b.kinetic, b.internal});
    ranks_->sum_in_rank_order(sums);
    out.kinetic = sums[0];
    out.internal = sums[1];
    out.plastic = sums[2];
    out.viscous = sums[3];
    out.external_work = sums[4];
    out.contact = sums[5];
    out.outflow = sums[6];
    out.outflow_mass = sums[7];
    out.outflow_momentum = Vec3{sums[8], sums[9], sums[10]};
    for (std::size_t k = 0; k < nb; ++k) {
      const double* b = sums.data() + whole + 6 * k;
      out.bodies[k].mass = b[0];
      out.bodies[k].momentum = Vec3{b[1], b[2], b[3]};
      out.bodies[k].kinetic = b[4];
      out.bodies[k].internal = b[5];
    }
  }
  if (!ranks_) out.contact = contact_energy_;
  out.sliding = wall_sliding_;
  out.friction = wall_friction_;
  return out;
}

void MpmSolver::reorder_particles() {
  // Material batches for the constitutive update; cell order inside a batch keeps the
  // grid accesses of neighbouring particles close in memory.
  Particles& p = particles_;
  const std::size_t n = p.size();
  std::vector<std::int64_t> key(n);
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  const std::vector<Vec3>& x = weight_positions();
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = grid_.cell_of(x[i]);
    key[i] = grid_.inside(c) ? grid_.linear_cell(c) : 0;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], x[i][a]);
      hi[a] = std::max(hi[a], x[i][a]);
    }
  }
  std::vector<std::int32_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::stable_sort(perm.begin(), perm.end(), [&](std::int32_t a, std::int32_t b) {
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    if (p.material[ua] != p.material[ub]) return p.material[ua] < p.material[ub];
    return key[ua] < key[ub];
  });
  p.permute(perm);
  rebuild_batches();
  // Colour layers run along the axis the material spans most, for the most parallel work.
  sweep_axis_ = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[a] - lo[a] > hi[sweep_axis_] - lo[sweep_axis_]) sweep_axis_ = a;
}

void MpmSolver::rebuild_batches() {
  const Particles& p = particles_;
  const std::size_t n = p.size();
  batches_.clear();
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && p.material[j] == p.material[i]) ++j;
    batches_.push_back({p.material[i], i, j});
    i = j;
  }
}

void MpmSolver::raise_if_bad(const char* field) const {
  std::int64_t bad = -1;
  for (std::int64_t b : thread_bad_)
    if (b >= 0 && (bad < 0 || b < bad)) bad = b;
  if (bad < 0) return;
  const auto i = static_cast<std::size_t>(bad);
  const Particles& p = particles_;
  std::ostringstream who;
  who << "particle " << p.id[i] << " of body '"
      << scene_.bodies[static_cast<std::size_t>(p.body[i])].name << "' at (" << p.position[i].x
      << ", " << p.position[i].y << ", " << p.position[i].z << ")";
  std::ostringstream what;
  std::string f = field;
  if (f == "position" && std::isfinite(p.position[i].x) && std::isfinite(p.position[i].y) &&
      std::isfinite(p.position[i].z)) {
    what << "left the grid domain (the run stops; enlarge [grid] min/max)";
  } else if (f == "stress" && !(p.volume[i] > 0.0)) {
    // Total-Lagrangian: det F <= 0 is the cause to name, when it is one.
    if (plan_.total_lagrangian) check_deformation_gradients();
    // The strain pass flags the point; a non-positive volume is the cause to name.
    f = "volume";
    what << "became " << p.volume[i]
         << ": the point was compressed through zero volume in one step; try a smaller "
            "time_step_factor";
  } else
    what << "became NaN or Inf (velocity (" << p.velocity[i].x << ", " << p.velocity[i].y << ", "
         << p.velocity[i].z << "), pressure " << core::pressure(p.stress[i])
         << "); try a smaller time_step_factor";
  throw core::SimulationError(steps_, time_, who.str(), f, what.str());
}

std::size_t MpmSolver::active_cells() const {
  std::vector<std::int64_t> cells = cell_;
  std::sort(cells.begin(), cells.end());
  return static_cast<std::size_t>(std::unique(cells.begin(), cells.end()) - cells.begin());
}

std::size_t MpmSolver::bytes() const {
  return particles_.bytes() + grid_.bytes() + cell_.capacity() * sizeof(std::int64_t) +
         velocity_gradient_.capacity() * sizeof(core::Mat3) +
         (mixed_pressure_.capacity() + pressure_nodes_.capacity()) * sizeof(double) +
         contact_normal_.capacity() * sizeof(Vec3) +
         (layer_.capacity() + layer_order_.capacity()) * sizeof(std::int32_t) +
         layer_offsets_.capacity() * sizeof(std::int64_t);
}

}  // namespace afemp::mpm
