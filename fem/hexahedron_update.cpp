// The hexahedron stage: for every live element, the strain increment from v^{n+1/2} on the
// mid-step geometry (Belytschko, Liu & Moran box 6.1), the Jaumann-rotated stress updated by
// the shared material law (Ma 2005, eq 2-41), artificial bulk viscosity
// q = rho l (C_q l eps_v'^2 - C_l c eps_v') in compression (core/bulk_viscosity.hpp, shared with
// the particles), hourglass forces for one-point elements (Flanagan & Belytschko 1981 viscous
// or stiffness forms, or Belytschko & Bindeman 1993 assumed strain), the nodal forces on the
// end-of-step geometry, the critical step l / (Q + sqrt(Q^2 + c^2)) with
// Q = C_l c + C_q l |eps_v'|, and the erosion criteria. One std::visit per batch; one-point
// elements go in packs of kLanes through the vectorised kernels of fem/hexahedron_lanes.hpp.
#include <cmath>
#include <string>

#include "core/bulk_viscosity.hpp"
#include "core/erosion_criteria.hpp"
#include "core/materials/material.hpp"
#include "core/materials/user_strength_chunk.hpp"
#include "core/parallel.hpp"
#include "core/programmed_burn.hpp"
#include "fem/fe_solver.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_lanes.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/hourglass.hpp"
#include "fem/hourglass_assumed_strain.hpp"

