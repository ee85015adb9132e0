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
    mine_.clear();
    mine_nodes_.clear();
  }
  // Adds a contact of this rank with its stencil's field slots (-1: a node that takes no part,
  // weight 0) and weights.
  void add(const Contact& c, std::span<const std::int64_t> slots, std::span<const double> weights,
           const core::BackgroundGrid& g) {
    mine_.push_back(c);
    const std::size_t per_field = g.slot_count();
    for (int k = 0; k < k_; ++k) {
      const std::int64_t s = slots[static_cast<std::size_t>(k)];
      Node n;
      if (s >= 0) {
        const auto su = static_cast<std::size_t>(s);
        const std::size_t slot = su % per_field, field = su / per_field;
        const std::int64_t block = g.active_block(slot / core::BackgroundGrid::block_nodes);
        const auto local = static_cast<std::int64_t>(slot % core::BackgroundGrid::block_nodes);
        n.key = (block * core::BackgroundGrid::block_nodes + local) * g.field_count() +
                static_cast<std::int64_t>(field);
        n.weight = weights[static_cast<std::size_t>(k)];
        n.mass = g.mass[su];
        n.velocity = g.velocity_new[su];
        n.node = g.node_of_slot(slot);
      }
      mine_nodes_.push_back(n);
    }
  }
  // Every rank's contacts (on ranks: collective, called by every rank) in id order, and the
  // rows of their distinct nodes.
  void finish(const core::BackgroundGrid& g, core::RankLink* ranks) {
    contacts_.clear();
    nodes_.clear();
    if (ranks == nullptr) {
      contacts_.swap(mine_);
      nodes_.swap(mine_nodes_);
    } else {
      pack_mine();
      ranks->gather_into(buffer_, every_, false);
      for (const std::vector<std::byte>& in : every_) unpack(in);
    }
    // Id order (stable: ids are unique, and a tie would keep rank order).
    order_.resize(contacts_.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) {
      return contacts_[a].id < contacts_[b].id;
    });
    sorted_.clear();
    sorted_nodes_.clear();
    const auto k = static_cast<std::size_t>(k_);
    for (std::size_t c : order_) {
      sorted_.push_back(contacts_[c]);
      sorted_nodes_.insert(sorted_nodes_.end(), nodes_.begin() + static_cast<std::ptrdiff_t>(c * k),
                           nodes_.begin() + static_cast<std::ptrdiff_t>((c + 1) * k));
    }
    // Rows: one per distinct node (a node's copies carry the same bits, whichever rank sent
    // them).
    by_key_.clear();
    for (std::size_t e = 0; e < sorted_nodes_.size(); ++e)
      if (sorted_nodes_[e].key >= 0) by_key_.emplace_back(sorted_nodes_[e].key, e);
    std::sort(by_key_.begin(), by_key_.end());
    row_.assign(sorted_nodes_.size(), -1);
    keys_.clear();
    velocity.clear();
    mass.clear();
    constraint.clear();
    const FaceConstraints faces(g);
    for (std::size_t i = 0; i < by_key_.size(); ++i) {
      const Node& n = sorted_nodes_[by_key_[i].second];
      if (i == 0 || by_key_[i].first != by_key_[i - 1].first) {
        keys_.push_back(n.key);
        velocity.push_back(n.velocity);
        mass.push_back(n.mass);
        constraint.push_back(faces(n.node));
      }
      row_[by_key_[i].second] = static_cast<std::int32_t>(keys_.size() - 1);
    }
  }

  std::size_t size() const { return sorted_.size(); }
  Contact& operator[](std::size_t c) { return sorted_[c]; }
  const Contact& operator[](std::size_t c) const { return sorted_[c]; }
  // Node k of contact c: its row (-1: none) and weight.
  std::int32_t row(std::size_t c, int k) const {
    return row_[c * static_cast<std::size_t>(k_) + static_cast<std::size_t>(k)];
  }
  double weight(std::size_t c, int k) const {
    return sorted_nodes_[c * static_cast<std::size_t>(k_) + static_cast<std::size_t>(k)].weight;
  }

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
    const std::int64_t fields = g.field_count();
    const std::size_t per_field = g.slot_count();
    for (std::size_t r = 0; r < keys_.size(); ++r) {
      const std::int64_t key = keys_[r];
      const std::int64_t field = key % fields, node = key / fields;
      const std::int32_t active = g.active_number(node / core::BackgroundGrid::block_nodes);
      if (active < 0) continue;
      const std::size_t slot =
          static_cast<std::size_t>(active) * core::BackgroundGrid::block_nodes +
          static_cast<std::size_t>(node % core::BackgroundGrid::block_nodes);
      g.velocity_new[static_cast<std::size_t>(field) * per_field + slot] = velocity[r];
    }
  }

  // Each row's velocity, mass and face conditions, swept in place.
  std::vector<Vec3> velocity;
  std::vector<double> mass;
  std::vector<NodeConstraint> constraint;

 private:
  // A stencil node as a contact carries it: its key (block, node in the block, field; -1: none),
  // weight, and the grid's mass and velocity there.
  struct Node {
    std::int64_t key = -1;
    double weight = 0.0, mass = 0.0;
    Vec3 velocity;
    std::array<int, 3> node{};
  };

  void pack_mine() {
    const std::uint64_t n = mine_.size();
    buffer_.resize(sizeof n + n * sizeof(Contact) + mine_nodes_.size() * sizeof(Node));
    std::byte* at = buffer_.data();
    std::memcpy(at, &n, sizeof n);
    if (n > 0) {
      std::memcpy(at + sizeof n, mine_.data(), n * sizeof(Contact));
      std::memcpy(at + sizeof n + n * sizeof(Contact), mine_nodes_.data(),
                  mine_nodes_.size() * sizeof(Node));
    }
  }
  void unpack(const std::vector<std::byte>& in) {
    std::uint64_t n = 0;
    if (in.size() < sizeof n) throw std::logic_error("ContactNodes: a rank sent no contact count");
    std::memcpy(&n, in.data(), sizeof n);
    const std::size_t nodes = n * static_cast<std::size_t>(k_);
    if (in.size() != sizeof n + n * sizeof(Contact) + nodes * sizeof(Node))
      throw std::logic_error("ContactNodes: a rank's contacts have another stencil size");
    const std::size_t c0 = contacts_.size(), n0 = nodes_.size();
    contacts_.resize(c0 + n);
    nodes_.resize(n0 + nodes);
    if (n == 0) return;
    std::memcpy(contacts_.data() + c0, in.data() + sizeof n, n * sizeof(Contact));
    std::memcpy(nodes_.data() + n0, in.data() + sizeof n + n * sizeof(Contact),
                nodes * sizeof(Node));
  }

  int k_ = 0;
  std::vector<Contact> mine_, contacts_, sorted_;
  std::vector<Node> mine_nodes_, nodes_, sorted_nodes_;
  std::vector<std::size_t> order_;
  std::vector<std::pair<std::int64_t, std::size_t>> by_key_;
  std::vector<std::int32_t> row_;
  std::vector<std::int64_t> keys_;
  std::vector<std::byte> buffer_;
  std::vector<std::vector<std::byte>> every_;
};

}  // namespace afemp::mpm
