// The passes of the hexahedron stage (FeSolver::hexahedron_batch), run in turn on one pack of
// one-point elements (kLanes of them, the kernels of fem/hexahedron_lanes.hpp) or on one fully
// integrated element: kinematics (gather, b vectors, velocity gradient, lengths, hourglass
// shapes), material (the trial stress and state of every point), bulk viscosity and critical
// step, hourglass forces (one function per form), nodal forces, then commit (the trial state
// written to the element arrays, the work booked) and the checks (bad values, conversion,
// erosion, the forces stored). Everything before commit reads the element arrays and writes
// only the pack's scratch, so a residual (MFEM's AssembleElementVector) is the passes up to the
// forces without the commit.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/bulk_viscosity.hpp"
#include "core/erosion_criteria.hpp"
#include "core/materials/material.hpp"
#include "core/materials/user_strength_chunk.hpp"
#include "core/parallel.hpp"
#include "core/programmed_burn.hpp"
#include "fem/fe_solver.hpp"
#include "fem/hexahedron_deformation_gradient.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_lanes.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/hourglass.hpp"
#include "fem/hourglass_assumed_strain.hpp"

namespace afemp::fem {

namespace hexahedron_stage {
// Elements per pack of the one-point sweep: two AVX-512 or four AVX2 registers per array row.
inline constexpr int kLanes = 8;
// Thread slots: plastic work, bulk-viscous work, hourglass work, assumed-strain stabilisation.
inline constexpr std::size_t kPlastic = 0, kViscous = 1, kHourglass = 2, kStabilisation = 3;
}  // namespace hexahedron_stage

// The trial states of N integration points after the material pass, one array per field like
// the element arrays: what commit writes to them, and the terms of the work it books.
template <std::size_t N>
struct TrialPoints {
  std::array<core::SymTensor, N> stress;
  std::array<core::SymTensor, N> strain;  // the strain tensor (principal-strain failure only)
  double plastic_strain[N], temperature[N], energy[N], density[N], damage[N], burn[N];
  double history[N][core::largest_model_history<core::StrengthModel>];  // the model's own
  double plastic_work[N], q_heat[N];  // per unit mass: this step's, and the bulk-viscous heat
  double wave[N];                     // longitudinal wave speed at the trial state
};

// One element's trial state beside its points'.
struct TrialElement {
  double bulk_q = 0.0, critical_dt = 0.0;
  std::array<Vec3, 4> hourglass{};  // the hourglass form's state (HexElements::hourglass_force)
  double hourglass_power = 0.0;     // the viscous form's (HexElements::hourglass_power)
  // What commit books: the viscous form's work of the held forces at this step's velocities,
  // the stiffness form's work, or the assumed strain form's midpoint power.
  double hourglass_term = 0.0;
  const char* failure = nullptr;  // why the element cannot be updated (negative Jacobian)
  bool live = false;              // alive and updated
};

// A pack of W one-point elements, [component][node][lane] as in fem/hexahedron_lanes.hpp.
template <int W>
struct OnePointPack {
  std::size_t e0 = 0;  // its first element
  int n = 0;           // its elements (lanes past n repeat the last one)
  alignas(64) double x[3][8][W], v[3][8][W], c[3][8][W], bm[3][8][W], bn[3][8][W], f[3][8][W],
      grad[3][3][W], gamma[4][8][W], q[4][3][W], g[4][3][W], sigma[6][W];
  alignas(64) double vol_mid[W], vol[W], length[W], density[W];
  TrialPoints<W> point;
  std::array<TrialElement, W> element;
  std::array<std::size_t, W> slot{};  // a user model's chunk slot of each live lane
};

// One fully integrated element (B-bar, 8 points).
struct FullElement {
  std::size_t e = 0, p0 = 0;  // the element and its first point
  HexVectors x_new, x_mid, v, f;
  FullHex mid, now;
  double density = 0.0, trace_rate = 0.0, wave = 0.0;
  TrialPoints<8> point;
  TrialElement element;
};

template <class Strength, class Eos, bool Thermal, bool Fails>
class HexahedronPasses {
 public:
  static constexpr int W = hexahedron_stage::kLanes;
  static constexpr bool user = core::is_user_strength<Strength>;
  // A hyperelastic model reads each point's F, taken from the nodes (hexahedron_deformation_
  // gradient.hpp): at the centre of a one-point element, F-bar at the Gauss points of a full one.
  static constexpr bool reads_f = requires { Strength::reads_deformation_gradient; };
  using Pack = OnePointPack<W>;
  using UserChunk = core::UserChunkFor<Strength>;

  HexahedronPasses(FeSolver& fe, const ElementBatch& b, const Strength& strength, const Eos& eos,
                   double dt);

  // Thread t's share [begin, end) of the batch.
  void sweep_one_point(std::size_t begin, std::size_t end, int t) const;
  void sweep_full(std::size_t begin, std::size_t end, int t) const;

