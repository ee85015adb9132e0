// The explicit MPM solver: particles on the background grid, advanced one step at a time by
// the stages of its StepPlan (Ma 2005, §2.2.4; Lian et al. 2013, §2.1 for USF / USL / MUSL).
// The stage kernels live in files named after them: particle_binning.cpp,
// particle_to_grid.cpp, grid_momentum_update.cpp, grid_to_particle.cpp, stress_update.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "afemp/energies.hpp"
#include "afemp/run.hpp"
#include "core/exact_sum.hpp"
#include "core/grid/background_grid.hpp"
#include "core/grid/block_partition.hpp"
#include "core/rank_link.hpp"
#include "core/scene.hpp"
#include "mpm/absorbing_faces.hpp"
#include "mpm/axisymmetric.hpp"
#include "mpm/contact_nodes.hpp"
#include "mpm/grid_points.hpp"
#include "mpm/particles.hpp"
#include "mpm/stencil.hpp"
#include "mpm/step_plan.hpp"

namespace afemp::core {
class StateArchive;
}

namespace afemp::mpm {

using core::BodySums;
using core::Energies;

// A contiguous range of particles of one material.
struct MaterialBatch {
  int material;
  std::size_t begin, end;
};

class MpmSolver {
 public:
  // Particles of one material are made contiguous here (the order changes; ids do not).
  MpmSolver(const core::Scene& scene, Particles particles);
  // The solver keeps a reference to the scene: a temporary one would dangle.
  MpmSolver(core::Scene&&, Particles) = delete;

  const StepPlan& plan() const { return plan_; }
  const Particles& particles() const { return particles_; }
  // For drivers and tests that set a state the scene cannot express (a velocity field).
  Particles& mutable_particles() { return particles_; }
  const core::BackgroundGrid& grid() const { return grid_; }
  long step_count() const { return steps_; }
  double time() const { return time_; }
  // Before the first step: the clock starts at `time` (a static phase ran the meshes to it,
  // holding the particles).
  void set_clock(double time) { time_ = time; }
  // Every particle of body `body` moves at v, with no affine (APIC) part.
  void set_body_velocity(int body, const Vec3& v);

