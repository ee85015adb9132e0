// Strain and stress update of the particles (seed 001 eqs 2-38..2-41): velocity gradient
// from the nodal velocity the scheme names, Jaumann rotation of the stress, volume update
// V <- V (1 + tr d eps) (eq 2-40), then the material's constitutive update, batch by batch:
// one std::visit per material, one direct call per point.
#include <cmath>

#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::strain_stress_update(double dt) {
  const int nt = core::thread_count();
  thread_sums_.assign(static_cast<std::size_t>(nt) * core::cache_line_doubles, 0.0);
  thread_bad_.assign(static_cast<std::size_t>(nt), -1);
  for (const MaterialBatch& batch : batches_) {
    const core::Material& m = *materials_[static_cast<std::size_t>(batch.material)];
    std::visit(
        [&](const auto& strength, const auto& eos) {
          using S = std::decay_t<decltype(strength)>;
          using E = std::decay_t<decltype(eos)>;
          if (m.has_thermal_term())
            strain_stress_batch<S, E, true>(batch, strength, eos, dt, nt);
          else
            strain_stress_batch<S, E, false>(batch, strength, eos, dt, nt);
        },
        m.strength, m.eos);
  }
  double work = 0.0, speed = 0.0;
  for (int t = 0; t < nt; ++t) {
    work += thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
    speed = std::max(speed, thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles + 1]);
  }
  plastic_work_ += work;
  signal_speed_ = speed;
  raise_if_bad("stress");
}

template <class Strength, class Eos, bool Thermal>
void MpmSolver::strain_stress_batch(const MaterialBatch& batch, const Strength& strength,
                                    const Eos& eos, double dt, int nt) {
  const core::BackgroundGrid& g = grid_;
  Particles& p = particles_;
  const core::Material& mat = *materials_[static_cast<std::size_t>(batch.material)];
  const bool jaumann = plan_.jaumann;
  // The velocity the strain rate comes from: USF the start-of-step grid velocity, USL the
  // updated one, MUSL the remapped one. USL and MUSL move the particle here (eq 2-35).
  const std::vector<Vec3>* from = &g.velocity_new;
  bool move = true;
  if (plan_.scheme == core::UpdateScheme::USF) {
    from = &g.velocity;
    move = false;
  } else if (plan_.scheme == core::UpdateScheme::MUSL) {
    from = &g.velocity_remap;
  }
  const std::vector<Vec3>& v_strain = *from;
  const std::vector<Vec3>& v_move = g.velocity_new;

#pragma omp parallel num_threads(nt)
  {
    const int t = core::thread_index();
    const auto [b, e] = core::static_range(batch.end - batch.begin, t, core::team_size());
    double work = 0.0, speed = 0.0;
    std::int64_t bad = -1;
    for (std::size_t i = batch.begin + b; i < batch.begin + e; ++i) {
      Vec3& x = p.position[i];
      const auto c = g.cell_of(x);
      const core::CellWeights w = g.weights(x, c);
      std::array<std::int32_t, 8> slot;
      g.node_slots(c, slot);
      core::Mat3 l;  // L_ij = sum_I v_Ii dN_I/dx_j
      Vec3 v_bar;
      for (int k = 0; k < 8; ++k) {
        const auto s = static_cast<std::size_t>(slot[static_cast<std::size_t>(k)]);
        const Vec3& v = v_strain[s];
        const Vec3& d = w.grad[static_cast<std::size_t>(k)];
        for (int r = 0; r < 3; ++r) {
          l.m[r][0] += v[r] * d.x;
          l.m[r][1] += v[r] * d.y;
          l.m[r][2] += v[r] * d.z;
        }
        if (move) v_bar += w.w[static_cast<std::size_t>(k)] * v_move[s];
      }
      const core::SymTensor d_eps = dt * core::sym_part(l);
      core::PointState st;
      st.stress = p.stress[i];
      if (jaumann) {
        st.stress += core::jaumann_increment(st.stress, 0.5 * dt * (l.m[1][2] - l.m[2][1]),
                                             0.5 * dt * (l.m[0][2] - l.m[2][0]),
                                             0.5 * dt * (l.m[0][1] - l.m[1][0]));
      }
      p.volume[i] *= 1.0 + d_eps.trace();
      st.plastic_strain = p.plastic_strain[i];
      st.temperature = p.temperature[i];
      st.energy = p.energy[i];
      st.density = p.mass[i] / p.volume[i];
      const core::PointUpdate u =
          core::constitutive_update(mat, strength, eos, Thermal, st, d_eps, dt);
      p.stress[i] = st.stress;
      p.plastic_strain[i] = st.plastic_strain;
      if constexpr (Thermal) p.temperature[i] = st.temperature;
      p.energy[i] = st.energy;
      p.strain[i] += d_eps;
      work += p.mass[i] * u.plastic_work;
      if (move) x += dt * v_bar;
      const double s = core::wave_speed(mat, st) + core::norm(p.velocity[i]);
      if (!(std::isfinite(s) && std::isfinite(st.stress.trace()) && std::isfinite(x.x + x.y + x.z)) &&
          bad < 0)
        bad = static_cast<std::int64_t>(i);
      speed = std::max(speed, s);
    }
    double* out = thread_sums_.data() + static_cast<std::size_t>(t) * core::cache_line_doubles;
    out[0] += work;
    out[1] = std::max(out[1], speed);
    auto& tb = thread_bad_[static_cast<std::size_t>(t)];
    if (bad >= 0 && (tb < 0 || bad < tb)) tb = bad;
  }
}

}  // namespace afemp::mpm