  // One-point passes, in this order, on the pack of the elements from e0 (below end).
  void gather(Pack& k, std::size_t e0, std::size_t end) const;
  void kinematics(Pack& k) const;
  [[gnu::flatten]] void material(Pack& k, UserChunk& chunk) const;
  void viscosity(Pack& k) const;
  void hourglass(Pack& k) const;
  void forces(Pack& k) const;
  void commit(const Pack& k, const UserChunk& chunk, double* sums) const;
  void check(const Pack& k, int t) const;

  // Fully integrated passes on element e.
  void gather(FullElement& k, std::size_t e) const;
  void kinematics(FullElement& k) const;
  void material(FullElement& k, UserChunk& chunk) const;
  void viscosity(FullElement& k) const;
  void forces(FullElement& k) const;
  void commit(const FullElement& k, const UserChunk& chunk, double* sums) const;

 private:
  // A point's update in two halves around the strength model (a user model runs between
  // them on the points of a whole element or pack): the start, its Jaumann-rotated state and
  // strain increment, then the end, written to slot j of the trial arrays; returns the wave
  // speed. update_point is both halves and the model between them, inlined into the
  // material pass, which is flattened so that the strength model's update is inlined too
  // (called out of line, it stalled on reloading the stress its caller had just stored: a
  // fifth of the point update's time, HEX-BLOCK under perf). The multiply-adds fuse as they did
  // when update_point was a function of its own (the same bits, checked on the FE examples).
  struct PointStart {
    core::PointState st;
    core::SymTensor d_eps;
    double q_heat = 0.0;
  };
  AFEMP_INLINE inline PointStart begin_point(std::size_t p, const core::Mat3& l, double density,
                                             double q_old, const core::Mat3* f = nullptr) const;
  template <std::size_t N>
  AFEMP_INLINE inline double end_point(TrialPoints<N>& out, std::size_t j, std::size_t p,
                                       PointStart& ps, const core::PointUpdate& u) const;
  template <std::size_t N>
  AFEMP_INLINE inline double update_point(TrialPoints<N>& out, std::size_t j, std::size_t p,
                                          const core::Mat3& l, double density, double q_old,
                                          const core::Mat3* f = nullptr) const;
  // The initial positions of element e's nodes (the reference of F).
  HexVectors initial_nodes(std::size_t e) const;
  void hourglass_viscous(Pack& k) const;
  void hourglass_stiffness(Pack& k, int l) const;
  void hourglass_assumed_strain(Pack& k, int l) const;
  template <std::size_t N>
  void commit_point(std::size_t p, const TrialPoints<N>& in, std::size_t j, double* sums) const;
  void commit_hourglass(std::size_t e, const TrialElement& te, double* sums) const;
  // After the forces f of element e: bad values, conversion, erosion, the forces stored.
  void check(std::size_t e, std::size_t p0, double volume, const char* failure, HexVectors& f,
             int t) const;
  void report(int t, std::size_t e, const std::string& detail, const char* field) const;