namespace afemp::fem {

namespace {

struct StrainIncrement {
  core::SymTensor d_eps;
  double w23, w13, w12;  // spin increment W dt
};

StrainIncrement increment(const core::Mat3& l, double dt) {
  return {dt * core::sym_part(l), 0.5 * dt * (l.m[1][2] - l.m[2][1]),
          0.5 * dt * (l.m[0][2] - l.m[2][0]), 0.5 * dt * (l.m[0][1] - l.m[1][0])};
}

// Elements per pack of the one-point sweep: two AVX-512 or four AVX2 registers per array row.
constexpr int kLanes = 8;

// Thread slots: plastic work, bulk-viscous work, hourglass work, assumed-strain stabilisation.
constexpr std::size_t kPlastic = 0, kViscous = 1, kHourglass = 2, kStabilisation = 3;

}  // namespace

template <class Strength, class Eos, bool Thermal, bool Fails>
void FeSolver::hexahedron_batch(const ElementBatch& b, const Strength& strength, const Eos& eos,
                                double dt) {
  const core::BodySpec& body = scene_.bodies[static_cast<std::size_t>(b.body)];
  const core::Material& mat = scene_.materials[static_cast<std::size_t>(b.material)];
  const bool full = b.points_per_element == 8;
  const core::BulkViscositySettings viscosity = core::bulk_viscosity_of(scene_, body);
  const core::HourglassForm hg_form = body.hourglass.form;
  // Assumed strain: the elastic constants, the scene's coefficient scaling the stiffness.
  const double hg_shear = body.hourglass.coefficient * mat.shear_modulus();
  const double q_hg = body.hourglass.coefficient;
  // The force step of this step's nodal update, which the last update's forces acted over.
  const double dt_force = force_step(dt);
  const core::ErosionSettings* erosion = body.erosion ? &*body.erosion : nullptr;
  const core::ConversionSettings* conversion = body.conversion ? &*body.conversion : nullptr;
  // The retirement domain's Courant step for this material at rest, h / c (conversion's
  // time-step criterion).
  const double grid_step =
      conversion ? retirement_.cell /
                       core::wave_speed(mat, core::PointState{{}, 0.0, 0.0, 0.0, mat.density})
                 : 0.0;
  HexElements& el = hexes_;
  [[maybe_unused]] const bool principal_strain = mat.needs_strain();
  // A high explosive: burn fractions at the step's end (time_ is already there).
  const bool explosive = mat.is_explosive();

  // Update of one integration point with the velocity gradient l of the step, in two halves
  // around the strength model: a user model (afemp/user_material.hpp) runs between them on
  // the points of a whole element or pack.
  struct PointStart {
    core::PointState st;
    core::SymTensor d_eps;
    double q_heat = 0.0;
  };
  auto begin_point = [&](std::size_t p, const core::Mat3& l, double density,
                         double q_old) AFEMP_INLINE {
    const StrainIncrement inc = increment(l, dt);
    PointStart ps{core::PointState{el.stress[p], el.plastic_strain[p], el.temperature[p],
                                   el.energy[p], density},
                  inc.d_eps};
    // A failure model reads and writes any model's damage.
    if constexpr (core::has_damage_state<Strength> || Fails) ps.st.damage = el.damage[p];
    core::load_model_history<Strength>(ps.st, el.history.data() + p * el.history_count);
    ps.st.stress += core::jaumann_increment(ps.st.stress, inc.w23, inc.w13, inc.w12);
    if (explosive)
      ps.st.burn = core::burn_fraction(*mat.burn, mat.density, el.burn[p], time_, el.light_time[p],
                                       el.burn_length[p], mat.density / density);
    // Bulk-viscous heating by the q that acted over this step.
    ps.q_heat = core::bulk_viscous_heat(q_old, inc.d_eps.trace(), density);
    return ps;
  };
  auto end_point = [&](std::size_t p, PointStart& ps, const core::PointUpdate& u,
                       double* sums) AFEMP_INLINE {
    core::PointState& st = ps.st;
    st.energy += ps.q_heat;
    sums[kPlastic] += el.point_mass[p] * u.plastic_work;
    sums[kViscous] += el.point_mass[p] * ps.q_heat;
    if (!el.plastic_heat.empty()) {  // elements may erode (the same for every point)
      el.plastic_heat[p] += u.plastic_work;
      el.viscous_heat[p] += ps.q_heat;
    }
    el.stress[p] = st.stress;
    if (explosive) el.burn[p] = st.burn;
    el.plastic_strain[p] = st.plastic_strain;
    el.temperature[p] = st.temperature;
    el.energy[p] = st.energy;
    el.density[p] = st.density;
    if constexpr (core::has_damage_state<Strength> || Fails) el.damage[p] = st.damage;
    core::store_model_history<Strength>(st, el.history.data() + p * el.history_count);
    if constexpr (Fails) {
      if (principal_strain) {
        el.strain[p] += ps.d_eps;
        el.damage[p] = core::principal_strain_damage(mat.failure, el.damage[p], el.strain[p]);
      }
    }
    return core::wave_speed(mat, eos, st);
  };
  auto update_point = [&](std::size_t p, const core::Mat3& l, double density, double q_old,
                          double* sums) {
    if constexpr (core::is_user_strength<Strength>) {
      return 0.0;  // user models take load_point, run and finish_point below
    } else {
      PointStart ps = begin_point(p, l, density, q_old);
      const core::PointUpdate u = core::constitutive_update<Strength, Eos, Fails>(
          mat, strength, eos, Thermal, ps.st, ps.d_eps, dt);
      return end_point(p, ps, u, sums);
    }
  };
  // A user model's chunk: load point p into slot j, then (after run) finish slot j.
  constexpr bool user = core::is_user_strength<Strength>;
  [[maybe_unused]] const std::size_t hc = el.history_count;
  auto load_point = [&](auto& chunk, std::size_t j, std::size_t p, PointStart& ps,
                        core::IncrementStart& in) {
    in = core::start_increment<Fails>(mat, ps.st, ps.d_eps, dt);
    chunk.load(j, ps.st, in, el.history.data() + p * hc);
  };
  auto finish_point = [&](auto& chunk, std::size_t j, std::size_t p, PointStart& ps,
                          const core::IncrementStart& in, double* sums) {
    chunk.store_history(j, el.history.data() + p * hc);
    const core::PointUpdate u = core::finish_increment<Eos, Fails>(
        mat, eos, Thermal, ps.st, in, chunk.deviator(j), chunk.result(j));
    return end_point(p, ps, u, sums);
  };
  // Bulk-viscous pressure q and the critical step of an element (length l, dilatation rate
  // trace_rate, wave speed c).
  auto bulk_viscosity = [&](std::size_t e, double density, double length, double trace_rate,
                            double wave) {
    const core::ViscousState v = core::bulk_viscosity(viscosity, density, length, trace_rate, wave);
    el.bulk_q[e] = v.q;
    el.critical_dt[e] = length / v.signal;
    return v.q;
  };
  // After the forces f of element e: bad values, the erosion criteria, the forces stored.
  auto finish = [&](std::size_t e, std::size_t p0, double volume, const char* failure,
                    HexVectors& f, int t) {
    el.volume[e] = volume;
    if (!failure) {
      bool bad = !std::isfinite(f[0].x + f[0].y + f[0].z);
      for (int g = 0; g < b.points_per_element; ++g) {
        const core::SymTensor& s = el.stress[p0 + static_cast<std::size_t>(g)];
        bad = bad || !std::isfinite(s.xx + s.yy + s.zz + s.yz + s.xz + s.xy);
      }
      if (bad && thread_errors_[static_cast<std::size_t>(t)].empty()) {
        thread_errors_[static_cast<std::size_t>(t)] =
            "hexahedron " + std::to_string(e - b.begin) + " of body " + body.name;
        thread_error_field_[static_cast<std::size_t>(t)] = "stress";
      }
    }
    // Conversion first (AFEMP): an element inside the grid that meets a criterion, or inverts
    // with negative_jacobian on, becomes particles; outside the grid erosion still applies.
    if (conversion && (!failure || conversion->negative_jacobian) && inside_retirement_domain(e)) {
      const char* reason =
          failure ? failure : conversion_reason(*conversion, b, e, volume, grid_step);
      if (reason) {
        thread_conversions_[static_cast<std::size_t>(t)].push_back(e);
        thread_conversion_reason_[static_cast<std::size_t>(t)].push_back(reason);
        for (std::size_t a = 0; a < 8; ++a) element_force_[8 * e + a] = Vec3{};
        return;
      }
    }
    if (erosion && !failure) {
      double eps_p = 0.0, damage = 0.0;
      for (int g = 0; g < b.points_per_element; ++g) {
        eps_p = std::max(eps_p, el.plastic_strain[p0 + static_cast<std::size_t>(g)]);
        damage = std::max(damage, el.damage[p0 + static_cast<std::size_t>(g)]);
      }
      failure = core::erosion_reason(*erosion, mat, eps_p, volume, el.volume0[e], el.critical_dt[e],
                                     damage);
    }
    if (failure) {
      if (!erosion) {
        if (thread_errors_[static_cast<std::size_t>(t)].empty()) {
          // With conversion on inversion the element got here only by lying outside the grid.
          thread_errors_[static_cast<std::size_t>(t)] =
              "hexahedron " + std::to_string(e - b.begin) + " of body " + body.name +
              (conversion && conversion->negative_jacobian
                   ? " (outside the background grid, where it cannot convert)"
                   : "");
          thread_error_field_[static_cast<std::size_t>(t)] = "jacobian";
        }
        return;
      }
      thread_erosions_[static_cast<std::size_t>(t)].push_back(e);
      thread_failure_[static_cast<std::size_t>(t)].push_back(failure);
      for (HexVectors::size_type a = 0; a < 8; ++a) f[a] = Vec3{};
    }
    for (std::size_t a = 0; a < 8; ++a) element_force_[8 * e + a] = f[a];
  };

  // Fully integrated (B-bar) elements, one at a time.
  auto sweep_full = [&](std::size_t begin, std::size_t end, int t) {
    double* sums = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
    [[maybe_unused]] core::UserChunkFor<Strength> chunk(mat, strength);
    [[maybe_unused]] std::array<PointStart, 8> pending;
    [[maybe_unused]] std::array<core::IncrementStart, 8> starts;
    for (std::size_t e = begin; e < end; ++e) {
      if (!el.alive[e]) continue;
      HexVectors x_new, x_mid, v;
      for (std::size_t a = 0; a < 8; ++a) {
        const auto n = static_cast<std::size_t>(el.nodes[e][a]);
        v[a] = nodes_.velocity[n];
        x_new[a] = nodes_.position[n];
        x_mid[a] = x_new[a] - (0.5 * dt) * v[a];
      }
      const std::size_t p0 = b.point_begin + (e - b.begin) * 8;
      const double q_old = el.bulk_q[e];
      HexVectors f{};
      const char* failure = nullptr;
      const FullHex mid = full_hex(x_mid);
      const FullHex now = full_hex(x_new);
      const double volume = now.volume;
      if (!(min_jacobian(now) > 0.0) || !(min_jacobian(mid) > 0.0)) {
        failure = "negative Jacobian";
      } else {
        const double density = el.mass[e] / volume;  // B-bar: uniform dilatation
        double trace_rate = 0.0, wave = 0.0;
        for (std::size_t g = 0; g < 8; ++g) {
          const core::Mat3 l = velocity_gradient_bbar(mid, static_cast<int>(g), v);
          if (g == 0) trace_rate = l.m[0][0] + l.m[1][1] + l.m[2][2];
          if constexpr (user) {
            pending[g] = begin_point(p0 + g, l, density, q_old);
            load_point(chunk, g, p0 + g, pending[g], starts[g]);
          } else {
            wave = std::max(wave, update_point(p0 + g, l, density, q_old, sums));
          }
        }
        if constexpr (user) {
          chunk.run(8, dt);
          for (std::size_t g = 0; g < 8; ++g)
            wave = std::max(wave, finish_point(chunk, g, p0 + g, pending[g], starts[g], sums));
        }
        const double q =
            bulk_viscosity(e, density, characteristic_length(x_new, volume), trace_rate, wave);
        std::array<core::SymTensor, 8> sigma;
        for (std::size_t g = 0; g < 8; ++g)
          sigma[g] = el.stress[p0 + g] - q * core::SymTensor::identity();
        add_stress_forces_bbar(now, sigma, f);
      }
      finish(e, p0, volume, failure, f, t);
    }
  };

  // One-point elements in packs of kLanes: the geometry, velocity gradient, hourglass shapes
  // and nodal forces run on all lanes at once (fem/hexahedron_lanes.hpp); the material update,
  // bulk viscosity and hourglass resistance run lane by lane.
  constexpr int W = kLanes;
  auto sweep_one_point = [&](std::size_t begin, std::size_t end, int t) {
    double* sums = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
    alignas(64) double x[3][8][W], v[3][8][W], xm[3][8][W], c[3][8][W], bm[3][8][W], bn[3][8][W],
        f[3][8][W], grad[3][3][W], gamma[4][8][W], q[4][3][W], g[4][3][W], sigma[6][W];
    alignas(64) double vol_mid[W], vol[W], length[W];
    [[maybe_unused]] core::UserChunkFor<Strength> chunk(mat, strength);
    [[maybe_unused]] std::array<PointStart, W> pending;
    [[maybe_unused]] std::array<core::IncrementStart, W> starts;
    for (std::size_t e0 = begin; e0 < end; e0 += W) {
      const int n = static_cast<int>(std::min<std::size_t>(W, end - e0));
      // Lanes past the end repeat the last element; their results are dropped.
      for (int l = 0; l < W; ++l) {
        const std::size_t e = e0 + static_cast<std::size_t>(std::min(l, n - 1));
        for (int a = 0; a < 8; ++a) {
          const auto node = static_cast<std::size_t>(el.nodes[e][static_cast<std::size_t>(a)]);
          const Vec3& xa = nodes_.position[node];
          const Vec3& va = nodes_.velocity[node];
          for (int i = 0; i < 3; ++i) {
            x[i][a][l] = xa[i];
            v[i][a][l] = va[i];
          }
        }
      }
      for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 8; ++a)
          for (int l = 0; l < W; ++l) xm[i][a][l] = x[i][a][l] - 0.5 * dt * v[i][a][l];
      lanes::b_vectors<W>(xm, c, bm, vol_mid);
      lanes::b_vectors<W>(x, c, bn, vol);
      lanes::velocity_gradient<W>(bm, vol_mid, v, grad);
      lanes::characteristic_length<W>(x, vol, length);
      if (q_hg > 0.0) {
        lanes::hourglass_shapes<W>(c, bn, vol, gamma);
        lanes::hourglass_velocities<W>(gamma, v, q);
      }

      auto live_lane = [&](int l) {
        const std::size_t e = e0 + static_cast<std::size_t>(l);
        return l < n && el.alive[e] && vol[l] > 0.0 && vol_mid[l] > 0.0;
      };
      auto lane_gradient = [&](int l) {
        core::Mat3 lg;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) lg.m[i][j] = grad[i][j][l];
        return lg;
      };
      if constexpr (user) {
        // The live lanes' material points in one call of the user's function.
        std::size_t count = 0;
        for (int l = 0; l < W; ++l) {
          if (!live_lane(l)) continue;
          const std::size_t e = e0 + static_cast<std::size_t>(l);
          const std::size_t p = b.point_begin + (e - b.begin);
          pending[count] = begin_point(p, lane_gradient(l), el.mass[e] / vol[l], el.bulk_q[e]);
          load_point(chunk, count, p, pending[count], starts[count]);
          ++count;
        }
        if (count > 0) chunk.run(count, dt);
      }
      [[maybe_unused]] std::size_t slot = 0;  // the user chunk's slot of the next live lane
      const char* failure[W] = {};
      for (int l = 0; l < W; ++l) {
        const std::size_t e = e0 + static_cast<std::size_t>(l);
        const bool live = live_lane(l);
        if (l < n && el.alive[e] && !live) failure[l] = "negative Jacobian";
        for (int k = 0; k < 4; ++k)
          for (int i = 0; i < 3; ++i) g[k][i][l] = 0.0;
        for (double(&s)[W] : sigma) s[l] = 0.0;
        if (!live) continue;
        const core::Mat3 lg = lane_gradient(l);
        const double trace_rate = lg.m[0][0] + lg.m[1][1] + lg.m[2][2];
        const double density = el.mass[e] / vol[l];
        const std::size_t p = b.point_begin + (e - b.begin);
        double wave;
        if constexpr (user) {
          wave = finish_point(chunk, slot, p, pending[slot], starts[slot], sums);
          ++slot;
        } else {
          wave = update_point(p, lg, density, el.bulk_q[e], sums);
        }
        const double bulk_q = bulk_viscosity(e, density, length[l], trace_rate, wave);
        const core::SymTensor& s = el.stress[p];
        sigma[0][l] = s.xx - bulk_q;
        sigma[1][l] = s.yy - bulk_q;
        sigma[2][l] = s.zz - bulk_q;
        sigma[3][l] = s.yz;
        sigma[4][l] = s.xz;
        sigma[5][l] = s.xy;
        if (q_hg <= 0.0) continue;
        if (hg_form == core::HourglassForm::assumed_strain) {
          HexVectors xe;
          lanes::store<W>(x, l, xe);
          std::array<Vec3, 4> qe, ge;
          for (int k = 0; k < 4; ++k) qe[k] = {q[k][0][l], q[k][1][l], q[k][2][l]};
          sums[kStabilisation] += dt * assumed_strain_hourglass_forces(
                                           assumed_strain_geometry(xe), vol[l], hg_shear,
                                           mat.poisson_ratio, dt, qe, el.hourglass_force[e], ge);
          for (int k = 0; k < 4; ++k)
            for (int i = 0; i < 3; ++i) g[k][i][l] = ge[k][i];
        } else if (hg_form == core::HourglassForm::stiffness) {
          // The stored energy changes by (Q_old + Q_new)/2 . q dt (exactly Q^2 / 2 k_h for a
          // constant k_h); Q_new alone would be off by k_h q^2 dt^2 / 2 a step.
          double b_squared = 0.0;
          for (int i = 0; i < 3; ++i)
            for (int a = 0; a < 8; ++a) b_squared += bn[i][a][l] * bn[i][a][l];
          const double k_h =
              stiffness_hourglass_factor(q_hg, density * wave * wave, b_squared, vol[l]);
          double work = 0.0;
          for (int k = 0; k < 4; ++k) {
            Vec3& hk = el.hourglass_force[e][static_cast<std::size_t>(k)];
            const Vec3 qk{q[k][0][l], q[k][1][l], q[k][2][l]};
            const Vec3 h_old = hk;
            hk += (k_h * dt) * qk;
            work += 0.5 * core::dot(h_old + hk, qk) * dt;
            for (int i = 0; i < 3; ++i) g[k][i][l] = hk[i];
          }
          sums[kHourglass] += work;
        } else {
          double a_h = viscous_hourglass_factor(q_hg, density, wave, vol[l]);
          // A mode's velocity decays at a rate a_h sum_a gamma_ka^2 / m_a. In a parallelepiped
          // sum_a gamma_ka^2 = 8; in an element far from one it is larger (27 in a random
          // element with a smallest scaled corner Jacobian of 0.05), and, explicit, the force
          // then reverses its mode within the step (in a steel plate a blunt projectile shears
          // a plug out of, the hourglass energy, then booked when the force was found, jumped
          // by 0.6 % of the total in ten steps, and the balance drifted by 1.7 %). The factor is
          // scaled so that no mode decays faster than twice as fast as in the parallelepiped
          // of its volume: regular meshes are untouched.
          double modes = 0.0;
          for (int k = 0; k < 4; ++k) {
            double sum = 0.0;
            for (int a = 0; a < 8; ++a) sum += gamma[k][a][l] * gamma[k][a][l];
            modes = std::max(modes, sum);
          }
          if (modes > 16.0) a_h *= 16.0 / modes;
          // The work is booked once it is done. The forces found here act in the next nodal
          // update, over the force step dt_f, and change the velocities from those they were
          // found from, v^{n+1/2}, to v^{n+3/2}: their work is dt_f (g . q^{n+1/2} +
          // g . q^{n+3/2}) / 2 (g = a_h q, the generalised forces). The held forces of the last
          // update (global axes) and their power at their own velocities are the first half;
          // the second is theirs at this step's q (this step's shape vectors: the element moved
          // by one step). Booking a_h q^2 dt when the force is found counts work it does not
          // do: within the step it changes its mode's velocity by the fraction
          // alpha = a_h sum gamma^2 dt / m (about 1.4 on a regular mesh at the default step and
          // coefficient), and does the work a_h q^2 dt (1 - alpha / 2): a lone element started
          // in an hourglass mode booked 1.9 times its kinetic energy.
          std::array<Vec3, 4>& held = el.hourglass_force[e];
          double done = 0.0, power = 0.0;
          for (int k = 0; k < 4; ++k)
            for (int i = 0; i < 3; ++i) {
              const double gk = a_h * q[k][i][l];
              done += held[static_cast<std::size_t>(k)][i] * q[k][i][l];
              power += gk * q[k][i][l];
              held[static_cast<std::size_t>(k)][i] = gk;
              g[k][i][l] = gk;
            }
          sums[kHourglass] += 0.5 * dt_force * (el.hourglass_power[e] + done);
          el.hourglass_power[e] = power;
        }
      }
      lanes::stress_forces<W>(bn, sigma, f);
      if (q_hg > 0.0) lanes::subtract_hourglass_forces<W>(gamma, g, f);
      for (int l = 0; l < n; ++l) {
        const std::size_t e = e0 + static_cast<std::size_t>(l);
        if (!el.alive[e]) continue;
        HexVectors fe;
        lanes::store<W>(f, l, fe);
        finish(e, b.point_begin + (e - b.begin), vol[l], failure[l], fe, t);
      }
    }
  };

  core::parallel_chunks(b.end - b.begin, [&](std::size_t lo, std::size_t hi, int t) {
    if (full)
      sweep_full(b.begin + lo, b.begin + hi, t);
    else
      sweep_one_point(b.begin + lo, b.begin + hi, t);
  });
}