  // Stable step: factor * h / (max_p c_p + max_p |v_p|), or the scene's fixed step.
  double stable_time_step() const;
  // The particle with the largest c_p + |v_p|, which bounds that step: its id, body and
  // position, both speeds and the cell, for the run summary (core::Model::time_step_setter). On
  // ranks (collective): the fastest of every rank's, the same text on every rank.
  std::string time_step_setter() const;
  // Advances by dt running each stage of the plan once. Throws core::SimulationError naming
  // the step, particle and field when a value becomes NaN/Inf or a particle leaves the grid.
  void step(double dt);
  // Multiplies the particles' velocities, and with APIC their affine velocities, by factor
  // (core::Model::scale_velocities); the grid is built again from them each step.
  void scale_velocities(double factor);
  // Energies and per-body sums of the current state (ordered reduction: same bits for a
  // given thread count).
  Energies energies() const;
  // How many times each stage of the plan has run, and the wall seconds spent in it, in plan
  // order; the reordering of particles for locality is counted apart.
  const std::vector<long>& stage_counts() const { return stage_counts_; }
  const std::vector<double>& stage_seconds() const { return stage_seconds_; }
  double reorder_seconds() const { return reorder_seconds_; }
  // Particles that have left through outflow faces so far.
  long outflow_count() const { return outflow_count_; }
  // Particles split so far (each split of one particle, into 2, 4 or 8, counts once).
  long split_count() const { return split_count_; }
  // Each [[walls]] entry's force on the particles over the last step (0 for a wall that
  // names no particle body), as the history's wallK columns report it.
  const std::vector<Vec3>& wall_forces() const { return wall_force_; }
  // Each grid [[contact]]'s force on its first body over the last step (the update pass's
  // impulses over dt), split into its normal and tangential parts (summed over the contact
  // nodes, each along its own normal), in the scene's order of grid contacts.
  struct InterfaceForce {
    Vec3 normal, tangential;
  };
  const std::vector<InterfaceForce>& grid_contact_forces() const { return grid_contact_force_; }
  // Points that join the grid step from now on (grid_points.hpp; coupling/ puts FE nodes on
  // the grid this way). nullptr: none. Throws std::invalid_argument with the USL scheme.
  void set_grid_points(GridPoints* points);
  // Contacts resolved on the updated grid velocity after the particle walls (grid_points.hpp);
  // nullptr: none. The plan runs that stage when the scene has a surface contact.
  void set_surface_contacts(SurfaceContacts* contacts) { surface_contacts_ = contacts; }
  // Appends particles made during the run (hexahedra converted into particles, coupling/):
  // their ids continue after the largest so far, the arrays the scene asks for are filled as
  // each field's AddRule says (particles.hpp: what `more` holds is carried, the solver sets the
  // uGIMP half width and the lengths), and the material batches are rebuilt. On ranks
  // (collective) every rank passes the same particles and keeps those of its own blocks.
  void add_particles(const Particles& more);
  // The grid's stable step for points moving at `speed` (the scene's factor applied).
  double stable_time_step_for_speed(double speed) const {
    return scene_.run.time_step_factor * grid_.cell() / speed;
  }
  // Bins the particles and activates their grid blocks without advancing, so that
  // active_cells() and bytes() describe the first step (`afemp check`).
  void prepare() { bin_particles(); }
  // Saves or restores the solver's state (a checkpoint, core/state_archive.hpp; mpm_state.cpp).
  // Restoring needs a solver built from the same scene. On ranks the checkpoint is one
  // process's: saving writes what prepare_checkpoint() gathered (rank 0's file is the one that
  // counts), and restoring reads every particle on every rank and divides them anew, by a
  // partition of their present positions, among this run's ranks, however many wrote it.
  void state(core::StateArchive& archive);
  // Before state() saves on ranks (collective): every rank's particles gathered onto rank 0 in
  // id order, the accumulators summed in rank order, the signal speed's two parts' maxima.
  void prepare_checkpoint();
  // Divides the run among the ranks of `link` (core/rank_link.hpp; mpm/domain_decomposition.cpp).
  // Collective. The particles this solver was built with must be the whole run's, the same on
  // every rank (a scene's generation): the grid blocks that hold particles are split by
  // recursive coordinate bisection weighted by their particles (core/grid/block_partition.hpp)
  // and each rank keeps the particles of its blocks. From then on every scatter is followed by
  // the shared blocks' sums, the particles whose block has another rank move to it after each
  // step, the stable step is the smallest over the ranks and energies() sums in rank order.
  // Throws std::invalid_argument, on every rank alike, for more ranks than blocks that hold
  // particles.
  // `balance` says how the ranks' loads are kept even as the material moves (afemp/run.hpp).
  void divide_among_ranks(core::RankLink& link, const core::RankBalance& balance = {});
  bool on_ranks() const { return ranks_ != nullptr; }
  // On ranks: how many particles the ranks hold together (only conversion adds any, on every
  // rank alike; no stage that divides removes any).
  std::size_t whole_particle_count() const { return whole_count_; }
  const core::BlockPartition& partition() const { return partition_; }
  // Wall seconds spent summing shared blocks and moving particles between ranks, and the
  // particles this rank has sent to others so far.
  double rank_seconds() const { return rank_seconds_; }
  long particles_sent() const { return particles_sent_; }
  // Of those, the seconds moving particles after the steps (rebalances apart); the rebalances
  // made and their seconds (the costs compared at each check, the partition, the moves); the
  // slowest rank's cost over the mean at the last check (0 before one).
  double migration_seconds() const { return migration_seconds_; }
  long rebalances() const { return rebalances_; }
  double balance_seconds() const { return balance_seconds_; }
  // Every rank's particles in id order, on rank 0 alone or on every rank (collective); off ranks,
  // this process's particles in id order. For output and the end-of-run measures, not for steps.
  Particles gathered_particles(bool on_every_rank) const;
  // Every rank's `values` (the same length on each), one after the other in rank order, on every
  // rank (collective); off ranks, `values` itself.
  std::vector<double> values_of_every_rank(std::span<const double> values) const;
  // Active grid cells of the last binning.
  std::size_t active_cells() const;
  // Bytes held by particles, grid and solver scratch.
  std::size_t bytes() const;