  FeSolver& fe_;
  HexElements& el_;
  const ElementBatch& b_;
  const core::BodySpec& body_;
  const core::Material& mat_;
  const Strength& strength_;
  const Eos& eos_;
  double dt_;
  // The force step of this step's nodal update, which the last update's forces acted over.
  double dt_force_;
  core::BulkViscositySettings viscosity_;
  core::HourglassForm hg_form_;
  double q_hg_;
  double hg_shear_;  // assumed strain: the shear modulus times the scene's coefficient
  const core::ErosionSettings* erosion_;
  const core::ConversionSettings* conversion_;
  // The retirement domain's Courant step for this material at rest, h / c (conversion's
  // time-step criterion).
  double grid_step_;
  bool principal_strain_;  // the failure model reads the strain tensor
  bool explosive_;         // burn fractions at the step's end (time_ is already there)
};

template <class S, class E, bool Thermal, bool Fails>
HexahedronPasses<S, E, Thermal, Fails>::HexahedronPasses(FeSolver& fe, const ElementBatch& b,
                                                         const S& strength, const E& eos, double dt)
    : fe_(fe),
      el_(fe.hexes_),
      b_(b),
      body_(fe.scene_.bodies[static_cast<std::size_t>(b.body)]),
      mat_(fe.scene_.materials[static_cast<std::size_t>(b.material)]),
      strength_(strength),
      eos_(eos),
      dt_(dt),
      dt_force_(fe.force_step(dt)),
      viscosity_(core::bulk_viscosity_of(fe.scene_, body_)),
      hg_form_(body_.hourglass.form),
      q_hg_(body_.hourglass.effective_coefficient()),
      hg_shear_(body_.hourglass.effective_coefficient() * mat_.shear_modulus()),
      erosion_(body_.erosion ? &*body_.erosion : nullptr),
      conversion_(body_.conversion ? &*body_.conversion : nullptr),
      grid_step_(conversion_
                     ? fe.retirement_.cell /
                           core::wave_speed(mat_, core::PointState{{}, 0.0, 0.0, 0.0, mat_.density})
                     : 0.0),
      principal_strain_(mat_.needs_strain()),
      explosive_(mat_.is_explosive()) {}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::sweep_one_point(std::size_t begin, std::size_t end,
                                                             int t) const {
  double* sums = &fe_.thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
  UserChunk chunk(mat_, strength_);
  Pack k{};  // zeros: lanes that never turn live still hold values
  for (std::size_t e0 = begin; e0 < end; e0 += W) {
    gather(k, e0, end);
    kinematics(k);
    material(k, chunk);
    viscosity(k);
    hourglass(k);
    forces(k);
    commit(k, chunk, sums);
    check(k, t);
  }
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::sweep_full(std::size_t begin, std::size_t end,
                                                        int t) const {
  double* sums = &fe_.thread_sums_[static_cast<std::size_t>(t) * core::cache_line_doubles];
  UserChunk chunk(mat_, strength_);
  FullElement k;
  for (std::size_t e = begin; e < end; ++e) {
    if (!el_.alive[e]) continue;
    gather(k, e);
    kinematics(k);
    if (k.element.live) {
      material(k, chunk);
      viscosity(k);
      forces(k);
    }
    commit(k, chunk, sums);
    check(e, k.p0, k.now.volume, k.element.failure, k.f, t);
  }
}

// ---- Points -------------------------------------------------------------------------------

template <class S, class E, bool Thermal, bool Fails>
auto HexahedronPasses<S, E, Thermal, Fails>::begin_point(std::size_t p, const core::Mat3& l,
                                                         double density, double q_old,
                                                         const core::Mat3* f) const -> PointStart {
  // The strain increment D dt and the spin increment W dt of the velocity gradient l.
  const double dt = dt_;
  const core::SymTensor d_eps = dt * core::sym_part(l);
  const double w23 = 0.5 * dt * (l.m[1][2] - l.m[2][1]), w13 = 0.5 * dt * (l.m[0][2] - l.m[2][0]),
               w12 = 0.5 * dt * (l.m[0][1] - l.m[1][0]);
  PointStart ps{core::PointState{el_.stress[p], el_.plastic_strain[p], el_.temperature[p],
                                 el_.energy[p], density},
                d_eps};
  // A failure model reads and writes any model's damage.
  if constexpr (core::has_damage_state<S> || Fails) ps.st.damage = el_.damage[p];
  ps.st.deformation_gradient = f;
  core::load_model_history<S>(ps.st, el_.history.data() + p * el_.history_count);
  ps.st.stress += core::jaumann_increment(ps.st.stress, w23, w13, w12);
  if (explosive_)
    ps.st.burn = core::burn_fraction(*mat_.burn, mat_.density, el_.burn[p], fe_.time_,
                                     el_.light_time[p], el_.burn_length[p], mat_.density / density);
  // Bulk-viscous heating by the q that acted over this step.
  ps.q_heat = core::bulk_viscous_heat(q_old, d_eps.trace(), density);
  return ps;
}

template <class S, class E, bool Thermal, bool Fails>
template <std::size_t N>
double HexahedronPasses<S, E, Thermal, Fails>::end_point(TrialPoints<N>& out, std::size_t j,
                                                         std::size_t p, PointStart& ps,
                                                         const core::PointUpdate& u) const {
  core::PointState& st = ps.st;
  st.energy += ps.q_heat;
  out.plastic_work[j] = u.plastic_work;
  out.q_heat[j] = ps.q_heat;
  out.stress[j] = st.stress;
  if (explosive_) out.burn[j] = st.burn;
  out.plastic_strain[j] = st.plastic_strain;
  out.temperature[j] = st.temperature;
  out.energy[j] = st.energy;
  out.density[j] = st.density;
  if constexpr (core::has_damage_state<S> || Fails) out.damage[j] = st.damage;
  core::store_model_history<S>(st, out.history[j]);
  if constexpr (Fails) {
    if (principal_strain_) {
      out.strain[j] = el_.strain[p] + ps.d_eps;
      out.damage[j] = core::principal_strain_damage(mat_.failure, out.damage[j], out.strain[j]);
    }
  }
  // The wave speed of the state the strength model left (before the strain's damage).
  return core::wave_speed(mat_, eos_, st);
}

template <class S, class E, bool Thermal, bool Fails>
template <std::size_t N>
double HexahedronPasses<S, E, Thermal, Fails>::update_point(TrialPoints<N>& out, std::size_t j,
                                                            std::size_t p, const core::Mat3& l,
                                                            double density, double q_old,
                                                            const core::Mat3* f) const {
  static_assert(!user, "user models take the chunk of material()");
  PointStart ps = begin_point(p, l, density, q_old, f);
  const core::PointUpdate u =
      core::constitutive_update<S, E, Fails>(mat_, strength_, eos_, Thermal, ps.st, ps.d_eps, dt_);
  return end_point(out, j, p, ps, u);
}

template <class S, class E, bool Thermal, bool Fails>
HexVectors HexahedronPasses<S, E, Thermal, Fails>::initial_nodes(std::size_t e) const {
  HexVectors x0;
  for (std::size_t a = 0; a < 8; ++a)
    x0[a] = fe_.nodes_.initial_position[static_cast<std::size_t>(el_.nodes[e][a])];
  return x0;
}

template <class S, class E, bool Thermal, bool Fails>
template <std::size_t N>
void HexahedronPasses<S, E, Thermal, Fails>::commit_point(std::size_t p, const TrialPoints<N>& in,
                                                          std::size_t j, double* sums) const {
  using namespace hexahedron_stage;
  HexElements& el = el_;
  fe_.book(sums, kPlastic, el.point_mass[p] * in.plastic_work[j]);
  fe_.book(sums, kViscous, el.point_mass[p] * in.q_heat[j]);
  if (!el.plastic_heat.empty()) {  // elements may erode (the same for every point)
    el.plastic_heat[p] += in.plastic_work[j];
    el.viscous_heat[p] += in.q_heat[j];
  }
  el.stress[p] = in.stress[j];
  if (explosive_) el.burn[p] = in.burn[j];
  el.plastic_strain[p] = in.plastic_strain[j];
  el.temperature[p] = in.temperature[j];
  el.energy[p] = in.energy[j];
  el.density[p] = in.density[j];
  if constexpr (core::has_damage_state<S> || Fails) el.damage[p] = in.damage[j];
  for (std::size_t h = 0; h < core::model_history_size<S>; ++h)
    el.history[p * el.history_count + h] = in.history[j][h];
  if constexpr (Fails) {
    if (principal_strain_) el.strain[p] = in.strain[j];
  }
}

// ---- One-point elements, a pack at a time --------------------------------------------------

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::gather(Pack& k, std::size_t e0,
                                                    std::size_t end) const {
  k.e0 = e0;
  k.n = static_cast<int>(std::min<std::size_t>(W, end - e0));
  // The next pack's nodes are fetched while this one is computed (the node arrays outgrow
  // the caches; the element stage waited on their loads 11 % of its time).
  if (e0 + 2 * W <= end) {
    for (int l = 0; l < W; ++l)
      for (int a = 0; a < 8; ++a) {
        const auto node =
            static_cast<std::size_t>(el_.nodes[e0 + W + static_cast<std::size_t>(l)][a]);
        __builtin_prefetch(&fe_.nodes_.position[node]);
        __builtin_prefetch(&fe_.nodes_.velocity[node]);
      }
  }
  // Lanes past the end repeat the last element; their results are dropped.
  for (int l = 0; l < W; ++l) {
    const std::size_t e = e0 + static_cast<std::size_t>(std::min(l, k.n - 1));
    for (int a = 0; a < 8; ++a) {
      const auto node = static_cast<std::size_t>(el_.nodes[e][static_cast<std::size_t>(a)]);
      const Vec3& xa = fe_.nodes_.position[node];
      const Vec3& va = fe_.nodes_.velocity[node];
      for (int i = 0; i < 3; ++i) {
        k.x[i][a][l] = xa[i];
        k.v[i][a][l] = va[i];
      }
    }
  }
}

// The b vectors at the mid-step geometry x - v dt/2 (the strain rate's) and at the end (the
// forces'), the velocity gradient, the length, the hourglass shapes and velocities, and which
// lanes are live.
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::kinematics(Pack& k) const {
  alignas(64) double xm[3][8][W];
  const double dt = dt_;
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 8; ++a)
      for (int l = 0; l < W; ++l) xm[i][a][l] = k.x[i][a][l] - 0.5 * dt * k.v[i][a][l];
  lanes::b_vectors<W>(xm, k.c, k.bm, k.vol_mid);
  lanes::b_vectors<W>(k.x, k.c, k.bn, k.vol);
  lanes::velocity_gradient<W>(k.bm, k.vol_mid, k.v, k.grad);
  lanes::characteristic_length<W>(k.x, k.vol, k.length);
  if (q_hg_ > 0.0) {
    lanes::hourglass_shapes<W>(k.c, k.bn, k.vol, k.gamma);
    lanes::hourglass_velocities<W>(k.gamma, k.v, k.q);
  }
  for (int l = 0; l < W; ++l) {
    const std::size_t e = k.e0 + static_cast<std::size_t>(l);
    TrialElement& te = k.element[l];
    const bool alive = l < k.n && el_.alive[e];
    te.live = alive && k.vol[l] > 0.0 && k.vol_mid[l] > 0.0;
    te.failure = alive && !te.live ? "negative Jacobian" : nullptr;
  }
}

namespace hexahedron_stage {
template <int W>
core::Mat3 lane_gradient(const OnePointPack<W>& k, int l) {
  core::Mat3 lg;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) lg.m[i][j] = k.grad[i][j][l];
  return lg;
}
}  // namespace hexahedron_stage

