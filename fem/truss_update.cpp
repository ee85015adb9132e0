// The truss stage: the axial strain increment from v^{n+1/2} along the mid-step axis, the
// axial stress from the uniaxial-stress form of the shared material law
// (core/materials/uniaxial_update.hpp), the area from mass conservation, the axial force
// N = sigma A along the end-of-step axis, the bar critical step L / c, and erosion.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/erosion_criteria.hpp"
#include "core/materials/uniaxial_update.hpp"
#include "core/parallel.hpp"
#include "fem/fe_solver.hpp"
#include "fem/truss.hpp"

namespace afemp::fem {

template <class Strength, class Eos, bool Thermal>
void FeSolver::truss_batch(const ElementBatch& b, const Strength& strength, const Eos& eos,
                           double dt) {
  const core::BodySpec& body = scene_.bodies[static_cast<std::size_t>(b.body)];
  const core::Material& mat = scene_.materials[static_cast<std::size_t>(b.material)];
  const core::ErosionSettings* erosion = body.erosion ? &*body.erosion : nullptr;
  TrussElements& el = trusses_;
  const std::size_t force_base = trusses_.first_slot;

  // The mid-step kinematics of truss e: its nodes' positions x and velocities v, its point's
  // start state st and axial strain increment d_axial (separate locals, not one struct, so
  // that the compiler keeps them in registers as in one fused loop).
  auto prepare = [&](std::size_t e, std::array<Vec3, 4>& xv, core::PointState& st,
                     double& d_axial) AFEMP_INLINE {
    const auto na = static_cast<std::size_t>(el.nodes[e][0]);
    const auto nb = static_cast<std::size_t>(el.nodes[e][1]);
    xv = {nodes_.position[na], nodes_.position[nb], nodes_.velocity[na], nodes_.velocity[nb]};
    const std::size_t p = b.point_begin + (e - b.begin);
    const TrussKinematics mid =
        truss_kinematics(xv[0] - (0.5 * dt) * xv[2], xv[1] - (0.5 * dt) * xv[3], xv[2], xv[3]);
    st = core::PointState{el.stress[p], el.plastic_strain[p], el.temperature[p],
                          el.energy[p], el.density[p],        el.damage[p]};
    core::load_model_history<Strength>(st, el.history.data() + p * el.history_count);
    d_axial = mid.axial_strain_rate * dt;
  };
  // The state stored after the uniaxial update u, the forces, the critical step and erosion.
  auto complete = [&](std::size_t e, const std::array<Vec3, 4>& xv, const core::PointState& st,
                      const core::UniaxialUpdate& u, int t, double* sums) AFEMP_INLINE {
    const std::size_t p = b.point_begin + (e - b.begin);
    book(sums, 0, el.point_mass[p] * u.point.plastic_work);
    if (!el.plastic_heat.empty()) el.plastic_heat[p] += u.point.plastic_work;
    el.stress[p] = st.stress;
    el.plastic_strain[p] = st.plastic_strain;
    el.temperature[p] = st.temperature;
    el.energy[p] = st.energy;
    el.density[p] = st.density;
    el.damage[p] = st.damage;
    core::store_model_history<Strength>(st, el.history.data() + p * el.history_count);
    const TrussKinematics now = truss_kinematics(xv[0], xv[1], xv[2], xv[3]);
    const double area =
        current_area(el.area0[e], el.length0[e], mat.density, now.length, st.density);
    el.volume[e] = area * now.length;
    Vec3 fa, fb;
    add_truss_forces(now, st.stress.xx * area, fa, fb);
    el.critical_dt[e] =
        truss_time_step(now.length, core::uniaxial_modulus(mat, eos, st), st.density);
    if (!std::isfinite(st.stress.xx + fa.x + fa.y + fa.z) &&
        thread_errors_[static_cast<std::size_t>(t)].empty()) {
      thread_errors_[static_cast<std::size_t>(t)] =
          "truss " + std::to_string(e - b.begin) + " of body " + body.name;
      thread_error_field_[static_cast<std::size_t>(t)] = "stress";
    }
    const char* failure = erosion
                              ? core::erosion_reason(*erosion, mat, st.plastic_strain, el.volume[e],
                                                     el.volume0[e], el.critical_dt[e])
                              : nullptr;
    if (failure) {
      thread_erosions_[static_cast<std::size_t>(t)].push_back(e);
      thread_failure_[static_cast<std::size_t>(t)].push_back(failure);
      fa = fb = Vec3{};
    }
    element_force_[force_base + 2 * e] = fa;
    element_force_[force_base + 2 * e + 1] = fb;
  };

  auto sweep = [&](std::size_t begin, std::size_t end, int t) {
    double* sums = &thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
    if constexpr (core::is_user_strength<Strength>) {
      // A user model: the live trusses of a chunk search their lateral strain together, each
      // round of trials one call of the user's function.
      core::UserStrengthChunk chunk(mat, strength);
      const std::size_t hc = el.history_count;
      std::array<std::array<Vec3, 4>, core::kUserChunk> xv;
      std::array<core::PointState, core::kUserChunk> points;
      std::array<double, core::kUserChunk> d_axial;
      std::array<double*, core::kUserChunk> history;
      std::array<core::UniaxialUpdate, core::kUserChunk> updates;
      std::array<std::size_t, core::kUserChunk> element;
      std::vector<double> kept;
      for (std::size_t e = begin; e < end;) {
        std::size_t n = 0;
        for (; e < end && n < core::kUserChunk; ++e) {
          if (!el.alive[e]) continue;
          prepare(e, xv[n], points[n], d_axial[n]);
          history[n] = el.history.data() + (b.point_begin + (e - b.begin)) * hc;
          element[n++] = e;
        }
        core::uniaxial_update_user(mat, chunk, eos, Thermal, points.data(), d_axial.data(),
                                   history.data(), n, dt, updates.data(), kept);
        for (std::size_t j = 0; j < n; ++j)
          complete(element[j], xv[j], points[j], updates[j], t, sums);
      }
    } else {
      for (std::size_t e = begin; e < end; ++e) {
        if (!el.alive[e]) continue;
        std::array<Vec3, 4> xv;
        core::PointState st;
        double d_axial = 0.0;
        prepare(e, xv, st, d_axial);
        const core::UniaxialUpdate u =
            core::uniaxial_update(mat, strength, eos, Thermal, st, d_axial, dt);
        complete(e, xv, st, u, t, sums);
      }
    }
  };
  sweep_share(b, sweep);  // this rank's elements (all of them in one process)
}

void TrussSet::update(FeSolver& fe, double dt) {
  fe.update_trusses(dt);
}

void FeSolver::update_trusses(double dt) {
  std::fill(thread_sums_.begin(), thread_sums_.end(), 0.0);
  for (core::ExactSum& s : exact_mirror_) s.clear();
  for (auto& e : thread_errors_) e.clear();
  for_each_batch(
      trusses_, [&]<class S, class E, bool Thermal>(const ElementBatch& b, const S& s, const E& e) {
        truss_batch<S, E, Thermal>(b, s, e, dt);
        raise_thread_errors();
        collect_erosions(trusses_);
      });
  for (std::size_t t = 0; t < thread_errors_.size(); ++t)
    plastic_work_ += thread_sums_[t * core::cache_line_doubles];
  if (reproducible()) exact_[exact_plastic] += exact_threads(0);
}

}  // namespace afemp::fem