 private:
  // Stages (one file each).
  void bin_particles();
  void particle_to_grid(bool mass_momentum, bool force);
  void grid_velocity();
  void grid_momentum_update(double dt);
  void grid_to_particle(double dt, bool move_positions);
  void remap_to_grid();
  // [[loads]] on particles (particle_loads.cpp): marks the particles each load's box holds,
  // adds their forces N_I f_p to the nodes after the internal force, and books their work at
  // the nodes' mean velocity over the step once the grid is updated.
  void setup_particle_loads();
  void add_particle_loads();
  void book_particle_load_work(double dt);
  // The largest component of the force particle i's load gives it now (0 without one): the
  // reproducible mode's force bound (reproducible_sums.cpp).
  double largest_particle_load(std::size_t i) const;
  // Grid contact (grid_contact.cpp): each contact field's normal and reach at the nodes it
  // shares, then the correction of one nodal velocity field.
  void contact_surfaces();
  void grid_contact(ContactPass pass);
  template <class Stencil>
  void contact_surfaces_kernel();
  // Offset of particle i's velocity field in the nodal arrays (0 with a single field).
  std::size_t field_offset(std::size_t i) const {
    return multi_field_ ? static_cast<std::size_t>(
                              field_of_body_[static_cast<std::size_t>(particles_.body[i])]) *
                              grid_.slot_count()
                        : 0;
  }
  // The kernels behind them, one instance per shape function and transfer (defined and
  // instantiated in the stage's file).
  // Exact: the reproducible mode's fixed-point sums (reproducible_sums.cpp), a kernel of its own
  // so that the plain one keeps its loop.
  template <class Stencil, bool Affine, bool MassMomentum, bool Force, bool Gravity, bool Exact>
  void p2g_kernel();
  template <class Stencil, bool Affine, bool Exact>
  void remap_kernel();
  template <class Stencil, bool Affine>
  void g2p_kernel(double dt, bool move_positions);
  // Which part of the step's strain increment a stress update takes (USAVG splits it).
  enum class StrainPart { whole, start_half, end_half };
  // Which nodal velocities a strain sweep reads, what else it updates, and over what time.
  struct StrainSweep {
    const Vec3* strain_velocity = nullptr;  // USF, USAVG start: v^k; USL: v^{k+1}; else remapped
    bool move = false;                      // USL, MUSL, USAVG end: x += dt sum N v^{k+1}
    bool flip_update = false;               // USL: the particle velocity update of G2P
    double strain_dt = 0.0;                 // the strain increment is strain_dt sym(L)
    double time_after = 0.0;                // the time the updated state belongs to
  };
  template <class Stencil, bool Affine>
  void kinematics_kernel(double dt, const StrainSweep& sweep);
  // Mixed u-p (mpm/mixed_pressure.cpp): mixed_pressure_ from det F over the reference grid;
  // Constant: one pressure per cell (under the linear hat), else the linear hat.
  void project_mixed_pressure();
  template <int Colours, bool Constant>
  void mixed_pressure_kernel();
  // Calls f.template operator()<Stencil, Affine>() for the scene's shape function, form and
  // transfer: the total-Lagrangian form reads its stencil over the reference configuration
  // (ReferenceStencil), and the affine transfer is taken by every stencil but the linear hat
  // and CPDI (the parser refuses it with them, and CPDI with the total-Lagrangian form, so
  // neither combination is instantiated).
  template <class F>
  void with_stencil(F&& f) {
    const bool affine = plan_.transfer == core::Transfer::apic;
    with_shape(plan_.shape, [&]<class Stencil>() {
      constexpr bool cpdi = requires {
        Stencil::tracks_corners;
      };
      constexpr bool takes_affine = !cpdi && !std::is_same_v<Stencil, LinearStencil>;
      const auto run = [&]<class S>() {
        if constexpr (takes_affine)
          if (affine) {
            f.template operator()<S, true>();
            return;
          }
        f.template operator()<S, false>();
      };
      if (!plan_.total_lagrangian)
        run.template operator()<Stencil>();
      else if constexpr (!cpdi)
        run.template operator()<ReferenceStencil<Stencil>>();
    });
  }
  // Turns a nodal momentum field into velocity (when divide_by_mass) and zeroes the
  // components the face conditions constrain.
  void apply_velocity_conditions(std::vector<Vec3>& field, bool divide_by_mass);
  void strain_stress_update(double dt, StrainPart part);
  // CPDI: stops the run at the first particle whose domain is inside out or reaches past its
  // stencil (particle_binning.cpp).
  void check_domains() const;
  void check_deformation_gradients() const;
  // What the grid points' owner may read and write during a stage (grid_points.hpp).
  GridStepAccess access();
  // One thread's pass over a material batch (stress_update.cpp).
  template <class Strength, class Eos, bool Thermal, bool Fused, bool Fails>
  struct StressPass;
  template <class Strength, class Eos, bool Thermal, bool Fused, bool Fails>
  void strain_stress_batch(const MaterialBatch& batch, const Strength& strength, const Eos& eos,
                           double dt, const StrainSweep& sweep, int thread_slot_offset);
  void reorder_particles();
  // On ranks (domain_decomposition.cpp): the shared blocks' sums of the given nodal arrays
  // after a scatter (which also mark the blocks this rank books, owned_block_), and the
  // particles sent to the rank of their block after a step.
  // The particles this process holds, every rank's, divided among the ranks of ranks_ by the
  // recursive bisection of the blocks that hold them (a partition made anew, the same on every
  // rank): this rank keeps its own, in their present order, and the material batches, the
  // cell order and the signal speed's parts are its own.
  void keep_own_particles();
  // Every balance.every steps on ranks: each rank's cost since the last check compared with the
  // mean over the ranks, and above balance.imbalance times it the blocks split anew by their
  // costs and the particles moved (domain_decomposition.cpp).
  void balance_ranks();
  void sum_shared_blocks(std::span<const core::NodalArray> arrays);
  // The reproducible mode ([run] reproducible; mpm/reproducible_sums.cpp): which scatter is
  // summed in fixed point; its scales from bounds on this step's terms agreed over the ranks,
  // and its arrays cleared; then the shared blocks' sums of the fixed-point arrays and the
  // grid's doubles made from them (a term past its bound stops the run).
  enum class FixedScatter { mass_momentum_force, mass_momentum, force, remap, gradient };
  void start_fixed_scatter(FixedScatter what);
  void finish_fixed_scatter(FixedScatter what);
  // Stops every rank where a fixed-point term passed its bound on any (`passed`: 0 none, 1 a
  // particle's, 2 a mesh node's), naming the sums, the array and what ran away
  // (reproducible_sums.cpp).
  void stop_past_fixed_bound(int passed, const char* sums, const char* array,
                             const char* runaway) const;
  bool reproducible() const { return scene_.run.reproducible; }
  // Per-thread exact sums of a stage, `per` of them a thread, cleared.
  core::ExactSum* exact_thread_sums(std::size_t per);
  // Each thread's first `per` exact sums added into `into` (per of them).
  void add_exact_thread_sums(std::size_t per, core::ExactSum* into);
  Energies reproducible_energies() const;
  // Particle i's kinetic energy, its affine velocity's (APIC) included.
  double particle_kinetic_energy(std::size_t i, bool affine) const;
  void migrate_particles();
  // Whether this rank books the node of `slot`: its nodal sums (external work) are booked by
  // one rank only, the block's owner, or the lowest rank holding it where the owner holds none
  // of it (set by each shared sum, core/mpi/shared_block_sums.hpp; the first of a step, P2G's,
  // comes before any node is booked).
  bool books_node(std::size_t slot) const {
    return owned_block_.empty() || owned_block_[slot / core::BackgroundGrid::block_nodes] != 0;
  }
  // The material batches from the particles' order (materials contiguous).
  void rebuild_batches();
  // Per-particle data made from a particle's volume, the same at the start, for particles
  // added from elements and for the pieces of a split: uGIMP's half width (the cube of the
  // volume, at most one cell) and, with splitting, its initial lengths; and the id that
  // follows the largest so far.
  double gimp_half_width(double volume) const {
    return std::min(0.5, particle_half_width(volume) * grid_.inverse_cell());
  }
  // CPDI: particle i's domain starts as the cube of its volume around it (core/grid/cpdi.hpp).
  void start_domain(std::size_t i) {
    Particles& p = particles_;
    const double a = particle_half_width(p.volume[i]);
    if (!p.domain.empty()) {
      p.domain[i] = core::Mat3{};
      for (int k = 0; k < 3; ++k) p.domain[i].m[k][k] = a;
    }
    if (!p.corners.empty())
      for (int c = 0; c < 8; ++c)
        p.corners[i][static_cast<std::size_t>(c)] = p.position[i] + a * core::cpdi_corner_sign(c);
  }
  // Where a particle's weights are taken: its reference position (total-Lagrangian) or its
  // current one.
  const std::vector<Vec3>& weight_positions() const {
    return plan_.total_lagrangian ? particles_.reference_position : particles_.position;
  }
  // The linear hat's kinematics run inside the constitutive loop (stress_update.cpp); the other
  // stencils, and every total-Lagrangian one, in a pass of their own.
  bool fused_kinematics() const {
    return plan_.shape == core::ShapeFunction::linear && !plan_.deformation_gradient;
  }
  static core::Mat3 identity_matrix() {
    core::Mat3 i;
    for (int a = 0; a < 3; ++a) i.m[a][a] = 1.0;
    return i;
  }
  // Particle i's edge (mpm/axisymmetric.hpp).
  double particle_edge(std::size_t i) const {
    return mpm::particle_edge(particles_.volume[i], particles_.position[i], axisymmetric_);
  }
  void start_lengths(std::size_t i) {
    const double l = particle_edge(i);
    particles_.length[i] = particles_.length0[i] = Vec3{l, l, l};
  }
  std::int32_t next_particle_id() const;
  void setup_explosives();
  // Outflow faces (outflow.cpp): whether a position lies beyond the grid through outflow
  // faces, past no face that stops the run (one that returns particles does not count), and
  // the removal of such particles at the start of a step.
  bool left_through_outflow(const Vec3& x) const;
  void remove_outflow();
  // Particles carried past a symmetric face are mirrored back, past a far-field face put back
  // on its plane (face_crossings.cpp), at the start of binning; whether face f (xmin, xmax,
  // ...) returns them so (never in the total-Lagrangian form, whose grid does not move).
  void return_particles_past_faces();
  bool returns_past_face(std::size_t f) const;
  // Absorbing faces (absorbing_faces.cpp): their wave speeds from the material that meets
  // each; throws core::InputError naming the face if none or several.
  void setup_absorbing_faces();
  // A far-field node's update on the faces in `faces` (bits; absorbing_faces.hpp) for velocity
  // field `field`: its normal components of v_new and its lags; returns the work.
  double far_field(const std::array<int, 3>& node, int field, unsigned faces, double m, double dt,
                   const Vec3& v, Vec3& v_new);
  // Where the lag of `node` and `field` on far-field face `face` lies in far_lag_[face].
  std::size_t far_lag_index(int face, const std::array<int, 3>& node, int field) const;
  // On ranks, after the momentum update: each far-field lag taken from the rank that books its
  // node, so that every rank keeps every node's lag as one process does (the lag is a node's
  // state from step to step, and a rank may hold a node in one step and not the next).
  void share_far_field_lags();
  // Splitting (particle_splitting.cpp): particles whose length along an axis reached 2 alpha
  // times their initial length split along those axes.
  void split_particles();
  // Rigid walls met at the particles' boundary (particle_wall_contact.cpp).
  void particle_wall_contact(double dt);
  template <class Stencil>
  void particle_wall_kernel(std::size_t wall, double dt);
  void raise_if_bad(const char* field) const;
  // max_p c_p + max_p |v_p| over this process's particles; max_signal_parts sets the two parts
  // as well.
  double max_signal_speed() const;
  double max_signal_parts();