// The live lanes' trial states; a user model (afemp/user_material.hpp) runs once on them all,
// between the two halves of the update.
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::material(Pack& k, UserChunk& chunk) const {
  using hexahedron_stage::lane_gradient;
  if constexpr (user) {
    std::array<PointStart, W> pending;
    std::array<core::IncrementStart, W> starts;
    std::size_t count = 0;
    for (int l = 0; l < W; ++l) {
      if (!k.element[l].live) continue;
      const std::size_t e = k.e0 + static_cast<std::size_t>(l);
      const std::size_t p = b_.point_begin + (e - b_.begin);
      k.density[l] = el_.mass[e] / k.vol[l];
      PointStart& ps = pending[count];
      ps = begin_point(p, lane_gradient(k, l), k.density[l], el_.bulk_q[e]);
      starts[count] = core::start_increment<Fails>(mat_, ps.st, ps.d_eps, dt_);
      chunk.load(count, ps.st, starts[count], el_.history.data() + p * el_.history_count);
      k.slot[l] = count++;
    }
    if (count > 0) chunk.run(count, dt_);
    for (int l = 0; l < W; ++l) {
      if (!k.element[l].live) continue;
      const std::size_t j = k.slot[l];
      const std::size_t p = b_.point_begin + (k.e0 + static_cast<std::size_t>(l) - b_.begin);
      const core::PointUpdate u = core::finish_increment<E, Fails>(
          mat_, eos_, Thermal, pending[j].st, starts[j], chunk.deviator(j), chunk.result(j));
      k.point.wave[l] = end_point(k.point, static_cast<std::size_t>(l), p, pending[j], u);
    }
  } else {
    for (int l = 0; l < W; ++l) {
      if (!k.element[l].live) continue;
      const std::size_t e = k.e0 + static_cast<std::size_t>(l);
      k.density[l] = el_.mass[e] / k.vol[l];
      core::Mat3 f;
      if constexpr (reads_f) {
        HexVectors x;
        for (std::size_t a = 0; a < 8; ++a) x[a] = {k.x[0][a][l], k.x[1][a][l], k.x[2][a][l]};
        f = hexahedron_deformation_gradient(x, initial_nodes(e), 0.0, 0.0, 0.0);
      }
      k.point.wave[l] =
          update_point(k.point, static_cast<std::size_t>(l), b_.point_begin + (e - b_.begin),
                       lane_gradient(k, l), k.density[l], el_.bulk_q[e], reads_f ? &f : nullptr);
    }
  }
}

