// Strain and stress update of the particles (Ma 2005, eqs 2-38..2-41): velocity gradient
// from the nodal velocity the scheme names, Jaumann rotation of the stress, volume update
// V <- V (1 + tr d eps) (eq 2-40), then the material's constitutive update, batch by batch:
// one std::visit per material, one direct (inlined) call per point, and the bulk viscosity
// (core/bulk_viscosity.hpp). USL also updates the particle velocity here, since it uses the
// same weights and the same grid velocity.
#include <cmath>

#include "core/bulk_viscosity.hpp"
#include "core/materials/user_strength_chunk.hpp"
#include "core/parallel.hpp"
#include "core/programmed_burn.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

// The nodal velocity the scheme's strain reads, and the part of the step it covers. USAVG
// (Wallstedt & Guilkey 2008, "An evaluation of explicit time integration schemes for use with
// the generalized interpolation material point method", J. Comput. Phys. 227): half the strain
// increment from the start velocity before the forces, so that they come from the mid-step
// stress, and half from the remapped end velocity after, as MUSL.
void MpmSolver::strain_stress_update(double dt, StrainPart part) {
  const core::BackgroundGrid& g = grid_;
  StrainSweep sweep;
  sweep.strain_dt = part == StrainPart::whole ? dt : 0.5 * dt;
  sweep.time_after = part == StrainPart::start_half ? time_ + 0.5 * dt : time_ + dt;
  if (part == StrainPart::start_half || plan_.scheme == core::UpdateScheme::USF) {
    sweep.strain_velocity = g.velocity.data();
  } else if (plan_.scheme == core::UpdateScheme::USL) {
    sweep = {g.velocity_new.data(), true, true, dt, time_ + dt};
  } else {
    sweep.strain_velocity = g.velocity_remap.data();
    sweep.move = true;
  }
  const int nt = core::thread_count();
  thread_sums_.assign(static_cast<std::size_t>(nt) * core::cache_line_doubles, 0.0);
  // The mode's per-thread exact sums: plastic work, viscous heat, the ambient pressure's work
  // (added below into exact_plastic, exact_viscous, exact_external, which follow each other).
  static_assert(exact_viscous == exact_plastic + 1 && exact_external == exact_plastic + 2);
  if (reproducible()) exact_thread_sums(3);
  thread_bad_.assign(static_cast<std::size_t>(nt), -1);
  // The linear hat computes the kinematics inside the constitutive loop (one pass over the
  // particles); the wider stencils (uGIMP, B-splines) run them in a pass of their own
  // (kinematics_kernel)
  // and leaves L in velocity_gradient_, so the material loops are not duplicated per shape.
  const bool fused = fused_kinematics();
  if (!fused) {
    velocity_gradient_.resize(particles_.size());
    with_stencil(
        [&]<class Stencil, bool Affine>() { kinematics_kernel<Stencil, Affine>(dt, sweep); });
  }
  // The mixed u-p pressure from the F just updated, before the materials read it (the
  // staggered step of Zhang et al. 2022: displacement, then pressure, then stress).
  if (plan_.mixed_pressure) project_mixed_pressure();
  for (const MaterialBatch& batch : batches_) {
    const core::Material& m = *materials_[static_cast<std::size_t>(batch.material)];
    core::visit_models(m, [&](const auto& strength, const auto& eos) {
      using S = std::decay_t<decltype(strength)>;
      using E = std::decay_t<decltype(eos)>;
      // One instantiation per combination, so that a material without a failure model
      // runs exactly the update it had (material.hpp, finish_increment).
      auto run = [&]<bool Thermal, bool Fused>() {
        if (m.fails())
          strain_stress_batch<S, E, Thermal, Fused, true>(batch, strength, eos, dt, sweep, nt);
        else
          strain_stress_batch<S, E, Thermal, Fused, false>(batch, strength, eos, dt, sweep, nt);
      };
      if (fused) {
        if (m.has_thermal_term())
          run.template operator()<true, true>();
        else
          run.template operator()<false, true>();
      } else {
        if (m.has_thermal_term())
          run.template operator()<true, false>();
        else
          run.template operator()<false, false>();
      }
    });
  }
  double work = 0.0, wave = 0.0, speed2 = 0.0, heat = 0.0, swept = 0.0;
  for (int t = 0; t < nt; ++t) {
    const double* sums =
        thread_sums_.data() + static_cast<std::size_t>(t) * core::cache_line_doubles;
    work += sums[0];
    heat += sums[3];
    swept += sums[4];
    wave = std::max(wave, sums[1]);
    speed2 = std::max(speed2, sums[2]);
  }
  plastic_work_ += work;
  viscous_work_ += heat;
  if (reproducible()) add_exact_thread_sums(3, exact_.data() + exact_plastic);
  // A far field's ambient pressure does -p_inf dV on the particles (absorbing_faces.hpp).
  if (ambient_pressure_ != 0.0) external_work_ -= ambient_pressure_ * swept;
  signal_wave_ = wave;
  signal_flow_ = std::sqrt(speed2);
  signal_speed_ = signal_wave_ + signal_flow_;
  raise_if_bad("stress");
}

