// The coupled model's part of a checkpoint (core/state_archive.hpp): the FE and MPM solvers'
// own parts, and what the coupling carries between steps: the node points the grid sees (bonded
// and contact nodes, and those of converted elements), the map between them and the FE nodes,
// the contact nodes' start velocities, the surface contacts' forces and friction work, and the
// energy conversion lost. The boundary faces are rebuilt from the live elements at the next
// step, as the run rebuilds them whenever elements leave.
#include <stdexcept>

#include "core/state_archive.hpp"
#include "coupling/coupled_model.hpp"
#include "coupling/particle_surface_contact.hpp"

namespace afemp::coupling {

using core::StateArchive;

void ParticleSurfaceContacts::state(StateArchive& a) {
  const StateArchive::Group group(a, "surface_contacts");
  std::uint64_t n = pairs_.size();
  a.item("count", n);
  if (n != pairs_.size())
    throw core::CheckpointError(a.where("count") + ": the checkpoint has " + std::to_string(n) +
                                " surface contacts, the scene " + std::to_string(pairs_.size()));
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const StateArchive::Group one(a, std::to_string(k));
    a.item("normal_force", pairs_[k].normal_force);
    a.item("tangential_force", pairs_[k].tangential_force);
    a.item("friction_work", pairs_[k].friction_work);
    // The faces are made again from the live elements at the next step.
    if (a.loading()) pairs_[k].live = static_cast<std::size_t>(-1);
  }
}

void CoupledModel::state(StateArchive& a) {
  if (!conversion_rows_.empty())
    throw std::logic_error("CoupledModel::state: conversion rows not yet taken");
  fe_.state(a);
  mpm_.state(a);
  const StateArchive::Group group(a, "coupling");
  a.item("position", points_.position);
  a.item("velocity", points_.velocity);
  a.item("force", points_.force);
  a.item("mass", points_.mass);
  a.item("body", points_.body);
  a.item("bonded", points_.bonded);
  a.item("normal", points_.normal);
  a.item("surface", points_.surface);
  a.item("motion", points_.motion);
  a.item("on_grid", points_.on_grid);
  a.item("fe_node", fe_node_);
  a.item("point_of_node", point_of_node_);
  a.item("driven", driven_);
  a.item("start_velocity", start_velocity_);
  a.item("fe_normal", normal_);
  a.item("coupling_seconds", coupling_seconds_);
  a.item("converted_energy", converted_energy_);
  if (surface_contacts_) surface_contacts_->state(a);
  if (a.loading()) {
    surface_live_ = static_cast<std::size_t>(-1);  // rebuilt from the live elements
    surface_ = {};
  }
}

}  // namespace afemp::coupling
