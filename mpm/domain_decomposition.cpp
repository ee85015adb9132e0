// The MPM run divided among ranks by the grid's blocks (Berger & Bokhari 1987 for the recursive
// coordinate bisection, core/grid/block_partition.hpp): a particle lives on the rank of its
// cell's block; each rank scatters its own particles and the blocks that several ranks reach are
// summed across them (core/rank_link.hpp), so that the grid update, G2P and the stress update run
// unchanged on each rank; after each step the particles that crossed into another rank's block
// move there through the point-state schema (particle_migration.hpp). docs/parallel.md has the
// design.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <stdexcept>

#include "mpm/mpm_solver.hpp"
#include "mpm/particle_migration.hpp"

namespace afemp::mpm {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool finite(const Vec3& x) {
  return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
}

// The cell of a point, or {-1, -1, -1} for a point that is not finite (outside every grid).
std::array<int, 3> cell_of_point(const core::BackgroundGrid& g, const Vec3& x) {
  return finite(x) ? g.cell_of(x) : std::array<int, 3>{-1, -1, -1};
}

// The blocks of `weight` split among `ranks` by recursive bisection of their weights, in the
// map's order of blocks: every rank that passes the same map finds the same partition.
core::BlockPartition bisect_weighted(const std::map<core::BlockCoord, double>& weight, int ranks) {
  std::vector<core::BlockCoord> blocks;
  std::vector<double> weights;
  for (const auto& [b, w] : weight) {
    blocks.push_back(b);
    weights.push_back(w);
  }
  return core::bisect_blocks(blocks, weights, ranks);
}

std::vector<std::int32_t> first_indices(std::size_t n) {
  std::vector<std::int32_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  return all;
}

}  // namespace

void MpmSolver::divide_among_ranks(core::RankLink& link, const core::RankBalance& balance) {
  if (balance.cost != core::RankBalance::Cost::off &&
      (balance.every < 1 || !(balance.imbalance >= 1.0)))
    throw std::invalid_argument("rank balance: every " + std::to_string(balance.every) +
                                " steps above " + std::to_string(balance.imbalance) +
                                " x the mean: give every >= 1 and an imbalance >= 1");
  if (axisymmetric_)
    throw core::InputError(scene_.grid_where, "grid.axisymmetric",
                           "an axisymmetric grid runs on one process (its rings are not divided "
                           "among ranks); run it without mpirun");
  balance_ = balance;
  ranks_ = &link;
  try {
    keep_own_particles();
  } catch (...) {
    ranks_ = nullptr;
    throw;
  }
}

void MpmSolver::keep_own_particles() {
  // Every rank holds the same particles here (a scene's generation, a checkpoint's), so every
  // rank finds the same blocks and weights, and the same partition.
  const std::vector<Vec3>& x = weight_positions();
  std::map<core::BlockCoord, double> count;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const auto c = cell_of_point(grid_, x[i]);
    if (!grid_.inside(c))
      throw std::invalid_argument("particle " + std::to_string(particles_.id[i]) +
                                  " lies outside the grid: no rank can hold it");
    count[grid_.block_of_cell(c)] += 1.0;
  }
  // Mesh nodes on the grid (a coupling) weigh as particles: the rank of their block scatters
  // them, and a converting mesh's particles appear there.
  if (points_)
    for (const Vec3& y : points_->positions()) {
      const auto c = cell_of_point(grid_, y);
      if (grid_.inside(c)) count[grid_.block_of_cell(c)] += 1.0;
    }
  const int ranks = ranks_->ranks();
  if (count.size() < static_cast<std::size_t>(ranks))
    throw std::invalid_argument(
        std::to_string(ranks) + " ranks for " + std::to_string(count.size()) +
        " grid blocks that hold particles or mesh nodes (a block is 4 x 4 x 4 nodes): at most " +
        std::to_string(count.size()) + " ranks, or a finer grid");
  partition_ = bisect_weighted(count, ranks);
  whole_count_ = particles_.size();
  const int me = ranks_->rank();
  std::vector<std::int32_t> kept;
  for (std::size_t i = 0; i < particles_.size(); ++i)
    if (partition_.rank_of(grid_.block_of_cell(grid_.cell_of(x[i]))) == me)
      kept.push_back(static_cast<std::int32_t>(i));
  particles_.select(kept);
  if (!fused_kinematics()) velocity_gradient_.resize(particles_.size());
  reorder_particles();
  signal_speed_ = max_signal_parts();
  balance_stage_mark_ = std::accumulate(stage_seconds_.begin(), stage_seconds_.end(), 0.0);
  balance_sum_mark_ = sum_seconds_;
}