template <class Stencil, bool Affine>
void MpmSolver::kinematics_kernel(double dt, const StrainSweep& sweep) {
  const core::BackgroundGrid& g = grid_;
  Particles& p = particles_;
  const Vec3* v_old = g.velocity.data();
  const Vec3* v_new = g.velocity_new.data();
  const double flip = scene_.mpm.flip;
  const bool track_f = plan_.deformation_gradient;
  for_each_particle_stencil<Stencil>(g, p, [&](std::size_t i, const Stencil& st, const auto& slot) {
    core::Mat3 l;                            // L = sum v (x) grad S
    VelocityUpdate<Stencil, Affine> update;  // USL: the G2P of grid_to_particle.cpp
    const std::size_t field = field_offset(i);
    double v_r = 0.0;  // axisymmetric: the particle's radial velocity
    for (int k = 0; k < Stencil::nodes; ++k) {
      const auto s = static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]) + field;
      core::add_outer(l, sweep.strain_velocity[s], st.grad(k));
      if (axisymmetric_) v_r += st.w(k) * sweep.strain_velocity[s].x;
      if (sweep.move) update.add(st, k, v_new[s], v_old[s]);
    }
    // The hoop rate v_r / r (mpm/axisymmetric.hpp), as L_yy.
    if (axisymmetric_) l.m[1][1] += v_r / p.position[i].x;
    velocity_gradient_[i] = l;
    // F <- (I + dt L) F, the strain increment's own deformation (total-Lagrangian, or a
    // hyperelastic material).
    if (track_f) add_velocity_gradient_step(p.deformation_gradient[i], l, sweep.strain_dt);
    if (sweep.flip_update) update.store(p, i, st, flip);
    if (sweep.move) {
      p.position[i] += dt * update.v_grid;
      move_domain(p, i, st, slot, field, v_new, dt);
    }
  });
}

// One thread's share of a material batch, point by point in passes: the kinematics (the
// velocity gradient L and, fused with the linear hat, USL's velocity update), the strain
// increment and start state, the material's update (the caller's), and the commit of the new
// state with the step bound. The thread constructs its own copy, so that stores to the particle
// arrays cannot alias the material constants and they stay in registers through the loop.
// Each pass takes its values as separate arguments rather than one struct, so that the
// compiler keeps them in registers and the arithmetic stays that of one fused loop.
template <class Strength, class Eos, bool Thermal, bool Fused, bool Fails>
struct MpmSolver::StressPass {
  // What the model declares it reads (include/afemp/strength_models.hpp), and the temperature
  // whenever plastic work heats the point.
  static constexpr bool reads_plastic_strain = Strength::reads_plastic_strain;
  static constexpr bool reads_temperature = Thermal || Strength::reads_temperature;
  static constexpr bool reads_damage = Strength::reads_damage;

  const MpmSolver& solver;
  Particles& p;
  const core::BackgroundGrid& g;
  const StrainSweep& sweep;
  const core::Material mat;
  const Strength strength;
  const Eos eos;
  const double dt;       // of the strain increment
  const double step_dt;  // positions move over the whole step
  const Vec3* v_old;
  const Vec3* v_new;
  const double flip;
  const bool jaumann;
  const bool track_strain;
  const bool principal_strain;
  const bool track_length;  // splitting: the particle's extent along each axis
  // Outflow: each particle's plastic work and viscous heat (Particles::plastic_heat).
  const bool track_heat;
  // Programmed burn: the fraction at the end of the update (mid-step for the first half of
  // USAVG), burning over 1.5 cells.
  const bool explosive;
  const double burn_time;
  const double h;
  const bool viscous;
  const bool axisymmetric;  // the hoop rate (mpm/axisymmetric.hpp)
  const core::BulkViscositySettings* viscosity;
  const double* mixed;  // the projected pressures (mixed u-p), or null
  double work = 0.0, wave = 0.0, speed2 = 0.0, heat = 0.0, swept = 0.0;
  // The reproducible mode: the thread's exact sums of the plastic work, the viscous heat and
  // the far field's ambient pressure work -p_inf dV (reproducible_sums.cpp); null otherwise.
  core::ExactSum* exact = nullptr;
  const double ambient;
  std::int64_t bad = -1;