  const core::Scene& scene_;
  StepPlan plan_;
  Particles particles_;
  core::BackgroundGrid grid_;
  std::vector<MaterialBatch> batches_;
  std::vector<const core::Material*> materials_;

  // Binning scratch: cell per particle, colour layers (counting sort along sweep_axis_).
  std::vector<std::int64_t> cell_;
  std::vector<std::int32_t> layer_;
  std::vector<std::int32_t> layer_order_;
  std::vector<std::int64_t> layer_offsets_;
  std::vector<std::int64_t> scratch_offsets_;
  int sweep_axis_ = 2;
  // uGIMP, B-splines: the velocity gradient of each particle, from kinematics_kernel to the
  // stress update.
  std::vector<core::Mat3> velocity_gradient_;
  // Mixed u-p: each particle's projected pressure p_p (tension positive), read by its material
  // in place of K (J - 1); and the nodal sums of the projection (3 per node slot).
  std::vector<double> mixed_pressure_;
  std::vector<double> pressure_nodes_;
  // The reproducible mode's: the same three sums in fixed point, and each particle's load
  // K V0 (Jbar - 1), whose bound sets the third's scale (mixed_pressure.cpp).
  std::vector<core::Fixed> pressure_fixed_;
  std::vector<double> pressure_load_;

