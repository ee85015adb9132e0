// The grid nodes of a step's particle contacts (particles at rigid walls,
// particle_wall_contact.cpp; particles at mesh faces, coupling/particle_surface_contact.cpp),
// copied out of the grid for their projected Gauss-Seidel sweeps. The sweeps resolve the
// contacts one after another, each on the nodal velocities the ones before it left, so their
// result depends on their order. Here that order is the particles' ids: the run does not depend
// on how the particles are stored (their reordering by cell, which particles a rank holds).
// On MPI ranks each rank finds the contacts of its own particles and sends them with their
// nodes' masses and velocities (the same bits on every rank that holds a shared block,
// core/rank_link.hpp) to every rank; every rank then sweeps every contact in id order, ends
// with the same nodal velocities, and writes back those of the blocks it holds. The sweeps'
// cost is repeated on every rank, as the contacts are few beside the particles.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/grid/background_grid.hpp"
#include "core/rank_link.hpp"
#include "mpm/face_constraints.hpp"

namespace afemp::mpm {

// Contact: a plain struct with the particle's id, `std::int64_t id`, and what its sweep needs
// (nothing indexed by this rank's particle arrays).
template <class Contact>
class ContactNodes {
  static_assert(std::is_trivially_copyable_v<Contact>);

 public:
  // Starts a step's contacts, of `nodes` stencil nodes each.
  void begin(int nodes) {
    k_ = nodes;
    contacts_.clear();
    slots_.clear();
    weights_.clear();
  }
  // Adds a contact of this rank with its stencil's field slots (-1: a node that takes no part,
  // weight 0) and weights.
  void add(const Contact& c, std::span<const std::int64_t> slots, std::span<const double> weights) {
    contacts_.push_back(c);
    slots_.insert(slots_.end(), slots.begin(), slots.begin() + k_);
    weights_.insert(weights_.end(), weights.begin(), weights.begin() + k_);
  }
  // Every rank's contacts (on ranks: collective, called by every rank) in id order, and the
  // rows of their distinct nodes.
  void finish(const core::BackgroundGrid& g, core::RankLink* ranks) {
    velocity.clear();
    mass.clear();
    constraint.clear();
    row_slot_.clear();
    if (ranks == nullptr)
      rows_of_slots(g);
    else
      rows_of_every_rank(g, *ranks);
    // Id order (ids are unique; in one process the contacts often come in it already).
    order_.resize(contacts_.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    const auto by_id = [&](std::size_t a, std::size_t b) {
      return contacts_[a].id < contacts_[b].id;
    };
    if (!std::is_sorted(order_.begin(), order_.end(), by_id))
      std::stable_sort(order_.begin(), order_.end(), by_id);
  }

  std::size_t size() const { return contacts_.size(); }
  Contact& operator[](std::size_t c) { return contacts_[order_[c]]; }
  const Contact& operator[](std::size_t c) const { return contacts_[order_[c]]; }
  // Node k of contact c (in id order): its row (-1: none) and weight.
  std::int32_t row(std::size_t c, int k) const { return row_[entry(c, k)]; }
  double weight(std::size_t c, int k) const { return weights_[entry(c, k)]; }

  // Contact c's velocity, sum N_k v_k over its nodes.
  Vec3 particle_velocity(std::size_t c) const {
    Vec3 v;
    for (int k = 0; k < k_; ++k)
      if (const std::int32_t r = row(c, k); r >= 0)
        v += weight(c, k) * velocity[static_cast<std::size_t>(r)];
    return v;
  }
  // Contact c's inverse mass sum N_k^2 / m_k.
  double particle_inverse_mass(std::size_t c) const {
    double w = 0.0;
    for (int k = 0; k < k_; ++k)
      if (const std::int32_t r = row(c, k); r >= 0)
        w += weight(c, k) * weight(c, k) / mass[static_cast<std::size_t>(r)];
    return w;
  }
  // Gives contact c's nodes the impulse J (N_k J / m_k each), the grid faces' conditions kept;
  // returns the momentum the nodes took.
  Vec3 push(std::size_t c, const Vec3& impulse) {
    Vec3 took;
    for (int k = 0; k < k_; ++k) {
      const std::int32_t r = row(c, k);
      if (r < 0) continue;
      const auto ru = static_cast<std::size_t>(r);
      Vec3& v = velocity[ru];
      const Vec3 before = v;
      v += (weight(c, k) / mass[ru]) * impulse;
      if (constraint[ru].any()) constrain(v, constraint[ru].mask_for(v));
      took += mass[ru] * (v - before);
    }
    return took;
  }

  // The rows' velocities into the nodes of this rank's grid (every node in one process).
  void write_back(core::BackgroundGrid& g) const {
    for (std::size_t r = 0; r < row_slot_.size(); ++r)
      if (row_slot_[r] >= 0) g.velocity_new[static_cast<std::size_t>(row_slot_[r])] = velocity[r];
  }

  // Each row's velocity, mass and face conditions, swept in place.
  std::vector<Vec3> velocity;
  std::vector<double> mass;
  std::vector<NodeConstraint> constraint;

 private:
  std::size_t entry(std::size_t c, int k) const {
    return order_[c] * static_cast<std::size_t>(k_) + static_cast<std::size_t>(k);
  }
  // One process: a row for the node of each field slot, with the grid's values there.
  void rows_of_slots(const core::BackgroundGrid& g) {
    const FaceConstraints faces(g);
    row_of_slot_.resize(std::max(row_of_slot_.size(), g.field_slot_count()), -1);
    row_.resize(slots_.size());
    for (std::size_t e = 0; e < slots_.size(); ++e) {
      const std::int64_t s = slots_[e];
      if (s < 0) {
        row_[e] = -1;
        continue;
      }
      const auto su = static_cast<std::size_t>(s);
      std::int32_t& r = row_of_slot_[su];
      if (r < 0) {
        r = static_cast<std::int32_t>(row_slot_.size());
        row_slot_.push_back(s);
        velocity.push_back(g.velocity_new[su]);
        mass.push_back(g.mass[su]);
        constraint.push_back(faces(g.node_of_slot(su % g.slot_count())));
      }
      row_[e] = r;
    }
    for (std::int64_t s : row_slot_) row_of_slot_[static_cast<std::size_t>(s)] = -1;
  }

  // A stencil node as a contact carries it to the other ranks: its key (block, node in the
  // block, field; -1: none), and the grid's mass and velocity there.
  struct Node {
    std::int64_t key = -1;
    double mass = 0.0;
    Vec3 velocity;
    std::array<int, 3> node{};
  };

  // On ranks: this rank's contacts with their nodes to every rank, every rank's taken in rank
  // order; a row per distinct key (a node's copies carry the same bits, whichever rank sent
  // them), with this rank's slot of it where it holds the node's block.
  void rows_of_every_rank(const core::BackgroundGrid& g, core::RankLink& ranks) {
    const std::size_t per_field = g.slot_count();
    const std::int64_t fields = g.field_count();
    nodes_.resize(slots_.size());
    for (std::size_t e = 0; e < slots_.size(); ++e) {
      Node& n = nodes_[e];
      n = Node{};
      if (slots_[e] < 0) continue;
      const auto su = static_cast<std::size_t>(slots_[e]);
      const std::size_t slot = su % per_field, field = su / per_field;
      const std::int64_t block = g.active_block(slot / core::BackgroundGrid::block_nodes);
      const auto local = static_cast<std::int64_t>(slot % core::BackgroundGrid::block_nodes);
      n.key = (block * core::BackgroundGrid::block_nodes + local) * fields +
              static_cast<std::int64_t>(field);
      n.mass = g.mass[su];
      n.velocity = g.velocity_new[su];
      n.node = g.node_of_slot(slot);
    }
    pack_mine();
    ranks.gather_into(buffer_, every_, false);
    contacts_.clear();
    weights_.clear();
    nodes_.clear();
    for (const std::vector<std::byte>& in : every_) unpack(in);
    by_key_.clear();
    for (std::size_t e = 0; e < nodes_.size(); ++e)
      if (nodes_[e].key >= 0) by_key_.emplace_back(nodes_[e].key, e);
    std::sort(by_key_.begin(), by_key_.end());
    row_.assign(nodes_.size(), -1);
    const FaceConstraints faces(g);
    for (std::size_t i = 0; i < by_key_.size(); ++i) {
      const auto [key, e] = by_key_[i];
      if (i == 0 || key != by_key_[i - 1].first) {
        const Node& n = nodes_[e];
        const std::int64_t field = key % fields, node = key / fields;
        const std::int32_t active = g.active_number(node / core::BackgroundGrid::block_nodes);
        row_slot_.push_back(active < 0 ? -1
                                       : field * static_cast<std::int64_t>(per_field) +
                                             static_cast<std::int64_t>(active) *
                                                 core::BackgroundGrid::block_nodes +
                                             node % core::BackgroundGrid::block_nodes);
        velocity.push_back(n.velocity);
        mass.push_back(n.mass);
        constraint.push_back(faces(n.node));
      }
      row_[e] = static_cast<std::int32_t>(row_slot_.size() - 1);
    }
  }
  void pack_mine() {
    const std::uint64_t n = contacts_.size();
    const std::size_t bytes_c = n * sizeof(Contact), bytes_w = weights_.size() * sizeof(double);
    buffer_.resize(sizeof n + bytes_c + bytes_w + nodes_.size() * sizeof(Node));
    std::byte* at = buffer_.data();
    std::memcpy(at, &n, sizeof n);
    if (n == 0) return;
    std::memcpy(at + sizeof n, contacts_.data(), bytes_c);
    std::memcpy(at + sizeof n + bytes_c, weights_.data(), bytes_w);
    std::memcpy(at + sizeof n + bytes_c + bytes_w, nodes_.data(), nodes_.size() * sizeof(Node));
  }
  void unpack(const std::vector<std::byte>& in) {
    std::uint64_t n = 0;
    if (in.size() < sizeof n) throw std::logic_error("ContactNodes: a rank sent no contact count");
    std::memcpy(&n, in.data(), sizeof n);
    const std::size_t entries = n * static_cast<std::size_t>(k_);
    const std::size_t bytes_c = n * sizeof(Contact), bytes_w = entries * sizeof(double);
    if (in.size() != sizeof n + bytes_c + bytes_w + entries * sizeof(Node))
      throw std::logic_error("ContactNodes: a rank's contacts have another stencil size");
    if (n == 0) return;
    const std::size_t c0 = contacts_.size(), e0 = weights_.size();
    contacts_.resize(c0 + n);
    weights_.resize(e0 + entries);
    nodes_.resize(e0 + entries);
    std::memcpy(contacts_.data() + c0, in.data() + sizeof n, bytes_c);
    std::memcpy(weights_.data() + e0, in.data() + sizeof n + bytes_c, bytes_w);
    std::memcpy(nodes_.data() + e0, in.data() + sizeof n + bytes_c + bytes_w,
                entries * sizeof(Node));
  }

  int k_ = 0;
  // The contacts as added (on ranks, after finish: every rank's), their stencil entries'
  // field slots (this rank's) and weights, and each entry's row; the contacts' id order.
  std::vector<Contact> contacts_;
  std::vector<std::int64_t> slots_;
  std::vector<double> weights_;
  std::vector<std::int32_t> row_;
  std::vector<std::size_t> order_;
  // Each row's field slot on this rank (-1: a node of a block it does not hold).
  std::vector<std::int64_t> row_slot_;
  // One process: the row of each field slot (all -1 between steps).
  std::vector<std::int32_t> row_of_slot_;
  // Ranks: the entries' nodes, the buffers sent and received, the entries by key.
  std::vector<Node> nodes_;
  std::vector<std::byte> buffer_;
  std::vector<std::vector<std::byte>> every_;
  std::vector<std::pair<std::int64_t, std::size_t>> by_key_;
};

}  // namespace afemp::mpm
