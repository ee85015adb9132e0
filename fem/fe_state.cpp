// The FE solver's part of a checkpoint (core/state_archive.hpp): nodes, elements with their
// integration points, erosion state (alive flags, node masses), rigid bodies, the contacts'
// surfaces and search state, and the running energy sums. What the builder derives from the
// scene and the mesh (walls' node sets, velocity curves, absorbing nodes, incidence, the plan)
// comes from constructing the solver from the same scene.
#include <stdexcept>

#include "core/rank_link.hpp"
#include "core/state_archive.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

namespace {

using core::StateArchive;

void visit_store(StateArchive& a, ElementStore& e) {
  a.item("mass", e.mass);
  a.item("volume0", e.volume0);
  a.item("volume", e.volume);
  a.item("critical_dt", e.critical_dt);
  a.item("alive", e.alive);
  for_each_point_field(
      e, [&a](const PointField& field, auto& array, std::size_t) { a.item(field.name, array); });
  a.item("history_count", e.history_count);
}

void visit_pass(StateArchive& a, ContactPass& p) {
  a.item("slaves", p.slaves);
  a.item("slave_faces", p.slave_faces);
  a.item("slave_normal", p.slave_normal);
  a.item("slave_face_offsets", p.slave_face_offsets);
  a.item("slave_face_list", p.slave_face_list);
  a.item("faces", p.faces);
  a.item("face_set", p.face_set);
  a.item("face_element", p.face_element);
  a.item("reach", p.reach);
  a.item("slaves_first_body", p.slaves_first_body);
  a.item("last_face", p.last_face);
  a.item("bin_min", p.bin_min);
  a.item("bin_size", p.bin_size);
  a.item("bin_count", p.bin_count);
  a.item("bin_offsets", p.bin_offsets);
  a.item("bin_faces", p.bin_faces);
  a.item("face_box", p.face_box);
  a.item("margin", p.margin);
  a.item("face_nodes", p.face_nodes);
  a.item("binned_position", p.binned_position);
  a.item("binned", p.binned);
}

void visit_rigid(StateArchive& a, RigidBody& r) {
  a.item("rotation", r.rotation);
  a.item("centre", r.centre);
  a.item("velocity", r.velocity);
  a.item("angular_momentum", r.angular_momentum);
  a.item("angular_velocity", r.angular_velocity);
  a.item("inverse_inertia", r.inverse_inertia);
  a.item("force", r.force);
  a.item("moment", r.moment);
  a.item("reaction", r.reaction);
  a.item("reaction_moment", r.reaction_moment);
  a.item("force_step", r.force_step);
}

// A list the scene fixes (contacts, rigid bodies): the stored count must be the scene's.
void check_count(StateArchive& a, const char* name, std::size_t have) {
  std::uint64_t n = have;
  a.item(name, n);
  if (n != have)
    throw core::CheckpointError(a.where(name) + ": the checkpoint has " + std::to_string(n) +
                                ", the scene " + std::to_string(have));
}

}  // namespace

