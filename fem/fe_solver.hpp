// The explicit FE solver: lumped-mass nodes moved by central differences (Belytschko, Liu &
// Moran, Nonlinear Finite Elements, box 6.1), 8-node hexahedra (one-point with
// Flanagan-Belytschko hourglass control, or 2x2x2 B-bar) and 2-node trusses, each kind an element
// set behind one interface (element_set.hpp), all updated by the shared material composition of
// core/materials. The stages a scene needs are its step plan (fe_step_plan.cpp); they live in
// files named after them: fe_model_builder.cpp (mesh, masses, sets), nodal_update.cpp (forces
// to motion, constraints), rigid_wall.cpp, hexahedron_update.cpp, truss_update.cpp, erosion.cpp,
// element_retirement.cpp.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <set>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "afemp/energies.hpp"
#include "core/exact_sum.hpp"
#include "core/materials/material.hpp"
#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/element_store.hpp"
#include "fem/embedded_nodes.hpp"
#include "fem/fe_step_plan.hpp"
#include "fem/hexahedron.hpp"
#include "fem/hexahedron_set.hpp"
#include "fem/mesh.hpp"
#include "fem/mesh_contact.hpp"
#include "fem/rigid_body.hpp"
#include "fem/truss_set.hpp"

namespace afemp::core {
class RankLink;
class StateArchive;
}  // namespace afemp::core

namespace afemp::fem {

template <class Strength, class Eos, bool Thermal, bool Fails>
class HexahedronPasses;  // hexahedron_passes.hpp
struct StaticPhaseMap;   // static_phase.hpp
struct StaticResult;     // static_solve.hpp

using core::Vec3;

// Nodes as structures of arrays. Velocities live at half steps (v^{n+1/2}).
struct FeNodes {
  std::vector<Vec3> position, initial_position, velocity;
  std::vector<double> mass;           // lumped, from the live elements
  std::vector<std::int32_t> body;     // scene body index
  std::vector<std::uint8_t> imposed;  // bit a: velocity component a is imposed
  std::vector<Vec3> imposed_velocity;
  // 1: the node moves with the background grid (bonded to particles, coupling/): the nodal
  // update and the position update leave it to the caller.
  std::vector<std::uint8_t> grid_driven;
  // Loads a program applies (afemp::Simulation::nodes), held until it changes them: empty, or
  // one force per node, acting on the nodes the FE update moves (not grid-driven ones).
  std::vector<Vec3> external_force;
  std::size_t size() const { return position.size(); }
};

// A record of an eroded element.
struct ErosionEvent {
  double time = 0.0;
  const char* kind = "hexahedron";  // "hexahedron", "truss" or "node" (left with no element)
  std::int64_t id = 0;              // index within its kind and body
  int body = 0;
  std::string reason;
  // An element's internal energy plus the kinetic energy of its node-mass share, and its mass:
  // the element records add up to the eroded energy. A dropped node's record reports its mass
  // and kinetic energy, which its elements' records already count.
  double energy = 0.0;
  double mass = 0.0;
  // The element in its set, or the node: with the kind, the order one process makes the
  // records of a step in (the records of a run on MPI ranks are put in that order).
  std::size_t index = 0;
};

// A hexahedron that left the mesh without eroding: its body's `conversion` criteria met inside
// the retirement domain (fem/element_retirement.cpp). Its state stays in the arrays (alive = 0)
// for the caller that takes it (take_retired_elements) to make what replaces it (particles:
// coupling/element_conversion.cpp); its nodes' masses follow the live elements.
struct RetiredElement {
  double time = 0.0;
  std::size_t element = 0;  // index into the hexahedra
  std::int64_t id = 0;      // index within its body
  int body = 0;
  const char* reason = "";
};

// Where hexahedra may retire, and the cell h that the time-step criterion compares an
// element's critical step with (at h / c): set by the caller that takes them (coupling/: the
// background grid's domain and cell). Unset, no element retires.
struct RetirementDomain {
  Vec3 min, max;
  double cell = 0.0;
  bool set = false;
};

// Where a wall acts: the nodes it may touch.
struct WallState {
  core::WallSpec spec;
  std::vector<std::int32_t> nodes;
  std::vector<Vec3> start;  // the nodes' v^{n-1/2}, for the work of the wall's impulses
};

class FeSolver {
 public:
  explicit FeSolver(const core::Scene& scene);
  // The solver keeps a reference to the scene: a temporary one would dangle.
  explicit FeSolver(core::Scene&&) = delete;
  // The list of element sets points into the solver.
  FeSolver(const FeSolver&) = delete;
  FeSolver& operator=(const FeSolver&) = delete;