void FeSolver::update_hexahedra(double dt) {
  std::fill(thread_sums_.begin(), thread_sums_.end(), 0.0);
  for (auto& e : thread_errors_) e.clear();
  // The stabilisation energy per body (part of its internal energy): the threads' sums
  // grow batch by batch, so a batch's share is the growth over its sweep.
  auto stabilisation = [&] {
    double sum = 0.0;
    for (std::size_t t = 0; t < thread_errors_.size(); ++t)
      sum += thread_sums_[t * core::cache_line_doubles + kStabilisation];
    return sum;
  };
  for_each_batch(
      hexes_, [&]<class S, class E, bool Thermal>(const ElementBatch& b, const S& s, const E& e) {
        const double before = stabilisation();
        if (scene_.materials[static_cast<std::size_t>(b.material)].fails())
          hexahedron_batch<S, E, Thermal, true>(b, s, e, dt);
        else
          hexahedron_batch<S, E, Thermal, false>(b, s, e, dt);
        body_stabilisation_[static_cast<std::size_t>(b.body)] += stabilisation() - before;
        raise_thread_errors();
        collect_erosions(hexes_, "hexahedron");
        collect_retirements();
      });
  for (std::size_t t = 0; t < thread_errors_.size(); ++t) {
    const double* s = &thread_sums_[t * core::cache_line_doubles];
    plastic_work_ += s[kPlastic];
    viscous_work_ += s[kViscous];
    hourglass_work_ += s[kHourglass];
    stabilisation_work_ += s[kStabilisation];
  }
}

}  // namespace afemp::fem