  StressPass(MpmSolver& s, const core::Material& m, const Strength& strength_in, const Eos& eos_in,
             double step_dt_in, const StrainSweep& sweep_in)
      : solver(s),
        p(s.particles_),
        g(s.grid_),
        sweep(sweep_in),
        mat(m),
        strength(strength_in),
        eos(eos_in),
        dt(sweep_in.strain_dt),
        step_dt(step_dt_in),
        v_old(s.grid_.velocity.data()),
        v_new(s.grid_.velocity_new.data()),
        flip(s.scene_.mpm.flip),
        jaumann(s.plan_.jaumann),
        track_strain(s.plan_.strain),
        principal_strain(m.needs_strain()),
        track_length(s.plan_.splitting),
        track_heat(!s.particles_.plastic_heat.empty()),
        explosive(m.is_explosive()),
        burn_time(sweep_in.time_after),
        h(s.grid_.cell()),
        viscous(s.viscous_),
        axisymmetric(s.axisymmetric_),
        viscosity(s.bulk_viscosity_.data()),
        mixed(s.plan_.mixed_pressure ? s.mixed_pressure_.data() : nullptr),
        ambient(s.ambient_pressure_) {}

  // L_ij = sum_I v_Ii dN_I/dx_j of particle i, its mean grid velocity v_bar and its velocity
  // v_p (updated here with USL's FLIP blend when fused, by kinematics_kernel otherwise).
  AFEMP_INLINE void kinematics(std::size_t i, const Vec3& x, core::Mat3& l, Vec3& v_bar,
                               Vec3& v_p) {
    v_bar = Vec3{};
    v_p = p.velocity[i];
    if constexpr (Fused) {
      const auto cell_index = g.cell_of(x);
      const core::CellWeights w = g.weights(x, cell_index);
      std::array<std::int32_t, 8> slot;
      g.node_slots(cell_index, slot);
      const std::size_t field = solver.field_offset(i);
      Vec3 dv;
      for (int k = 0; k < 8; ++k) {
        const auto s = static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]) + field;
        const Vec3 v = sweep.strain_velocity[s];
        const Vec3& d = w.grad[static_cast<std::size_t>(k)];
        for (int r = 0; r < 3; ++r) {
          l.m[r][0] += v[r] * d.x;
          l.m[r][1] += v[r] * d.y;
          l.m[r][2] += v[r] * d.z;
        }
        const double wk = w.w[static_cast<std::size_t>(k)];
        if (sweep.move) v_bar += wk * v_new[s];
        if (sweep.flip_update) dv += wk * (v_new[s] - v_old[s]);
      }
      // The hoop rate v_r / r (mpm/axisymmetric.hpp), as L_yy, v_r the particle's radial
      // velocity (a loop of its own, so that the 3-D one stays as it was).
      if (axisymmetric) {
        double v_r = 0.0;
        for (int k = 0; k < 8; ++k)
          v_r += w.w[static_cast<std::size_t>(k)] *
                 sweep
                     .strain_velocity[static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]) +
                                      field]
                     .x;
        l.m[1][1] += v_r / x.x;
      }
      if (sweep.flip_update) {
        v_p = flip * (v_p + dv) + (1.0 - flip) * v_bar;
        p.velocity[i] = v_p;
      }
    } else {
      l = solver.velocity_gradient_[i];  // kinematics_kernel moved x and updated v_p already
    }
  }

  // The strain increment d_eps of particle i from L, its Jaumann-rotated stress, its new
  // volume (stored) and the rest of its start state st.
  AFEMP_INLINE void start(std::size_t i, const core::Mat3& l, core::SymTensor& d_eps,
                          core::PointState& st) {
    d_eps = dt * core::sym_part(l);
    st.stress = p.stress[i];
    if (jaumann) {
      st.stress += core::jaumann_increment(st.stress, 0.5 * dt * (l.m[1][2] - l.m[2][1]),
                                           0.5 * dt * (l.m[0][2] - l.m[2][0]),
                                           0.5 * dt * (l.m[0][1] - l.m[1][0]));
    }
    const double volume = p.volume[i] * (1.0 + d_eps.trace());
    swept += volume - p.volume[i];
    if (exact && ambient != 0.0) exact[2].add(-ambient * (volume - p.volume[i]));
    p.volume[i] = volume;
    // History an elastic batch never reads stays in memory: less to stream per point.
    if constexpr (reads_plastic_strain) st.plastic_strain = p.plastic_strain[i];
    if constexpr (reads_temperature) st.temperature = p.temperature[i];
    // A failure model reads and writes any model's damage.
    if constexpr (reads_damage || Fails) st.damage = p.damage[i];
    core::load_model_history<Strength>(st, p.history.data() + i * p.history_count);
    if constexpr (requires { Strength::reads_deformation_gradient; })
      st.deformation_gradient = &p.deformation_gradient[i];  // updated by kinematics_kernel
    if constexpr (requires(const Strength& s) { s.splits_volumetric_energy(); })
      if (mixed) st.mixed_pressure = mixed + i;  // the refusals let only a splitting one take it
    st.energy = p.energy[i];
    st.density = p.mass[i] / volume;
    // A high explosive: its burn fraction at the step's end (core/programmed_burn.hpp).
    if (explosive)
      st.burn = core::burn_fraction(*mat.burn, mat.density, p.burn[i], burn_time, p.light_time[i],
                                    h, mat.density / st.density);
  }

  // Particle i's position x, kinematics and start state, each a separate local of the caller.
  AFEMP_INLINE void prepare(std::size_t i, Vec3& x, Vec3& v_bar, Vec3& v_p, core::SymTensor& d_eps,
                            core::PointState& st) {
    x = p.position[i];
    core::Mat3 l;
    kinematics(i, x, l, v_bar, v_p);
    st = core::PointState{};
    start(i, l, d_eps, st);
  }

  // The state stored after the constitutive update u, the bulk viscosity, the move and the
  // step bound of particle i.
  AFEMP_INLINE void commit(std::size_t i, Vec3& x, const Vec3& v_bar, const Vec3& v_p,
                           const core::SymTensor& d_eps, core::PointState& st,
                           const core::PointUpdate& u) {
    p.stress[i] = st.stress;
    if (explosive) p.burn[i] = st.burn;
    if constexpr (reads_plastic_strain) p.plastic_strain[i] = st.plastic_strain;
    if constexpr (Thermal) p.temperature[i] = st.temperature;
    if constexpr (reads_damage || Fails) p.damage[i] = st.damage;
    core::store_model_history<Strength>(st, p.history.data() + i * p.history_count);
    if (track_strain) p.strain[i] += d_eps;
    if constexpr (Fails) {
      if (principal_strain)
        p.damage[i] = core::principal_strain_damage(mat.failure, p.damage[i], p.strain[i]);
    }
    if (track_length) {  // the particle's extent along each axis stretches with the grid's
      Vec3& l = p.length[i];
      l = Vec3{l.x * (1.0 + d_eps.xx), l.y * (1.0 + d_eps.yy), l.z * (1.0 + d_eps.zz)};
    }
    const double plastic = p.mass[i] * u.plastic_work;
    work += plastic;
    if (exact) exact[0].add(plastic);
    if (track_heat) p.plastic_heat[i] += u.plastic_work;
    bound(i, x, v_bar, v_p, d_eps, st);
  }

  // The bulk viscosity, the energy, the move and the step bound of particle i. The bound uses
  // max c + max |v| >= max (c + |v|): squares here, two square roots per step instead of two
  // per particle.
  AFEMP_INLINE void bound(std::size_t i, Vec3& x, const Vec3& v_bar, const Vec3& v_p,
                          const core::SymTensor& d_eps, core::PointState& st) {
    double c_wave = core::wave_speed(mat, eos, st);
    if (viscous) {
      const double q_heat = core::bulk_viscous_heat(p.bulk_q[i], d_eps.trace(), st.density);
      st.energy += q_heat;
      heat += p.mass[i] * q_heat;
      if (exact) exact[1].add(p.mass[i] * q_heat);
      if (track_heat) p.viscous_heat[i] += q_heat;
      const core::ViscousState vs =
          core::bulk_viscosity(viscosity[static_cast<std::size_t>(p.body[i])], st.density, h,
                               d_eps.trace() / dt, c_wave);
      p.bulk_q[i] = vs.q;
      c_wave = vs.signal;
    }
    p.energy[i] = st.energy;
    if (Fused && sweep.move) {
      x += step_dt * v_bar;
      p.position[i] = x;
    }
    const double v2 = core::dot(v_p, v_p);
    const core::SymTensor& o = st.stress;
    // One sum catches a NaN or Inf in any of the values it adds.
    if (!std::isfinite(c_wave + v2 + o.xx + o.yy + o.zz + o.yz + o.xz + o.xy + x.x + x.y + x.z) &&
        bad < 0)
      bad = static_cast<std::int64_t>(i);
    wave = std::max(wave, c_wave);
    speed2 = std::max(speed2, v2);
  }

  // Particles [b, e): one direct (inlined) constitutive call per point.
  void run(std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Vec3 x, v_bar, v_p;
      core::SymTensor d_eps;
      core::PointState st;
      prepare(i, x, v_bar, v_p, d_eps, st);
      const core::PointUpdate u = core::constitutive_update<Strength, Eos, Fails>(
          mat, strength, eos, Thermal, st, d_eps, dt);
      commit(i, x, v_bar, v_p, d_eps, st, u);
    }
  }

  // A user model: the kinematics of a chunk, one call of the user's function, then the rest.
  void run_user_chunks(std::size_t b, std::size_t e) {
    core::UserStrengthChunk chunk(mat, strength);
    const std::size_t hc = p.history_count;
    constexpr std::size_t N = core::kUserChunk;
    std::array<Vec3, N> x, v_bar, v_p;
    std::array<core::SymTensor, N> d_eps;
    std::array<core::PointState, N> st;
    std::array<core::IncrementStart, N> begin;
    for (std::size_t i0 = b; i0 < e; i0 += N) {
      const std::size_t n = std::min(N, e - i0);
      for (std::size_t j = 0; j < n; ++j) {
        prepare(i0 + j, x[j], v_bar[j], v_p[j], d_eps[j], st[j]);
        begin[j] = core::start_increment<Fails>(mat, st[j], d_eps[j], dt);
        chunk.load(j, st[j], begin[j], p.history.data() + (i0 + j) * hc);
      }
      chunk.run(n, dt);
      for (std::size_t j = 0; j < n; ++j) {
        chunk.store_history(j, p.history.data() + (i0 + j) * hc);
        const core::PointUpdate u = core::finish_increment<Eos, Fails>(
            mat, eos, Thermal, st[j], begin[j], chunk.deviator(j), chunk.result(j));
        commit(i0 + j, x[j], v_bar[j], v_p[j], d_eps[j], st[j], u);
      }
    }
  }
};