  const FeNodes& nodes() const { return nodes_; }
  // For drivers and tests that prescribe node motion between steps (velocities at half steps).
  FeNodes& mutable_nodes() { return nodes_; }
  const HexElements& hexahedra() const { return hexes_; }
  const TrussElements& trusses() const { return trusses_; }
  // For programs that change the integration points' state between steps (afemp::Simulation).
  HexElements& mutable_hexahedra() { return hexes_; }
  TrussElements& mutable_trusses() { return trusses_; }
  const MeshData& mesh() const { return mesh_; }  // the assembled input mesh (for reports)
  long step_count() const { return steps_; }
  double time() const { return time_; }
  // The stages a step runs, built once from the scene, and the wall seconds of each.
  const FeStepPlan& plan() const { return plan_; }
  const std::vector<double>& stage_seconds() const { return stage_seconds_; }

  // factor * min over live elements of the critical step (or the scene's fixed step).
  double stable_time_step() const;
  // Where the smallest critical step is: "hexahedron 12 of body bar".
  std::string smallest_step_element() const;
  // The same with why its step is small: its critical step and its volume against its initial
  // one (a crushed or inverting element), for the run summary (core::Model::time_step_setter).
  std::string time_step_setter() const;
  // One central-difference step. Throws core::SimulationError naming the step, the node or
  // element and the field when a value goes NaN/Inf or an element inverts without erosion.
  // It is begin_step then finish_step; a coupled step (coupling/) runs the grid in between.
  void step(double dt);
  // v^{n+1/2} of every node not grid driven: element forces, gravity, imposed velocities,
  // rigid walls.
  void begin_step(double dt);
  // x^{n+1} of every node not grid driven (the caller has moved the others), then the
  // elements' stress and forces at x^{n+1} with v^{n+1/2}, erosion, and the clock.
  void finish_step(double dt);
  // Multiplies the nodes' v^{n+1/2} and the rigid bodies' momenta by factor, imposed
  // components kept (core::Model::scale_velocities); rigid nodes follow their bodies.
  void scale_velocities(double factor);
  // Marks the nodes the grid moves (driven[i] != 0); they also leave the rigid walls.
  void set_grid_driven(const std::vector<std::uint8_t>& driven);
  // The step the nodal update applies the forces over: dt^n = (dt^{n-1/2} + dt^{n+1/2}) / 2
  // (half a step on the first), for a coupled step that hands other nodes the same impulse.
  double force_step(double dt) const { return steps_ == 0 ? 0.5 * dt : 0.5 * (previous_dt_ + dt); }
  // The step whose motion came before this one's, as the work of an impulse J at step n is
  // taken: J . (dt^{n-1/2} v^{n-1/2} + dt^{n+1/2} v^{n+1/2}) / (dt^{n-1/2} + dt^{n+1/2}); on the
  // first step dt itself, so that the impulse works on the mean of v^0 and v^{1/2} (the kinetic
  // energy starts at v^0, not at a half step).
  double motion_before_step(double dt) const { return steps_ == 0 ? dt : previous_dt_; }
  // The sum of the element forces on node i at the current state (no gravity).
  Vec3 node_force(std::size_t i) const {
    Vec3 f;
    for (std::int64_t k = incidence_offsets_[i]; k < incidence_offsets_[i + 1]; ++k)
      f += element_force_[static_cast<std::size_t>(incidence_[static_cast<std::size_t>(k)])];
    return f;
  }
  core::Energies energies() const;
  // The records since the last call, by step, then hexahedra, trusses and nodes, each by index
  // (the order the sweeps met them in depends on the packs of elements and the threads). On
  // MPI ranks (collective): every rank's, on rank 0 alone.
  std::vector<ErosionEvent> take_erosion_events();
  // Hexahedra retired (their body's `conversion` criteria met) since the last call, in the
  // order they retired; the caller makes what replaces them from the arrays and the nodes.
  std::vector<RetiredElement> take_retired_elements();
  // Where hexahedra may retire (see RetirementDomain); the coupled model sets the grid's.
  void set_retirement_domain(const RetirementDomain& domain);  // unset unless a body converts
  // Whether hexahedron e lies inside the retirement domain (where it may retire).
  bool inside_retirement_domain(std::size_t e) const;
  std::size_t bytes() const;
  // Penalty contacts between meshes (their resultant forces of the last step) and rigid bodies.
  const std::vector<MeshContact>& mesh_contacts() const { return contacts_; }
  const std::vector<RigidBody>& rigid_bodies() const { return rigid_bodies_; }
  const EmbeddedNodes& embedded_nodes() const { return embedded_; }
  // Wall seconds the contacts' search took (part of the mesh contact stage's).
  double contact_search_seconds() const { return contact_search_seconds_; }
  // The resultant force the walls exerted on the nodes over the last step (impulse / dt),
  // one per [[walls]] entry.
  const std::vector<Vec3>& wall_forces() const { return wall_force_; }
  // The walls and the nodes each may touch.
  const std::vector<WallState>& walls() const { return walls_; }
  std::size_t live_hexahedra() const;
  std::size_t live_trusses() const;
  // The live elements' stable step (element_time_step_factor x their least critical step);
  // +inf when none bounds it (rigid bodies' elements do not). stable_time_step() is this,
  // or the fixed step, and an error when it is +inf.
  double element_step_limit() const;
  // Contact impulses from outside the FE update, between begin_step and finish_step (particles
  // at a mesh surface, coupling/particle_surface_contact.cpp), as the mesh contacts give them:
  // node i's inverse mass along unit n (its free components' share of 1/m, or its rigid body's
  // at that point); an impulse on node i (a free node's free components change by J / m; a
  // rigid node moves with w (J . n) n until settled); then rigid bodies take the impulses their
  // nodes got and their nodes follow the bodies again.
  double contact_inverse_mass(std::size_t i, const Vec3& n) const;
  void push_contact_impulse(std::size_t i, double w, const Vec3& n, const Vec3& impulse);
  void settle_contact_impulses(double dt);