void MpmSolver::balance_ranks() {
  const auto t0 = std::chrono::steady_clock::now();
  const int ranks = ranks_->ranks(), me = ranks_->rank();
  const auto r = static_cast<std::size_t>(me), n = static_cast<std::size_t>(ranks);
  // This rank's cost since the last check, and its particles: every rank's, on every rank.
  const double stages = std::accumulate(stage_seconds_.begin(), stage_seconds_.end(), 0.0);
  const double seconds = (stages - balance_stage_mark_) - (sum_seconds_ - balance_sum_mark_);
  balance_stage_mark_ = stages;
  balance_sum_mark_ = sum_seconds_;
  const bool by_time = balance_.cost == core::RankBalance::Cost::time;
  std::vector<double> each(2 * n, 0.0);
  each[r] = by_time ? std::max(seconds, 0.0) : static_cast<double>(particles_.size());
  each[n + r] = static_cast<double>(particles_.size());
  ranks_->sum_in_rank_order(each);
  double total = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    total += each[k];
    worst = std::max(worst, each[k]);
  }
  const double mean = total / static_cast<double>(ranks);
  const double imbalance = mean > 0.0 ? worst / mean : 1.0;
  if (!(imbalance > balance_.imbalance)) {
    balance_seconds_ += seconds_since(t0);
    return;
  }
  // Each block weighted by its particles times its rank's cost per particle (every particle of
  // a block lives on the block's rank), sent to every rank, so that every rank splits the same
  // blocks with the same weights into the same partition.
  const double per_particle = each[n + r] > 0.0 ? each[r] / each[n + r] : 0.0;
  std::map<core::BlockCoord, double> weight;
  const std::vector<Vec3>& x = weight_positions();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const auto c = cell_of_point(grid_, x[i]);
    if (grid_.inside(c)) weight[grid_.block_of_cell(c)] += per_particle;
  }
  std::vector<std::byte> mine;
  for (const auto& [b, w] : weight) {
    const std::byte* at = reinterpret_cast<const std::byte*>(b.data());
    mine.insert(mine.end(), at, at + sizeof(core::BlockCoord));
    at = reinterpret_cast<const std::byte*>(&w);
    mine.insert(mine.end(), at, at + sizeof(double));
  }
  const std::vector<std::vector<std::byte>> every = ranks_->gather(mine);
  for (int k = 0; k < ranks; ++k) {
    if (k == me) continue;
    const std::vector<std::byte>& in = every[static_cast<std::size_t>(k)];
    for (std::size_t at = 0; at + sizeof(core::BlockCoord) + sizeof(double) <= in.size();
         at += sizeof(core::BlockCoord) + sizeof(double)) {
      core::BlockCoord b;
      double w = 0.0;
      std::memcpy(b.data(), in.data() + at, sizeof b);
      std::memcpy(&w, in.data() + at + sizeof b, sizeof w);
      weight[b] += w;
    }
  }
  // Fewer blocks than ranks hold particles now (the material gathered): the partition stays.
  if (weight.size() < n) {
    balance_seconds_ += seconds_since(t0);
    return;
  }
  partition_ = bisect_weighted(weight, ranks);
  ++rebalances_;
  migrate_particles();
  balance_seconds_ += seconds_since(t0);
}