  // Velocity fields: the field of each body, and what happens where fields f and g meet at
  // a node (law_[f * fields + g]): they stick (one velocity, as in a single field) unless the
  // scene put their bodies in contact.
  struct PairLaw {
    bool contact = false;
    double friction = 0.0;
    double distance_factor = 0.5;
  };
  std::vector<int> field_of_body_;
  std::vector<PairLaw> law_;
  std::vector<char> field_in_contact_;  // the field meets some field it is in contact with
  bool multi_field_ = false;
  std::vector<Vec3> contact_normal_;        // unit normal of each field at its contact nodes, or 0
  std::vector<std::uint8_t> contact_node_;  // per slot: where normals are needed (grid_contact.cpp)
  double contact_energy_ = 0.0;  // kinetic energy the contact took out (Energies::contact)
  // Per field pair (f * fields + g): the grid contact it belongs to, +1 + k when f carries
  // contact k's first body, -1 - k when g does, 0 for none; its force and per-thread sums.
  std::vector<int> contact_of_pair_;
  std::vector<InterfaceForce> grid_contact_force_;
  std::vector<InterfaceForce> contact_force_scratch_;
  // Points that join the grid step (grid_points.hpp), and the velocity change grid contact
  // made to each field at each slot in the update pass (what self-updating points receive);
  // field_self_updated_: the field holds self-updating points only, whose gravity work their
  // owner counts.
  GridPoints* points_ = nullptr;
  SurfaceContacts* surface_contacts_ = nullptr;
  std::vector<Vec3> contact_change_;
  std::vector<char> field_self_updated_;
  // Self-updating points in a field shared with particles (grid_points.hpp).
  SelfUpdatedShare shared_;
  // Adds the shifts of shared_ to the grid velocities after contact (grid_to_particle.cpp).
  void apply_shared_shifts();
  double step_dt_ = 0.0;