  // The travel each imposed velocity component gives its node over [t0, t1]: the integral of
  // the constraint's velocity times its curve (nodal_update.cpp); 0 for free components.
  std::vector<Vec3> imposed_travel(double t0, double t1) const;
  // The nodal forces of the scene's [[loads]] on hexahedra at time t, per node (empty without
  // any; surface_loads.cpp): what a static or implicit phase holds.
  std::vector<Vec3> scene_loads_at(double t) const;
  // core::Model::set_body_velocity and set_clock (nodal_update.cpp).
  void set_body_velocity(int body, const Vec3& v);
  void hold_body(int body, bool hold);
  void set_clock(double time) { time_ = time; }
  // A static phase's solution as the state at `time` (fem/static_phase.cpp): the nodes of the
  // problem map moved by their displacement, its points' stresses, plastic strains and work,
  // the hourglass forces and element forces of that state, and the work as external work;
  // returns that work.
  double take_static_state(const StaticPhaseMap& map, const StaticResult& result, double time);
  // The listed nodes' kinetic energy (lumped masses), and their velocities set (an implicit
  // phase's end; fem/static_phase.cpp).
  double kinetic_energy(std::span<const std::int32_t> nodes) const;
  void set_velocities(std::span<const std::int32_t> nodes, std::span<const Vec3> velocity);
  void add_external_work(double work) { external_work_ += work; }
  // Saves or restores the solver's state (a checkpoint, core/state_archive.hpp; fe_state.cpp).
  // Restoring needs a solver built from the same scene; events must have been taken.
  void state(core::StateArchive& archive);

  // MPI ranks (element_division.cpp; docs/parallel.md): each rank updates a share of every
  // batch of elements (runs of 64 dealt round the ranks) and, after the element stages, sends its
  // elements' corner forces, critical steps, volumes and alive flags to every rank, so that every
  // rank moves every node as one process does, to the bit; the state of an element's points stays
  // on its rank. Energies sum the ranks' element parts in rank order, the erosion records are
  // gathered on rank 0 (take_erosion_events), and every call below that reads the element state is
  // collective. A static or implicit phase is solved on rank 0 in an undivided model
  // (core::TimeLoop::solve_phase_on_rank_0), whose state every rank then takes.
  void divide_among_ranks(core::RankLink& link);
  bool on_ranks() const { return ranks_ != nullptr; }
  int rank() const;
  // f(store, batch, first point) for each live element of this rank's share (every element in
  // one process), in element order: the points whose state this rank keeps.
  template <class F>
  void for_each_live_element(F&& f) const;
  // Collective: rank 0's copies of the other ranks' elements take their points' state, bulk
  // viscosity and hourglass forces (for the frame, the probes or the checkpoint rank 0 writes).
  // It changes nothing any rank's update reads; nothing in one process.
  void gather_elements() const;
  // Per scene body, the axial forces of its live trusses at their extremes: most[b] the largest
  // (tension positive), least[b] the smallest; -inf and +inf for a body with none. On ranks
  // (collective) over every rank's trusses: a truss's stress lives on its rank.
  void truss_axial_range(std::vector<double>& most, std::vector<double>& least) const;
  // Collective, before state() saves on ranks: the elements gathered on rank 0 and the running
  // sums of the element stages added in rank order (core::Model::prepare_checkpoint).
  void prepare_checkpoint();
  // Wall seconds spent sending the element results between ranks.
  double exchange_seconds() const { return exchange_seconds_; }