// Bulk-viscous pressure q, the critical step, and the stress the forces take, sigma - q I.
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::viscosity(Pack& k) const {
  for (int l = 0; l < W; ++l) {
    for (double(&s)[W] : k.sigma) s[l] = 0.0;
    if (!k.element[l].live) continue;
    const double trace_rate = k.grad[0][0][l] + k.grad[1][1][l] + k.grad[2][2][l];
    const core::ViscousState v =
        core::bulk_viscosity(viscosity_, k.density[l], k.length[l], trace_rate, k.point.wave[l]);
    TrialElement& te = k.element[l];
    te.bulk_q = v.q;
    te.critical_dt = k.length[l] / v.signal;
    const core::SymTensor& s = k.point.stress[static_cast<std::size_t>(l)];
    k.sigma[0][l] = s.xx - te.bulk_q;
    k.sigma[1][l] = s.yy - te.bulk_q;
    k.sigma[2][l] = s.zz - te.bulk_q;
    k.sigma[3][l] = s.yz;
    k.sigma[4][l] = s.xz;
    k.sigma[5][l] = s.xy;
  }
}

// The generalised hourglass forces g of the live lanes by the body's form.
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::hourglass(Pack& k) const {
  for (int m = 0; m < 4; ++m)
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < W; ++l) k.g[m][i][l] = 0.0;
  if (q_hg_ <= 0.0) return;
  if (hg_form_ == core::HourglassForm::viscous) return hourglass_viscous(k);
  for (int l = 0; l < W; ++l) {
    if (!k.element[l].live) continue;
    if (hg_form_ == core::HourglassForm::assumed_strain)
      hourglass_assumed_strain(k, l);
    else
      hourglass_stiffness(k, l);
  }
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::hourglass_assumed_strain(Pack& k, int l) const {
  const std::size_t e = k.e0 + static_cast<std::size_t>(l);
  TrialElement& te = k.element[l];
  HexVectors xe;
  lanes::store<W>(k.x, l, xe);
  std::array<Vec3, 4> qe, ge;
  for (int m = 0; m < 4; ++m) qe[m] = {k.q[m][0][l], k.q[m][1][l], k.q[m][2][l]};
  te.hourglass = el_.hourglass_force[e];
  te.hourglass_term =
      assumed_strain_hourglass_forces(assumed_strain_geometry(xe), k.vol[l], hg_shear_,
                                      mat_.poisson_ratio, dt_, qe, te.hourglass, ge);
  for (int m = 0; m < 4; ++m)
    for (int i = 0; i < 3; ++i) k.g[m][i][l] = ge[m][i];
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::hourglass_stiffness(Pack& k, int l) const {
  const std::size_t e = k.e0 + static_cast<std::size_t>(l);
  TrialElement& te = k.element[l];
  const double wave = k.point.wave[l];
  // The stored energy changes by (Q_old + Q_new)/2 . q dt (exactly Q^2 / 2 k_h for a
  // constant k_h); Q_new alone would be off by k_h q^2 dt^2 / 2 a step.
  double b_squared = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 8; ++a) b_squared += k.bn[i][a][l] * k.bn[i][a][l];
  const double k_h =
      stiffness_hourglass_factor(q_hg_, k.density[l] * wave * wave, b_squared, k.vol[l]);
  double work = 0.0;
  for (int m = 0; m < 4; ++m) {
    const Vec3 h_old = el_.hourglass_force[e][static_cast<std::size_t>(m)];
    Vec3& hk = te.hourglass[static_cast<std::size_t>(m)];
    const Vec3 qk{k.q[m][0][l], k.q[m][1][l], k.q[m][2][l]};
    hk = h_old;
    hk += (k_h * dt_) * qk;
    work += 0.5 * core::dot(h_old + hk, qk) * dt_;
    for (int i = 0; i < 3; ++i) k.g[m][i][l] = hk[i];
  }
  te.hourglass_term = work;
}