  // Wall-face components constrained at each grid slot by this step's momentum update
  // (bit a: component a), reused for the MUSL remapped velocity (see remap_to_grid).
  std::vector<std::uint8_t> wall_contact_;

  // Artificial bulk viscosity of each body's particles (core::BodySpec::bulk_viscosity;
  // core/bulk_viscosity.hpp), and whether any body has it.
  std::vector<core::BulkViscositySettings> bulk_viscosity_;
  bool viscous_ = false;
  // The axisymmetric form ([grid] axisymmetric; mpm/axisymmetric.hpp): the hoop terms in the
  // internal force and the strain rate.
  bool axisymmetric_ = false;

  // Outflow faces (xmin, xmax, ymin, ymax, zmin, zmax), and what left through them.
  std::array<bool, 6> outflow_{};
  // Per scene body: whether its particles split ([mpm] splitting, its `bodies`).
  std::vector<char> splits_;
  std::array<AbsorbingFace, 6> absorbing_{};  // per face (xmin, xmax, ...)
  // Far-field faces: the lag w of each node on the face plane, per velocity field
  // (field-major, then the two other axes in cyclic order); empty for the other faces.
  std::vector<std::vector<double>> far_lag_ = std::vector<std::vector<double>>(6);
  // On ranks: the lags and their flags summed over the ranks each step (share_far_field_lags),
  // kept between steps so that the step allocates nothing.
  std::vector<double> far_lag_shared_;
  // A far field's ambient pressure: taken off the stress in the internal force (gauge), or
  // applied to the far-field faces' nodes as a static traction (absolute); 0 where unused.
  double ambient_pressure_ = 0.0, face_pressure_ = 0.0;
  double outflow_mass_ = 0.0, outflow_energy_ = 0.0;
  Vec3 outflow_momentum_{};
  long outflow_count_ = 0;
  long split_count_ = 0;  // splits so far (one particle into 2, 4 or 8 counts once)
  // [[loads]] on particles: per load (1 + its index is Particles::load), the force per unit
  // mass at factor 1, F / M over the mass M its particles start with.
  std::vector<Vec3> load_acceleration_;