void FeSolver::state(StateArchive& a) {
  if (!events_.empty() || !retired_.empty())
    throw std::logic_error("FeSolver::state: erosion events or retired elements not yet taken");
  const StateArchive::Group group(a, "fe");
  {
    const StateArchive::Group nodes(a, "nodes");
    a.item("position", nodes_.position);
    a.item("initial_position", nodes_.initial_position);
    a.item("velocity", nodes_.velocity);
    a.item("mass", nodes_.mass);
    a.item("body", nodes_.body);
    a.item("imposed", nodes_.imposed);
    a.item("imposed_velocity", nodes_.imposed_velocity);
    a.item("grid_driven", nodes_.grid_driven);
    a.item("external_force", nodes_.external_force);
  }
  {
    const StateArchive::Group hexes(a, "hexahedra");
    visit_store(a, hexes_);
    a.item("bulk_q", hexes_.bulk_q);
    a.item("hourglass_force", hexes_.hourglass_force);
    a.item("hourglass_power", hexes_.hourglass_power);
  }
  {
    const StateArchive::Group trusses(a, "trusses");
    visit_store(a, trusses_);
    a.item("length0", trusses_.length0);
    a.item("area0", trusses_.area0);
  }
  // The masses written are those after the tied nodes lent theirs; the tied nodes' own masses
  // follow from the live elements again (the same sums, in the same order).
  if (a.loading() && !embedded_.empty()) recompute_node_masses();
  a.item("wall_force", wall_force_);
  // The elements' corner forces of the last update: the next step's nodal update gathers them.
  a.item("element_force", element_force_);
  {
    const StateArchive::Group contacts(a, "contacts");
    check_count(a, "count", contacts_.size());
    for (std::size_t c = 0; c < contacts_.size(); ++c) {
      MeshContact& mc = contacts_[c];
      const StateArchive::Group one(a, std::to_string(c));
      a.item("normal_force", mc.normal_force);
      a.item("tangential_force", mc.tangential_force);
      a.item("normal_sum", mc.normal_sum);
      a.item("tangential_sum", mc.tangential_sum);
      a.item("friction_work", mc.friction_work);
      std::uint64_t passes = mc.passes.size();
      a.item("passes", passes);
      if (a.loading()) mc.passes.resize(passes);
      for (std::size_t p = 0; p < mc.passes.size(); ++p) {
        const StateArchive::Group pass(a, "pass" + std::to_string(p));
        visit_pass(a, mc.passes[p]);
      }
    }
  }
  a.item("contact_nodes", contact_nodes_);
  a.item("predicted", predicted_);
  a.item("velocity_start", velocity_start_);
  a.item("contact_impulse", contact_impulse_);
  a.item("sliding_energy", sliding_energy_);
  a.item("wall_energy", wall_energy_);
  a.item("contact_search_seconds", contact_search_seconds_);
  a.item("outside_impulse", outside_impulse_);
  a.item("outside_free_impulse", outside_free_impulse_);
  {
    const StateArchive::Group rigid(a, "rigid_bodies");
    check_count(a, "count", rigid_bodies_.size());
    for (std::size_t r = 0; r < rigid_bodies_.size(); ++r) {
      const StateArchive::Group one(a, std::to_string(r));
      visit_rigid(a, rigid_bodies_[r]);
    }
  }
  // The element stages' running sums: on MPI ranks a checkpoint holds the whole run's, which
  // prepare_checkpoint() added over the ranks (each rank's are its own elements'); restored on
  // ranks, rank 0 holds them and the others add from zero.
  const bool whole_on_ranks = ranks_ != nullptr && !a.loading();
  if (whole_on_ranks && !rank_sums_.ready)
    throw std::logic_error("FeSolver::state: prepare_checkpoint() first on ranks");
  RankSums own{plastic_work_,       viscous_work_,  hourglass_work_,
               stabilisation_work_, eroded_energy_, body_stabilisation_};
  if (reproducible() && !a.loading() && !whole_on_ranks) own = exact_rank_sums(false);
  RankSums& sums = whole_on_ranks ? rank_sums_ : own;
  a.item("plastic_work", sums.plastic);
  a.item("viscous_work", sums.viscous);
  a.item("hourglass_work", sums.hourglass);
  a.item("stabilisation_work", sums.stabilisation);
  a.item("body_stabilisation", sums.body_stabilisation);
  a.item("eroded_energy", sums.eroded);
  if (whole_on_ranks) rank_sums_.ready = false;
  if (a.loading()) {
    if (ranks_ != nullptr && ranks_->rank() != 0) own = RankSums{};
    plastic_work_ = own.plastic;
    viscous_work_ = own.viscous;
    hourglass_work_ = own.hourglass;
    stabilisation_work_ = own.stabilisation;
    eroded_energy_ = own.eroded;
    body_stabilisation_ = own.body_stabilisation;
    if (body_stabilisation_.empty()) body_stabilisation_.assign(scene_.bodies.size(), 0.0);
    start_exact_sums();
  }
  a.item("external_work", external_work_);
  a.item("absorbing_start", absorbing_start_);
  a.item("previous_dt", previous_dt_);
  a.item("steps", steps_);
  a.item("time", time_);
  a.item("erosion_this_step", erosion_this_step_);
  a.item("converted_node", converted_node_);
  a.item("stage_seconds", stage_seconds_);
  if (a.loading() && stage_seconds_.size() != plan_.stages.size())
    throw core::CheckpointError(
        a.where("stage_seconds") + ": " + std::to_string(stage_seconds_.size()) +
        " stages, the scene's plan has " + std::to_string(plan_.stages.size()));
}

}  // namespace afemp::fem