// The viscous form on every lane at once (its formulas run as loops over the lanes; dead
// lanes keep g = 0).
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::hourglass_viscous(Pack& k) const {
  // A mode's velocity decays at a rate a_h sum_a gamma_ka^2 / m_a. In a parallelepiped
  // sum_a gamma_ka^2 = 8; in an element far from one it is larger (27 in a random
  // element with a smallest scaled corner Jacobian of 0.05), and, explicit, the force
  // then reverses its mode within the step (in a steel plate a blunt projectile shears
  // a plug out of, the hourglass energy, then booked when the force was found, jumped
  // by 0.6 % of the total in ten steps, and the balance drifted by 1.7 %). The factor is
  // scaled so that no mode decays faster than twice as fast as in the parallelepiped
  // of its volume: regular meshes are untouched.
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
  alignas(64) double a_h[W], modes[W], held[4][3][W], done[W], power[W], live[W];
  for (int l = 0; l < W; ++l) {
    live[l] = k.element[l].live ? 1.0 : 0.0;
    const std::size_t e = k.e0 + static_cast<std::size_t>(l);
    for (int m = 0; m < 4; ++m)
      for (int i = 0; i < 3; ++i)
        held[m][i][l] =
            k.element[l].live ? el_.hourglass_force[e][static_cast<std::size_t>(m)][i] : 0.0;
  }
  // Dead lanes hold no material state of this pack: their factor and forces are zero.
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    const double f = viscous_hourglass_factor(q_hg_, k.density[l], k.point.wave[l], k.vol[l]);
    a_h[l] = live[l] != 0.0 ? f : 0.0;
  }
  for (int l = 0; l < W; ++l) modes[l] = 0.0;
  for (int m = 0; m < 4; ++m) {
    double sum[W] = {};
    for (int a = 0; a < 8; ++a)
#pragma omp simd
      for (int l = 0; l < W; ++l) sum[l] += k.gamma[m][a][l] * k.gamma[m][a][l];
    for (int l = 0; l < W; ++l) modes[l] = std::max(modes[l], sum[l]);
  }
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    if (modes[l] > 16.0) a_h[l] *= 16.0 / modes[l];
    done[l] = 0.0;
    power[l] = 0.0;
  }
  for (int m = 0; m < 4; ++m)
    for (int i = 0; i < 3; ++i)
#pragma omp simd
      for (int l = 0; l < W; ++l) {
        const double gk = a_h[l] * k.q[m][i][l];
        done[l] += held[m][i][l] * k.q[m][i][l];
        power[l] += gk * k.q[m][i][l];
        k.g[m][i][l] = live[l] != 0.0 ? gk : 0.0;  // a dead lane's q may be NaN
      }
  for (int l = 0; l < W; ++l) {
    TrialElement& te = k.element[l];
    if (!te.live) continue;
    for (int m = 0; m < 4; ++m)
      for (int i = 0; i < 3; ++i) te.hourglass[static_cast<std::size_t>(m)][i] = k.g[m][i][l];
    te.hourglass_term = done[l];
    te.hourglass_power = power[l];
  }
}