  // Particle walls: per scene wall, the bodies it acts on (empty: none of this solver's), its
  // force over the last step; the work of their impulses (Energies::sliding, friction); the
  // contacts of one wall (each candidate's gap at the step's start, its inverse mass and
  // impulses, with its stencil's nodes; on ranks every rank's).
  std::vector<std::vector<char>> wall_bodies_;
  std::vector<Vec3> wall_force_;
  double wall_sliding_ = 0.0, wall_friction_ = 0.0;
  struct WallContact {
    std::int64_t id = 0;
    double gap = 0.0, inverse_mass = 0.0, normal_impulse = 0.0;
    Vec3 tangent_impulse;
  };
  ContactNodes<WallContact> wall_contacts_;
  std::vector<std::int64_t> wall_slots_;
  std::vector<double> wall_weights_;

  // The ranks the run is divided among (nullptr: this process runs all of it), the blocks'
  // owners, and per active block whether this rank owns it (empty off ranks).
  core::RankLink* ranks_ = nullptr;
  core::BlockPartition partition_;
  std::vector<char> owned_block_;
  double rank_seconds_ = 0.0;
  long particles_sent_ = 0;
  std::size_t whole_count_ = 0;
  core::RankBalance balance_{};
  double sum_seconds_ = 0.0, migration_seconds_ = 0.0, balance_seconds_ = 0.0;
  long rebalances_ = 0;
  // The stage seconds and shared-sum seconds at the last check (a rank's cost is the change).
  double balance_stage_mark_ = 0.0, balance_sum_mark_ = 0.0;
  // What prepare_checkpoint() gathered for state() to save (on rank 0: every particle).
  struct RankCheckpoint {
    Particles whole;
    double plastic_work = 0.0, viscous_work = 0.0, external_work = 0.0, contact_energy = 0.0;
    double signal_wave = 0.0, signal_flow = 0.0;
    double outflow_mass = 0.0, outflow_energy = 0.0;
    Vec3 outflow_momentum;
    long outflow_count = 0, split_count = 0;
    bool ready = false;
  } rank_checkpoint_;

  // The reproducible mode: the grid's nodal sums in fixed point (grid_points.hpp), each thread's
  // flag that no term passed its bound; this rank's running energies summed exactly (the doubles
  // below are kept too), and the threads' exact sums of a stage.
  using FixedNodes = FixedGridSums;
  FixedNodes fixed_;
  std::vector<char> fixed_ok_;
  // The works, then what the outflow faces took (mass, energy, momentum).
  enum ExactEntry : std::size_t {
    exact_plastic,
    exact_viscous,
    exact_external,
    exact_contact,
    exact_outflow_mass,
    exact_outflow_energy,
    exact_outflow_momentum  // x, y, z
  };
  std::array<core::ExactSum, exact_outflow_momentum + 3> exact_;
  std::vector<core::ExactSum> exact_threads_;

  // Accumulators and state.
  double plastic_work_ = 0.0;
  double viscous_work_ = 0.0;  // heat of the bulk viscosity (Energies::viscous)
  double external_work_ = 0.0;
  double signal_speed_ = 0.0;  // max c + max |v| at the last stress update
  // Its two parts, max c and max |v|: on ranks each is the largest over the ranks (their sum
  // may come from two ranks; the sum of one rank's parts would not be the whole run's).
  double signal_wave_ = 0.0, signal_flow_ = 0.0;
  long steps_ = 0;
  double time_ = 0.0;
  std::vector<long> stage_counts_;
  std::vector<double> stage_seconds_;
  double reorder_seconds_ = 0.0;
  // Per-thread partial results, combined in thread order (determinism).
  mutable std::vector<double> thread_sums_;
  mutable std::vector<std::int64_t> thread_bad_;
  mutable std::int64_t bad_particle_ = -1;
  mutable const char* bad_field_ = "";
  static constexpr long reorder_interval = 100;
  // Mixed u-p (kept last, clear of the members the other stages read each step): its pressure
  // basis at each particle, found once per step by the first sweep and read by the other two
  // (8 slots and weights per particle; the constant basis uses the first), and each material's
  // 1 / rho0 and K.
  std::vector<std::array<std::int32_t, 8>> pressure_slots_;
  std::vector<std::array<double, 8>> pressure_weights_;
  std::vector<double> pressure_inv_rho0_, pressure_bulk_;
};

}  // namespace afemp::mpm