 private:
  // The live element with the smallest critical step: its set, batch and index (set nullptr:
  // none).
  struct SmallestStep {
    const ElementSet* set = nullptr;
    const ElementBatch* batch = nullptr;
    std::size_t element = 0;
  };
  SmallestStep smallest_step() const;
  std::string element_name(const SmallestStep& s) const;  // "hexahedron 12 of body bar"
  // The hexahedron stage's passes (hexahedron_passes.hpp) read and write the solver's arrays.
  template <class Strength, class Eos, bool Thermal, bool Fails>
  friend class HexahedronPasses;
  // The element sets' updates run the solver's stages of their kind.
  friend class HexahedronSet;
  friend class TrussSet;

  void build(const core::Scene& scene);
  // The pieces of build, in its order (fe_model_builder.cpp).
  struct BodyMeshes;
  BodyMeshes build_nodes(const core::Scene& scene);
  void build_elements(const core::Scene& scene, const BodyMeshes& meshes);
  void setup_point_fields(const core::Scene& scene);
  void setup_explosives(const core::Scene& scene);
  void setup_constraints(const core::Scene& scene, const BodyMeshes& meshes);
  void setup_velocity_curves(const core::Scene& scene, const std::vector<std::int32_t>& owner);
  void setup_absorbing_boundaries(const core::Scene& scene, const BodyMeshes& meshes);
  void setup_walls(const core::Scene& scene);
  void build_incidence();
  void setup_mesh_contacts(const core::Scene& scene);
  void setup_step_arrays(const core::Scene& scene);
  // The pieces of resolve_contacts, in its order (mesh_contact.cpp).
  void search_mesh_contacts(double dt);
  void sweep_mesh_contacts(double dt);
  void settle_rigid_mesh_contacts(double dt);
  void report_mesh_contact_forces(double dt_force);
  void book_sliding_energy(double dt, double dt_force);
  void update_nodes(double dt);
  void apply_walls(double dt);
  // Contact corrections of v^{n+1/2} at the predicted positions (mesh_contact.cpp).
  void resolve_contacts(double dt);
  // Rigid bodies (rigid_body_update.cpp): the resultant on each body -> momenta and node
  // velocities; then, before the nodes move, the pose.
  void advance_rigid_bodies(double dt);
  void move_rigid_bodies(double dt);
  void setup_rigid_bodies();
  void update_hexahedra(double dt);
  void update_trusses(double dt);
  // Fails: the material has a failure model (one instantiation each: core/materials/material.hpp).
  template <class Strength, class Eos, bool Thermal, bool Fails>
  void hexahedron_batch(const ElementBatch& b, const Strength& s, const Eos& e, double dt);
  template <class Strength, class Eos, bool Thermal>
  void truss_batch(const ElementBatch& b, const Strength& s, const Eos& e, double dt);
  // Erodes the elements of `set` the last sweep flagged (thread order: deterministic).
  void collect_erosions(ElementSet& set);
  void finish_erosion();
  // Retirement (element_retirement.cpp): the first `conversion` criterion element e of batch b
  // meets (nullptr: none), and the records of the elements the last sweep flagged.
  const char* conversion_reason(const core::ConversionSettings& c, const ElementBatch& b,
                                std::size_t e, double volume, double grid_step) const;
  void collect_retirements();
  void recompute_node_masses();
  // Runs f as the plan's stage `kind` and adds its wall seconds; nothing when the scene does
  // not need that stage.
  template <class F>
  void run_stage(FeStageKind kind, F&& f);
  [[noreturn]] void raise(const std::string& entity, const char* field,
                          const std::string& detail) const;
  // Throws for the first thread (in thread order) that met a bad value in the last sweep.
  void raise_thread_errors() const;
  // Runs batch_update<Strength, Eos, Thermal>(batch, strength, eos, dt) for each batch with
  // the material's concrete model types: one std::visit per batch.
  template <class Update>
  void for_each_batch(const ElementStore& elements, Update&& batch_update);