// f = -(sigma - q I) b_a - sum_k g_k gamma_k,a.
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::forces(Pack& k) const {
  lanes::stress_forces<W>(k.bn, k.sigma, k.f);
  if (q_hg_ > 0.0) lanes::subtract_hourglass_forces<W>(k.gamma, k.g, k.f);
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::commit_hourglass(std::size_t e, const TrialElement& te,
                                                              double* sums) const {
  using namespace hexahedron_stage;
  if (q_hg_ <= 0.0) return;
  if (hg_form_ == core::HourglassForm::assumed_strain) {
    fe_.book(sums, kStabilisation, dt_ * te.hourglass_term);
  } else if (hg_form_ == core::HourglassForm::stiffness) {
    fe_.book(sums, kHourglass, te.hourglass_term);
  } else {
    fe_.book(sums, kHourglass, 0.5 * dt_force_ * (el_.hourglass_power[e] + te.hourglass_term));
    el_.hourglass_power[e] = te.hourglass_power;
  }
  el_.hourglass_force[e] = te.hourglass;
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::commit(const Pack& k, const UserChunk& chunk,
                                                    double* sums) const {
  for (int l = 0; l < k.n; ++l) {
    const std::size_t e = k.e0 + static_cast<std::size_t>(l);
    if (!el_.alive[e]) continue;
    el_.volume[e] = k.vol[l];
    const TrialElement& te = k.element[l];
    if (!te.live) continue;
    const std::size_t p = b_.point_begin + (e - b_.begin);
    commit_point(p, k.point, static_cast<std::size_t>(l), sums);
    if constexpr (user) chunk.store_history(k.slot[l], el_.history.data() + p * el_.history_count);
    el_.bulk_q[e] = te.bulk_q;
    el_.critical_dt[e] = te.critical_dt;
    commit_hourglass(e, te, sums);
  }
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::check(const Pack& k, int t) const {
  const bool retires = conversion_ || erosion_;
  for (int l = 0; l < k.n; ++l) {
    const std::size_t e = k.e0 + static_cast<std::size_t>(l);
    if (!el_.alive[e]) continue;
    if (!retires && !k.element[l].failure) {
      // What check() below does for an element that can only be updated: the bad-value test
      // and the forces stored, read straight from the pack.
      const core::SymTensor& s = el_.stress[b_.point_begin + (e - b_.begin)];
      if (!std::isfinite(k.f[0][0][l] + k.f[1][0][l] + k.f[2][0][l]) ||
          !std::isfinite(s.xx + s.yy + s.zz + s.yz + s.xz + s.xy))
        report(t, e, "", "stress");
      for (int a = 0; a < 8; ++a)
        fe_.element_force_[8 * e + static_cast<std::size_t>(a)] =
            Vec3{k.f[0][a][l], k.f[1][a][l], k.f[2][a][l]};
      continue;
    }
    HexVectors fe;
    lanes::store<W>(k.f, l, fe);
    check(e, b_.point_begin + (e - b_.begin), k.vol[l], k.element[l].failure, fe, t);
  }
}

// ---- Fully integrated elements, one at a time ----------------------------------------------

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::gather(FullElement& k, std::size_t e) const {
  k.e = e;
  k.p0 = b_.point_begin + (e - b_.begin) * 8;
  for (std::size_t a = 0; a < 8; ++a) {
    const auto n = static_cast<std::size_t>(el_.nodes[e][a]);
    k.v[a] = fe_.nodes_.velocity[n];
    k.x_new[a] = fe_.nodes_.position[n];
    k.x_mid[a] = k.x_new[a] - (0.5 * dt_) * k.v[a];
  }
  k.f = HexVectors{};
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::kinematics(FullElement& k) const {
  k.mid = full_hex(k.x_mid);
  k.now = full_hex(k.x_new);
  k.element.live = min_jacobian(k.now) > 0.0 && min_jacobian(k.mid) > 0.0;
  k.element.failure = k.element.live ? nullptr : "negative Jacobian";
}

// The eight points' trial states with the B-bar velocity gradient; a user model runs once on
// the element's points.
template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::material(FullElement& k, UserChunk& chunk) const {
  k.density = el_.mass[k.e] / k.now.volume;  // B-bar: uniform dilatation
  k.wave = 0.0;
  const double q_old = el_.bulk_q[k.e];
  auto gradient = [&](std::size_t g) {
    const core::Mat3 l = velocity_gradient_bbar(k.mid, static_cast<int>(g), k.v);
    if (g == 0) k.trace_rate = l.m[0][0] + l.m[1][1] + l.m[2][2];
    return l;
  };
  if constexpr (user) {
    std::array<PointStart, 8> pending;
    std::array<core::IncrementStart, 8> starts;
    for (std::size_t g = 0; g < 8; ++g) {
      pending[g] = begin_point(k.p0 + g, gradient(g), k.density, q_old);
      starts[g] = core::start_increment<Fails>(mat_, pending[g].st, pending[g].d_eps, dt_);
      chunk.load(g, pending[g].st, starts[g], el_.history.data() + (k.p0 + g) * el_.history_count);
    }
    chunk.run(8, dt_);
    for (std::size_t g = 0; g < 8; ++g) {
      const core::PointUpdate u = core::finish_increment<E, Fails>(
          mat_, eos_, Thermal, pending[g].st, starts[g], chunk.deviator(g), chunk.result(g));
      k.wave = std::max(k.wave, end_point(k.point, g, k.p0 + g, pending[g], u));
    }
  } else {
    if constexpr (reads_f) {
      // F-bar: each point's F scaled to the element's volume ratio, as B-bar takes the
      // element's mean dilatation.
      const HexVectors x0 = initial_nodes(k.e);
      const double j_bar = k.now.volume / el_.volume0[k.e], r = 1.0 / std::sqrt(3.0);
      for (std::size_t g = 0; g < 8; ++g) {
        const double* n = kHexNatural[g];
        const core::Mat3 f = f_bar(
            hexahedron_deformation_gradient(k.x_new, x0, r * n[0], r * n[1], r * n[2]), j_bar);
        k.wave =
            std::max(k.wave, update_point(k.point, g, k.p0 + g, gradient(g), k.density, q_old, &f));
      }
    } else {
      for (std::size_t g = 0; g < 8; ++g)
        k.wave =
            std::max(k.wave, update_point(k.point, g, k.p0 + g, gradient(g), k.density, q_old));
    }
  }
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::viscosity(FullElement& k) const {
  const double length = characteristic_length(k.x_new, k.now.volume);
  const core::ViscousState v =
      core::bulk_viscosity(viscosity_, k.density, length, k.trace_rate, k.wave);
  k.element.bulk_q = v.q;
  k.element.critical_dt = length / v.signal;
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::forces(FullElement& k) const {
  std::array<core::SymTensor, 8> sigma;
  for (std::size_t g = 0; g < 8; ++g)
    sigma[g] = k.point.stress[g] - k.element.bulk_q * core::SymTensor::identity();
  add_stress_forces_bbar(k.now, sigma, k.f);
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::commit(const FullElement& k, const UserChunk& chunk,
                                                    double* sums) const {
  el_.volume[k.e] = k.now.volume;
  if (!k.element.live) return;
  for (std::size_t g = 0; g < 8; ++g) {
    commit_point(k.p0 + g, k.point, g, sums);
    if constexpr (user) chunk.store_history(g, el_.history.data() + (k.p0 + g) * el_.history_count);
  }
  el_.bulk_q[k.e] = k.element.bulk_q;
  el_.critical_dt[k.e] = k.element.critical_dt;
}

// ---- Checks --------------------------------------------------------------------------------

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::report(int t, std::size_t e, const std::string& detail,
                                                    const char* field) const {
  const auto i = static_cast<std::size_t>(t);
  if (!fe_.thread_errors_[i].empty()) return;  // the thread's first bad value
  fe_.thread_errors_[i] =
      "hexahedron " + std::to_string(e - b_.begin) + " of body " + body_.name + detail;
  fe_.thread_error_field_[i] = field;
}

template <class S, class E, bool Thermal, bool Fails>
void HexahedronPasses<S, E, Thermal, Fails>::check(std::size_t e, std::size_t p0, double volume,
                                                   const char* failure, HexVectors& f,
                                                   int t) const {
  const auto ti = static_cast<std::size_t>(t);
  const int points = b_.points_per_element;
  if (!failure) {
    bool bad = !std::isfinite(f[0].x + f[0].y + f[0].z);
    for (int g = 0; g < points; ++g) {
      const core::SymTensor& s = el_.stress[p0 + static_cast<std::size_t>(g)];
      bad = bad || !std::isfinite(s.xx + s.yy + s.zz + s.yz + s.xz + s.xy);
    }
    if (bad) report(t, e, "", "stress");
  }
  // Conversion first (AFEMP): an element inside the grid that meets a criterion, or inverts
  // with negative_jacobian on, becomes particles; outside the grid erosion still applies.
  if (conversion_ && (!failure || conversion_->negative_jacobian) &&
      fe_.inside_retirement_domain(e)) {
    const char* reason =
        failure ? failure : fe_.conversion_reason(*conversion_, b_, e, volume, grid_step_);
    if (reason) {
      fe_.thread_conversions_[ti].push_back(e);
      fe_.thread_conversion_reason_[ti].push_back(reason);
      for (std::size_t a = 0; a < 8; ++a) fe_.element_force_[8 * e + a] = Vec3{};
      return;
    }
  }
  if (erosion_ && !failure) {
    double eps_p = 0.0, damage = 0.0;
    for (int g = 0; g < points; ++g) {
      eps_p = std::max(eps_p, el_.plastic_strain[p0 + static_cast<std::size_t>(g)]);
      damage = std::max(damage, el_.damage[p0 + static_cast<std::size_t>(g)]);
    }
    failure = core::erosion_reason(*erosion_, mat_, eps_p, volume, el_.volume0[e],
                                   el_.critical_dt[e], damage);
  }
  if (failure) {
    if (!erosion_) {
      // With conversion on inversion the element got here only by lying outside the grid.
      report(t, e,
             conversion_ && conversion_->negative_jacobian
                 ? " (outside the background grid, where it cannot convert)"
                 : "",
             "jacobian");
      return;
    }
    fe_.thread_erosions_[ti].push_back(e);
    fe_.thread_failure_[ti].push_back(failure);
    for (HexVectors::size_type a = 0; a < 8; ++a) f[a] = Vec3{};
  }
  for (std::size_t a = 0; a < 8; ++a) fe_.element_force_[8 * e + a] = f[a];
}

}  // namespace afemp::fem