template <class Strength, class Eos, bool Thermal, bool Fused, bool Fails>
void MpmSolver::strain_stress_batch(const MaterialBatch& batch, const Strength& strength,
                                    const Eos& eos, double step_dt, const StrainSweep& sweep,
                                    int nt) {
  const core::Material& material = *materials_[static_cast<std::size_t>(batch.material)];
#pragma omp parallel num_threads(nt) if (core::worth_threads(batch.end - batch.begin))
  {
    StressPass<Strength, Eos, Thermal, Fused, Fails> pass(*this, material, strength, eos, step_dt,
                                                          sweep);
    const int t = core::thread_index();
    if (!exact_threads_.empty() && reproducible())
      pass.exact = exact_threads_.data() + 3 * static_cast<std::size_t>(t);
    const auto [b, e] = core::static_range(batch.end - batch.begin, t, core::team_size());
    if constexpr (core::is_user_strength<Strength>)
      pass.run_user_chunks(batch.begin + b, batch.begin + e);
    else
      pass.run(batch.begin + b, batch.begin + e);
    double* out = thread_sums_.data() + static_cast<std::size_t>(t) * core::cache_line_doubles;
    out[0] += pass.work;
    out[1] = std::max(out[1], pass.wave);
    out[2] = std::max(out[2], pass.speed2);
    out[3] += pass.heat;
    out[4] += pass.swept;
    auto& tb = thread_bad_[static_cast<std::size_t>(t)];
    if (pass.bad >= 0 && (tb < 0 || pass.bad < tb)) tb = pass.bad;
  }
}

}  // namespace afemp::mpm