  const core::Scene& scene_;
  MeshData mesh_;
  FeNodes nodes_;
  // The element sets, each kind's container; the generic stages go through sets_ (hexahedra
  // first: hexahedron_passes.hpp writes their forces from slot 0).
  HexahedronSet hexes_;
  TrussSet trusses_;
  const std::array<ElementSet*, 2> sets_{&hexes_, &trusses_};
  std::vector<WallState> walls_;
  std::vector<Vec3> wall_force_;
  // Contacts between meshes; the nodes of their bodies and their predicted positions (per FE
  // node), and the impulses rigid nodes got (per FE node, with rigid bodies only).
  std::vector<MeshContact> contacts_;
  std::vector<std::int32_t> contact_nodes_;
  // and, per FE node, their velocities at the step's start and the impulse contact gave them.
  std::vector<Vec3> predicted_, velocity_start_, contact_impulse_;
  double sliding_energy_ = 0.0, contact_search_seconds_ = 0.0;
  // What the rigid walls took from the motion (Energies::wall, rigid_wall.cpp).
  double wall_energy_ = 0.0;
  // Impulses pushed from outside this step on rigid nodes (push_contact_impulse), per node.
  std::vector<Vec3> outside_impulse_;
  Vec3 outside_free_impulse_;  // their sum on free nodes (for gravity's work)
  // Rigid bodies, and per node the rigid body it belongs to (-1: none; empty without any).
  std::vector<RigidBody> rigid_bodies_;
  std::vector<std::int32_t> rigid_of_node_;
  EmbeddedNodes embedded_;  // trusses tied into hexahedra
  // Element nodal forces, gathered per node through the incidence lists (no atomics): corner a
  // of element e of a set at its first_slot + corners e + a (hexahedra, then trusses).
  std::vector<Vec3> element_force_;
  std::vector<std::int64_t> incidence_offsets_;
  std::vector<std::int64_t> incidence_;