void MpmSolver::sum_shared_blocks(std::span<const core::NodalArray> arrays) {
  const auto t0 = std::chrono::steady_clock::now();
  // The sums also say which blocks this rank books (owned_block_): its own, and those whose
  // owner holds none of their nodes and this rank is the lowest that does.
  ranks_->sum_shared_blocks(grid_, arrays, partition_, &owned_block_);
  const double seconds = seconds_since(t0);
  rank_seconds_ += seconds;
  sum_seconds_ += seconds;
}

void MpmSolver::migrate_particles() {
  const auto t0 = std::chrono::steady_clock::now();
  Particles& p = particles_;
  const int me = ranks_->rank();
  const std::vector<Vec3>& x = weight_positions();
  std::vector<std::vector<std::int32_t>> to(static_cast<std::size_t>(ranks_->ranks()));
  std::vector<std::int32_t> kept;
  kept.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    // A point outside the grid stays: the next binning stops the run naming it.
    const auto c = cell_of_point(grid_, x[i]);
    const int r = grid_.inside(c) ? partition_.rank_of(grid_.block_of_cell(c)) : me;
    (r == me ? kept : to[static_cast<std::size_t>(r)]).push_back(static_cast<std::int32_t>(i));
  }
  std::vector<core::RankMessage> out;
  for (std::size_t r = 0; r < to.size(); ++r)
    if (!to[r].empty()) out.push_back({static_cast<int>(r), pack_particles(p, to[r])});
  const std::vector<core::RankMessage> in = ranks_->exchange(out);
  particles_sent_ += static_cast<long>(p.size() - kept.size());
  const bool changed = kept.size() != p.size() || !in.empty();
  if (kept.size() != p.size()) p.select(kept);
  for (const core::RankMessage& m : in) unpack_particles(p, m.bytes);
  if (changed) {
    if (!fused_kinematics()) velocity_gradient_.resize(p.size());
    // The material batches need each material contiguous: arrivals of a material the end of
    // the arrays does not hold are sorted in, keeping every other order (cell order returns at
    // the next reordering).
    if (std::is_sorted(p.material.begin(), p.material.end())) {
      rebuild_batches();
    } else {
      std::vector<std::int32_t> perm = first_indices(p.size());
      std::stable_sort(perm.begin(), perm.end(), [&](std::int32_t a, std::int32_t b) {
        return p.material[static_cast<std::size_t>(a)] < p.material[static_cast<std::size_t>(b)];
      });
      p.permute(perm);
      rebuild_batches();
    }
  }
  rank_seconds_ += seconds_since(t0);
}

std::vector<double> MpmSolver::values_of_every_rank(std::span<const double> values) const {
  if (ranks_ == nullptr) return {values.begin(), values.end()};
  std::vector<double> all;
  all.reserve(values.size() * static_cast<std::size_t>(ranks_->ranks()));
  for (const std::vector<std::byte>& in : ranks_->gather(core::bytes_of(values))) {
    if (in.size() != values.size_bytes())
      throw std::logic_error("values_of_every_rank: ranks passed arrays of different lengths");
    const auto* at = reinterpret_cast<const double*>(in.data());
    all.insert(all.end(), at, at + values.size());
  }
  return all;
}

Particles MpmSolver::gathered_particles(bool on_every_rank) const {
  const Particles& p = particles_;
  const std::vector<std::int32_t> all = first_indices(p.size());
  Particles out;
  out.optional_fields = p.optional_fields;
  out.history_count = p.history_count;
  const std::vector<std::byte> mine = pack_particles(p, all);
  if (ranks_) {
    // In rank order (the order only breaks ties of the sort).
    const std::vector<std::vector<std::byte>> every = ranks_->gather(mine, !on_every_rank);
    if (ranks_->rank() != 0 && !on_every_rank) return out;
    for (const std::vector<std::byte>& in : every) unpack_particles(out, in);
  } else {
    unpack_particles(out, mine);
  }
  std::vector<std::int32_t> order = first_indices(out.size());
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return out.id[static_cast<std::size_t>(a)] < out.id[static_cast<std::size_t>(b)];
  });
  out.permute(order);
  return out;
}

}  // namespace afemp::mpm
