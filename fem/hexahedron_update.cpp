// The hexahedron stage: for every live element, the strain increment from v^{n+1/2} on the
// mid-step geometry (Belytschko, Liu & Moran box 6.1), the Jaumann-rotated stress updated by
// the shared material law (seed 001 eq 2-41), artificial bulk viscosity
// q = rho l (C_q l eps_v'^2 - C_l c eps_v') in compression (LS-DYNA theory manual, "Artificial
// bulk viscosity"), hourglass forces (Flanagan & Belytschko 1981) for one-point elements, the
// nodal forces on the end-of-step geometry, the critical step l / (Q + sqrt(Q^2 + c^2)) with
// Q = C_l c + C_q l |eps_v'|, and the erosion criteria. One std::visit per batch.
#include <cmath>
#include <string>

#include "core/materials/material.hpp"
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/hourglass.hpp"

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

// Thread slots: plastic work, bulk-viscous work, hourglass work.
constexpr std::size_t kPlastic = 0, kViscous = 1, kHourglass = 2;

}  // namespace

template <class Strength, class Eos, bool Thermal>
void FeSolver::hexahedron_batch(const ElementBatch& b, const Strength& strength, const Eos& eos,
                                double dt) {
  const core::BodySpec& body = scene_.bodies[static_cast<std::size_t>(b.body)];
  const core::Material& mat = scene_.materials[static_cast<std::size_t>(b.material)];
  const bool full = b.points_per_element == 8;
  const double c_lin = body.bulk_viscosity.linear, c_quad = body.bulk_viscosity.quadratic;
  const bool stiffness = body.hourglass.form == core::HourglassForm::stiffness;
  const double q_hg = body.hourglass.coefficient;
  const core::ErosionSettings* erosion = body.erosion ? &*body.erosion : nullptr;
  FeElements& el = hexes_;

  auto sweep = [&](std::size_t begin, std::size_t end, int t) {
    double* sums = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
    for (std::size_t e = begin; e < end; ++e) {
      if (!el.alive[e]) continue;
      HexVectors x_new, x_mid, v;
      for (std::size_t a = 0; a < 8; ++a) {
        const auto n = static_cast<std::size_t>(el.nodes[e][a]);
        v[a] = nodes_.velocity[n];
        x_new[a] = nodes_.position[n];
        x_mid[a] = x_new[a] - (0.5 * dt) * v[a];
      }
      const std::size_t p0 = b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element);
      const double q_old = el.bulk_q[e];
      HexVectors f{};
      double volume, trace_rate = 0.0, wave = 0.0;
      const char* failure = nullptr;

      auto update_point = [&](std::size_t p, const core::Mat3& l, double density) {
        const StrainIncrement inc = increment(l, dt);
        core::PointState st{el.stress[p], el.plastic_strain[p], el.temperature[p], el.energy[p],
                            density};
        st.stress += core::jaumann_increment(st.stress, inc.w23, inc.w13, inc.w12);
        // Bulk-viscous heating by the q that acted over this step.
        const double q_heat = -q_old * inc.d_eps.trace() / density;
        const core::PointUpdate u =
            core::constitutive_update(mat, strength, eos, Thermal, st, inc.d_eps, dt);
        st.energy += q_heat;
        sums[kPlastic] += el.point_mass[p] * u.plastic_work;
        sums[kViscous] += el.point_mass[p] * q_heat;
        el.stress[p] = st.stress;
        el.plastic_strain[p] = st.plastic_strain;
        el.temperature[p] = st.temperature;
        el.energy[p] = st.energy;
        el.density[p] = density;
        wave = std::max(wave, core::wave_speed(mat, eos, st));
      };

      if (full) {
        const FullHex mid = full_hex(x_mid);
        const FullHex now = full_hex(x_new);
        if (!(min_jacobian(now) > 0.0) || !(min_jacobian(mid) > 0.0)) {
          failure = "negative Jacobian";
          volume = now.volume;
        } else {
          volume = now.volume;
          const double density = el.mass[e] / volume;  // B-bar: uniform dilatation
          for (int g = 0; g < 8; ++g) {
            const core::Mat3 l = velocity_gradient_bbar(mid, g, v);
            if (g == 0) trace_rate = l.m[0][0] + l.m[1][1] + l.m[2][2];
            update_point(p0 + static_cast<std::size_t>(g), l, density);
          }
        }
        if (!failure) {
          const double length = characteristic_length(x_new, volume);
          const double q = trace_rate < 0.0
                               ? (el.mass[e] / volume) * length *
                                     (c_quad * length * trace_rate * trace_rate - c_lin * wave * trace_rate)
                               : 0.0;
          el.bulk_q[e] = q;
          std::array<core::SymTensor, 8> sigma;
          for (std::size_t g = 0; g < 8; ++g) sigma[g] = el.stress[p0 + g] - q * core::SymTensor::identity();
          add_stress_forces_bbar(now, sigma, f);
          const double qv = c_lin * wave + c_quad * length * std::abs(std::min(trace_rate, 0.0));
          el.critical_dt[e] = length / (qv + std::sqrt(qv * qv + wave * wave));
        }
      } else {
        const OnePointHex mid = one_point_hex(x_mid);
        const OnePointHex now = one_point_hex(x_new);
        volume = now.volume;
        if (!(volume > 0.0) || !(mid.volume > 0.0)) {
          failure = "negative Jacobian";
        } else {
          const core::Mat3 l = velocity_gradient(mid, v);
          trace_rate = l.m[0][0] + l.m[1][1] + l.m[2][2];
          const double density = el.mass[e] / volume;
          update_point(p0, l, density);
          const double length = characteristic_length(x_new, volume);
          const double q = trace_rate < 0.0
                               ? density * length *
                                     (c_quad * length * trace_rate * trace_rate - c_lin * wave * trace_rate)
                               : 0.0;
          el.bulk_q[e] = q;
          add_stress_forces(now, el.stress[p0] - q * core::SymTensor::identity(), f);
          if (q_hg > 0.0) {
            const HourglassModes modes = hourglass_modes(now, x_new);
            if (stiffness) {
              // The stored energy changes by (Q_old + Q_new)/2 . q dt (exactly Q^2 / 2 k_h for
              // a constant k_h); the kernel's power uses Q_new alone, and Q_old alone would be
              // off the other way, by k_h q^2 dt^2 / 2 a step either side.
              const std::array<Vec3, 4> q_old = el.hourglass_force[e];
              add_hourglass_stiffness(modes, v, q_hg, density * wave * wave, volume, dt,
                                      el.hourglass_force[e], f);
              double work = 0.0;
              for (std::size_t k = 0; k < 4; ++k) {
                Vec3 qk;
                for (std::size_t a = 0; a < 8; ++a) qk += modes.gamma[k][a] * v[a];
                work += 0.5 * core::dot(q_old[k] + el.hourglass_force[e][k], qk) * dt;
              }
              sums[kHourglass] += work;
            } else {
              sums[kHourglass] += dt * add_hourglass_viscous(modes, v, q_hg, density, wave, volume, f);
            }
          }
          const double qv = c_lin * wave + c_quad * length * std::abs(std::min(trace_rate, 0.0));
          el.critical_dt[e] = length / (qv + std::sqrt(qv * qv + wave * wave));
        }
      }
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
      if (erosion && !failure) {
        double eps_p = 0.0;
        for (int g = 0; g < b.points_per_element; ++g)
          eps_p = std::max(eps_p, el.plastic_strain[p0 + static_cast<std::size_t>(g)]);
        if (erosion->plastic_strain > 0.0 && eps_p >= erosion->plastic_strain)
          failure = "plastic strain";
        else if (erosion->material_failure && mat.failure_strain > 0.0 && eps_p >= mat.failure_strain)
          failure = "material failure strain";
        else if (volume < erosion->volume_ratio * el.volume0[e])
          failure = "volume ratio";
        else if (el.critical_dt[e] < erosion->time_step)
          failure = "time step";
      }
      if (failure) {
        if (!erosion) {
          if (thread_errors_[static_cast<std::size_t>(t)].empty()) {
            thread_errors_[static_cast<std::size_t>(t)] =
                "hexahedron " + std::to_string(e - b.begin) + " of body " + body.name;
            thread_error_field_[static_cast<std::size_t>(t)] = "jacobian";
          }
          continue;
        }
        thread_erosions_[static_cast<std::size_t>(t)].push_back(e);
        thread_failure_[static_cast<std::size_t>(t)].push_back(failure);
        for (HexVectors::size_type a = 0; a < 8; ++a) f[a] = Vec3{};
      }
      for (std::size_t a = 0; a < 8; ++a) element_force_[8 * e + a] = f[a];
    }
  };
  core::parallel_chunks(b.end - b.begin, [&](std::size_t lo, std::size_t hi, int t) {
    sweep(b.begin + lo, b.begin + hi, t);
  });
}

void FeSolver::update_hexahedra(double dt) {
  std::fill(thread_sums_.begin(), thread_sums_.end(), 0.0);
  for (auto& e : thread_errors_) e.clear();
  for_each_batch(hexes_, [&]<class S, class E, bool Thermal>(const ElementBatch& b, const S& s,
                                                         const E& e) {
    hexahedron_batch<S, E, Thermal>(b, s, e, dt);
    raise_thread_errors();
    collect_erosions(hexes_, "hexahedron");
  });
  for (std::size_t t = 0; t < thread_errors_.size(); ++t) {
    const double* s = &thread_sums_[t * core::cache_line_doubles];
    plastic_work_ += s[kPlastic];
    viscous_work_ += s[kViscous];
    hourglass_work_ += s[kHourglass];
  }
}

}  // namespace afemp::fem