  // Accounting.
  double plastic_work_ = 0.0, viscous_work_ = 0.0, hourglass_work_ = 0.0, stabilisation_work_ = 0.0;
  std::vector<double> body_stabilisation_;  // stabilisation_work_ per body
  double eroded_energy_ = 0.0, external_work_ = 0.0;
  // Prescribed velocities that follow a curve (ConstraintSpec::curve): the node components
  // each owns (a later constraint on the same component takes it over), set to velocity x
  // factor(t) at each step's mid-time before the nodal update.
  struct VelocityCurve {
    std::vector<std::array<double, 2>> curve;
    Vec3 velocity;
    std::vector<std::pair<std::uint32_t, std::uint8_t>> components;  // (node, axis)
  };
  std::vector<VelocityCurve> velocity_curves_;
  // Nodes hold_body holds: each with the imposed bits and velocity it had.
  struct HeldNode {
    std::uint32_t node = 0;
    std::uint8_t imposed = 0;
    Vec3 velocity;
  };
  std::vector<HeldNode> held_;
  void apply_velocity_curves(double t);
  // Absorbing boundaries (absorbing_boundary.cpp): per node, the outward unit normal and the
  // dashpots A rho c_L (along it) and A rho c_S (across it) of its boundary faces.
  struct AbsorbingNode {
    std::uint32_t node = 0;
    Vec3 normal;
    double normal_damping = 0.0, shear_damping = 0.0;
  };
  std::vector<AbsorbingNode> absorbing_nodes_;
  std::vector<Vec3> absorbing_start_;  // their velocities at the step's start
  // The boundary faces of `surface` (every body's) whose four nodes are selected.
  void setup_absorbing(const core::AbsorbingSpec& spec, const std::vector<char>& selected,
                       const SurfaceFaces& surface);
  void absorb(double dt);
  // [[loads]] on hexahedra (surface_loads.cpp): each load's nodes and their forces at factor 1
  // (a total force already spread over the faces' area), and the sum of every load at the
  // step's start time, per node (empty without loads), which the nodal update applies.
  struct NodalLoad {
    std::size_t scene_load = 0;  // index in scene_.loads (its curve)
    std::vector<std::uint32_t> nodes;
    std::vector<Vec3> force;
    double area = 0.0;  // the loaded faces' initial area
  };
  std::vector<NodalLoad> nodal_loads_;
  std::vector<Vec3> load_force_;
  void setup_loads(const core::Scene& scene, const BodyMeshes& meshes);
  // Load k's nodal forces from the boundary faces of `surface` whose four nodes are selected.
  void setup_load(std::size_t k, const std::vector<char>& selected, const SurfaceFaces& surface);
  void apply_loads(double t);
  // The loads' work for the change of their curves over the step, (f^{n+1} - f^n) / 2 .
  // v^{n+1/2} dt (the nodal update books f^n's).
  void book_load_change(double dt);
  double previous_dt_ = 0.0;
  long steps_ = 0;
  double time_ = 0.0;
  bool erosion_this_step_ = false;
  std::vector<ErosionEvent> events_;
  std::vector<RetiredElement> retired_;  // not yet taken
  // MPI ranks (element_division.cpp): the link, this rank and their count, the element results
  // sent after the element stages, and the element stages' running sums prepare_checkpoint
  // added over the ranks (for state() to save).
  core::RankLink* ranks_ = nullptr;
  int rank_ = 0, rank_count_ = 1;
  // Rank r's share of batch b: runs of kRankRun elements dealt round the ranks (run k to rank
  // k mod N), so that a region dearer than the rest (a plastic foot, an eroding crater) is
  // shared by every rank; the whole batch in one process. for_each_share calls f(first, last)
  // for each of rank r's runs; sweep_share calls f(first, last, thread) over this rank's
  // elements split among the threads (core::parallel_chunks over its element count).
  static constexpr std::size_t kRankRun = 64;
  template <class F>
  void for_each_share(const ElementBatch& b, int r, F&& f) const;
  template <class F>
  void sweep_share(const ElementBatch& b, F&& f) const;
  void share_element_results();
  // After the element results, where a body converts (AFEMP): every rank's hexahedra retired
  // this step, with their points' state, to every rank, so that every rank holds the same
  // retired list (by element index) to make the same particles of, and marks their nodes.
  void share_retirements();
  std::set<std::string> reasons_;  // received retirement reasons, whose c_str() records keep
  // The element parts of `e` (internal, plastic, viscous, hourglass, stabilisation, eroded,
  // each body's internal) added over the ranks in rank order.
  void sum_element_energies(core::Energies& e) const;
  std::vector<ErosionEvent> gather_erosion_events(std::vector<ErosionEvent> mine) const;
  static void sort_erosion_events(std::vector<ErosionEvent>& events);
  double exchange_seconds_ = 0.0;
  // The bytes sent and received between ranks, kept from step to step: a step allocates none.
  std::vector<std::byte> rank_send_;
  std::vector<std::vector<std::byte>> rank_receive_;
  struct RankSums {
    double plastic = 0.0, viscous = 0.0, hourglass = 0.0, stabilisation = 0.0, eroded = 0.0;
    std::vector<double> body_stabilisation;
    bool ready = false;
  } rank_sums_;
  RetirementDomain retirement_;
  std::vector<std::uint8_t> converted_node_;  // a node of an element converted this step
  std::vector<std::vector<std::size_t>> thread_conversions_;
  std::vector<std::vector<const char*>> thread_conversion_reason_;
  FeStepPlan plan_;
  std::vector<double> stage_seconds_;
  // Per-thread partial sums (padded), combined in thread order.
  std::vector<double> thread_sums_;
  // The reproducible mode ([run] reproducible; fem/reproducible_energies.cpp): sums that do not
  // depend on the thread count or on how the elements are shared among ranks. book() adds a
  // term to a thread's sum and to the exact sum that mirrors it (one a thread_sums_ entry);
  // exact_threads(k) is entry k's exact sum over the threads. The elements' running sums are
  // kept exactly per rank too (exact_, exact_body_stabilisation_), from the doubles'
  // values where a run starts, is divided or restarts (start_exact_sums).
  bool reproducible() const { return scene_.run.reproducible; }
  void book(double* sums, std::size_t k, double x) const {
    sums[k] += x;
    if (!exact_mirror_.empty())
      exact_mirror_[static_cast<std::size_t>(sums - thread_sums_.data()) + k].add(x);
  }
  core::ExactSum exact_threads(std::size_t k) const;
  void clear_exact_threads(std::size_t k) const;
  void start_exact_sums();
  // The running sums from the exact ones, over the ranks where `over_ranks` (collective).
  RankSums exact_rank_sums(bool over_ranks) const;
  core::Energies reproducible_energies() const;
  // energies()' part that every rank sums alike over every node: kinetic energy, mass and
  // momentum, the contacts' and walls' energies, the external work.
  core::Energies nodal_energies() const;
  mutable std::vector<core::ExactSum> exact_mirror_;
  enum ExactEntry : std::size_t {
    exact_plastic,
    exact_viscous,
    exact_hourglass,
    exact_stabilisation,
    exact_eroded
  };
  std::array<core::ExactSum, 5> exact_;
  std::vector<core::ExactSum> exact_body_stabilisation_;
  std::vector<std::vector<std::size_t>> thread_erosions_;
  std::vector<std::vector<const char*>> thread_failure_;
  std::vector<std::string> thread_errors_;       // entity of the first bad value per thread
  std::vector<const char*> thread_error_field_;  // and its field
};

template <class F>
void FeSolver::run_stage(FeStageKind kind, F&& f) {
  const int i = plan_.index(kind);
  if (i < 0) return;
  const auto t0 = std::chrono::steady_clock::now();
  f();
  stage_seconds_[static_cast<std::size_t>(i)] +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <class F>
void FeSolver::for_each_share(const ElementBatch& b, int r, F&& f) const {
  if (ranks_ == nullptr) {
    f(b.begin, b.end);
    return;
  }
  const std::size_t stride = kRankRun * static_cast<std::size_t>(rank_count_);
  for (std::size_t lo = b.begin + kRankRun * static_cast<std::size_t>(r); lo < b.end; lo += stride)
    f(lo, std::min(lo + kRankRun, b.end));
}

template <class F>
void FeSolver::for_each_live_element(F&& f) const {
  for (const ElementSet* set : sets_) {
    const ElementStore& el = set->store();
    for (const ElementBatch& b : el.batches)
      for_each_share(b, rank_, [&](std::size_t first, std::size_t last) {
        for (std::size_t e = first; e < last; ++e)
          if (el.alive[e])
            f(el, b,
              b.point_begin + (e - b.begin) * static_cast<std::size_t>(b.points_per_element));
      });
  }
}

template <class F>
void FeSolver::sweep_share(const ElementBatch& b, F&& f) const {
  const std::size_t n = b.end - b.begin;
  if (ranks_ == nullptr) {
    core::parallel_chunks(
        n, [&](std::size_t lo, std::size_t hi, int t) { f(b.begin + lo, b.begin + hi, t); });
    return;
  }
  const std::size_t runs = n / kRankRun, rest = n % kRankRun;
  const auto ranks = static_cast<std::size_t>(rank_count_), r = static_cast<std::size_t>(rank_);
  // This rank's elements: its whole runs, and the last, shorter run when it is its.
  const std::size_t own = (runs > r ? (runs - r + ranks - 1) / ranks : 0) * kRankRun +
                          (rest > 0 && runs % ranks == r ? rest : 0);
  // Its k-th element lies in its run k / kRankRun, the batch's run (k / kRankRun) N + r.
  core::parallel_chunks(own, [&](std::size_t lo, std::size_t hi, int t) {
    while (lo < hi) {
      const std::size_t first = b.begin + ((lo / kRankRun) * ranks + r) * kRankRun + lo % kRankRun;
      const std::size_t take = std::min(hi - lo, kRankRun - lo % kRankRun);
      f(first, first + take, t);
      lo += take;
    }
  });
}

template <class Update>
void FeSolver::for_each_batch(const ElementStore& elements, Update&& update) {
  for (const ElementBatch& b : elements.batches) {
    if (b.rigid) continue;  // no stress, no forces (rigid_body_update.cpp moves its nodes)
    const core::Material& m = scene_.materials[static_cast<std::size_t>(b.material)];
    core::visit_models(m, [&](const auto& strength, const auto& eos) {
      using S = std::decay_t<decltype(strength)>;
      using E = std::decay_t<decltype(eos)>;
      if (m.has_thermal_term())
        update.template operator()<S, E, true>(b, strength, eos);
      else
        update.template operator()<S, E, false>(b, strength, eos);
    });
  }
}

}  // namespace afemp::fem
