// The explicit FE step divided among MPI ranks by its elements, the nodes kept whole on every
// rank. Each rank updates a share of every batch of elements, runs of 64 dealt round the ranks
// so that a dearer region (a plastic foot, an eroding crater) is shared (the stress update and
// the element forces: the dearest stage of an FE step), then sends what the nodal update and
// the stable step read of its elements (their corner forces, critical steps, volumes and alive
// flags) to every other rank. Every rank then gathers the nodal forces through the same
// incidence lists in the same order and moves every node as one process does: positions and
// velocities are one process's to the bit whatever the rank count, and mesh contact, rigid
// bodies, walls, loads and constraints run on every rank unchanged. The state of an element's
// points stays on its rank until rank 0 gathers it for a frame, the probes or a checkpoint.
//
// What it costs: every rank holds the whole mesh and receives every element's forces each step
// (8 corners x 24 bytes a hexahedron, 2 x 24 a truss), so the scheme serves meshes of up to a
// few million elements on tens of ranks; beyond that the nodes must be divided too, with sums at
// the nodes ranks share (docs/parallel.md says so).
#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "core/rank_link.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {

namespace {

// A rank's slices of the element arrays, packed into bytes in the order they are visited and
// unpacked in the same order on the receiving rank.
void append_bytes(std::vector<std::byte>& out, std::span<const std::byte> bytes) {
  out.insert(out.end(), bytes.begin(), bytes.end());
}

// Reads the next `to.size()` values from `in` at `at`.
template <class T>
void read_slice(std::span<const std::byte> in, std::size_t& at, std::span<T> to, int rank) {
  if (at + to.size_bytes() > in.size())
    throw std::logic_error("fem element division: rank " + std::to_string(rank) +
                           " sent fewer element values than its share");
  std::memcpy(static_cast<void*>(to.data()), in.data() + at, to.size_bytes());
  at += to.size_bytes();
}

// Records of erosion as bytes: time, kind (0 hexahedron, 1 truss, 2 node), index, id, body,
// energy, mass, the reason's length and its characters.
constexpr const char* kKinds[] = {"hexahedron", "truss", "node"};

int kind_code(const char* kind) {
  for (int k = 0; k < 3; ++k)
    if (std::strcmp(kind, kKinds[k]) == 0) return k;
  throw std::logic_error(std::string("fem element division: erosion record of kind ") + kind);
}

template <class T>
void put(std::vector<std::byte>& out, const T& v) {
  append_bytes(out, std::as_bytes(std::span<const T>(&v, 1)));
}

template <class T>
T take(std::span<const std::byte> in, std::size_t& at) {
  T v{};
  read_slice(in, at, std::span<T>(&v, 1), -1);
  return v;
}

}  // namespace

int FeSolver::rank() const {
  return rank_;
}

void FeSolver::divide_among_ranks(core::RankLink& link) {
  if (steps_ != 0)
    throw std::logic_error("FeSolver::divide_among_ranks: divide before the first step");
  ranks_ = &link;
  rank_ = link.rank();
  rank_count_ = link.ranks();
  // The elements' running sums (their state after a phase or a program's change) stay rank 0's
  // alone: the others add from zero.
  if (link.rank() != 0) {
    plastic_work_ = viscous_work_ = hourglass_work_ = stabilisation_work_ = eroded_energy_ = 0.0;
    std::fill(body_stabilisation_.begin(), body_stabilisation_.end(), 0.0);
  }
  start_exact_sums();
}

void FeSolver::share_element_results() {
  const auto t0 = std::chrono::steady_clock::now();
  const int me = rank(), ranks = ranks_->ranks();
  // Rank r's slices, in a fixed order: per set and batch its share's corner forces, critical
  // steps, volumes and alive flags. A rigid body's elements have none of these that change.
  auto each_slice = [&](int r, auto&& forces, auto&& values, auto&& flags) {
    for (ElementSet* set : sets_) {
      ElementStore& el = set->store();
      const auto c = static_cast<std::size_t>(set->corners());
      for (const ElementBatch& b : el.batches) {
        if (b.rigid) continue;
        for_each_share(b, r, [&](std::size_t lo, std::size_t hi) {
          forces(std::span<Vec3>(element_force_).subspan(set->first_slot + c * lo, c * (hi - lo)));
          values(std::span<double>(el.critical_dt).subspan(lo, hi - lo));
          values(std::span<double>(el.volume).subspan(lo, hi - lo));
          flags(*set, lo, std::span<std::uint8_t>(el.alive).subspan(lo, hi - lo));
        });
      }
    }
  };
  std::vector<std::byte>& mine = rank_send_;
  mine.clear();
  const auto pack = [&](auto s) { append_bytes(mine, std::as_bytes(s)); };
  each_slice(me, pack, pack, [&](ElementSet&, std::size_t, auto s) { pack(s); });
  ranks_->gather_into(mine, rank_receive_, false);
  const std::vector<std::vector<std::byte>>& every = rank_receive_;
  std::vector<std::size_t> lost;  // allocates only when an element eroded
  for (int r = 0; r < ranks; ++r) {
    if (r == me) continue;
    const std::span<const std::byte> in = every[static_cast<std::size_t>(r)];
    std::size_t at = 0;
    const auto read = [&](auto s) { read_slice(in, at, s, r); };
    // An element whose flag went down eroded on its rank (which booked its energy and wrote
    // its record): here it leaves the mesh's surfaces and the node masses (finish_erosion).
    each_slice(r, read, read, [&](ElementSet& set, std::size_t lo, std::span<std::uint8_t> alive) {
      if (at + alive.size() > in.size())
        throw std::logic_error("fem element division: rank " + std::to_string(r) +
                               " sent fewer element values than its share");
      lost.clear();
      for (std::size_t k = 0; k < alive.size(); ++k) {
        const auto flag = static_cast<std::uint8_t>(in[at + k]);
        if (alive[k] != 0 && flag == 0) lost.push_back(lo + k);
        alive[k] = flag;
      }
      at += alive.size();
      if (!lost.empty()) {
        set.eroded(lost);
        erosion_this_step_ = true;
      }
    });
    if (at != in.size())
      throw std::logic_error("fem element division: rank " + std::to_string(r) +
                             " sent more element values than its share");
  }
  share_retirements();
  exchange_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void FeSolver::share_retirements() {
  if (!retirement_.set) return;  // no converting body (set_retirement_domain)
  // Rank r's records: per hexahedron it retired this step, its index, id, body, time, reason
  // and its points' arrays (the schema's), which the particles made of it inherit.
  HexElements& el = hexes_;
  auto points = [&](std::size_t e, auto&& f) {
    const ElementBatch& b = batch_of(el, e);
    const auto ppe = static_cast<std::size_t>(b.points_per_element);
    const std::size_t p0 = b.point_begin + (e - b.begin) * ppe;
    for_each_point_field(el, [&](const PointField&, auto& a, std::size_t width) {
      if (!a.empty()) f(std::span(a).subspan(p0 * width, ppe * width));
    });
  };
  std::vector<std::byte>& mine = rank_send_;
  mine.clear();
  for (const RetiredElement& ev : retired_) {
    put(mine, static_cast<std::uint64_t>(ev.element));
    put(mine, ev.id);
    put(mine, ev.body);
    put(mine, ev.time);
    const std::string_view reason(ev.reason);
    put(mine, static_cast<std::uint64_t>(reason.size()));
    append_bytes(mine, core::bytes_of(reason));
    points(ev.element, [&](auto s) { append_bytes(mine, std::as_bytes(s)); });
  }
  ranks_->gather_into(mine, rank_receive_, false);
  const int me = rank();
  for (int r = 0; r < ranks_->ranks(); ++r) {
    if (r == me) continue;
    const std::span<const std::byte> in = rank_receive_[static_cast<std::size_t>(r)];
    for (std::size_t at = 0; at < in.size();) {
      RetiredElement ev;
      ev.element = static_cast<std::size_t>(take<std::uint64_t>(in, at));
      ev.id = take<std::int64_t>(in, at);
      ev.body = take<int>(in, at);
      ev.time = take<double>(in, at);
      const auto length = static_cast<std::size_t>(take<std::uint64_t>(in, at));
      if (at + length > in.size() || ev.element >= el.size())
        throw std::logic_error("fem element division: a cut retirement record from rank " +
                               std::to_string(r));
      ev.reason =
          reasons_.emplace(reinterpret_cast<const char*>(in.data() + at), length).first->c_str();
      at += length;
      points(ev.element, [&](auto s) { read_slice(in, at, s, r); });
      for (std::size_t a = 0; a < 8; ++a)
        converted_node_[static_cast<std::size_t>(el.nodes[ev.element][a])] = 1;
      el.bulk_q[ev.element] = 0.0;
      retired_.push_back(ev);
    }
  }
  std::stable_sort(
      retired_.begin(), retired_.end(),
      [](const RetiredElement& a, const RetiredElement& b) { return a.element < b.element; });
}

void FeSolver::gather_elements() const {
  if (ranks_ == nullptr) return;
  // Rank 0's copies of the other ranks' elements are read by nothing of its own update: they are
  // brought up to date for what it writes, which is why a const call may change them.
  auto& self = const_cast<FeSolver&>(*this);
  const int me = rank(), ranks = ranks_->ranks();
  // Rank r's slices: per set and batch its share's points (every array of the schema the scene
  // keeps) and the hexahedra's own state.
  auto each_slice = [&](int r, auto&& f) {
    for (ElementSet* set : self.sets_) {
      ElementStore& el = set->store();
      for (const ElementBatch& b : el.batches) {
        if (b.rigid) continue;
        const auto ppe = static_cast<std::size_t>(b.points_per_element);
        for_each_share(b, r, [&](std::size_t lo, std::size_t hi) {
          const std::size_t p0 = b.point_begin + (lo - b.begin) * ppe;
          const std::size_t p1 = b.point_begin + (hi - b.begin) * ppe;
          for_each_point_field(el, [&](const PointField&, auto& a, std::size_t width) {
            if (!a.empty()) f(std::span(a).subspan(p0 * width, (p1 - p0) * width));
          });
          if (set == &self.hexes_) {
            HexElements& h = self.hexes_;
            f(std::span(h.bulk_q).subspan(lo, hi - lo));
            if (!h.hourglass_force.empty()) f(std::span(h.hourglass_force).subspan(lo, hi - lo));
            if (!h.hourglass_power.empty()) f(std::span(h.hourglass_power).subspan(lo, hi - lo));
          }
        });
      }
    }
  };
  std::vector<std::byte>& mine = self.rank_send_;
  mine.clear();
  each_slice(me, [&](auto s) { append_bytes(mine, std::as_bytes(s)); });
  ranks_->gather_into(mine, self.rank_receive_, true);
  const std::vector<std::vector<std::byte>>& every = self.rank_receive_;
  if (me != 0) return;
  for (int r = 1; r < ranks; ++r) {
    const std::span<const std::byte> in = every[static_cast<std::size_t>(r)];
    std::size_t at = 0;
    each_slice(r, [&](auto s) { read_slice(in, at, s, r); });
  }
}

void FeSolver::sum_element_energies(core::Energies& e) const {
  std::vector<double> sums{e.internal,  e.plastic,       e.viscous,
                           e.hourglass, e.stabilisation, e.eroded};
  for (const core::BodySums& b : e.bodies) sums.push_back(b.internal);
  ranks_->sum_in_rank_order(sums);
  e.internal = sums[0];
  e.plastic = sums[1];
  e.viscous = sums[2];
  e.hourglass = sums[3];
  e.stabilisation = sums[4];
  e.eroded = sums[5];
  for (std::size_t b = 0; b < e.bodies.size(); ++b) e.bodies[b].internal = sums[6 + b];
}

void FeSolver::prepare_checkpoint() {
  if (ranks_ == nullptr) return;
  gather_elements();
  if (reproducible()) {
    rank_sums_ = exact_rank_sums(true);
    rank_sums_.ready = true;
    return;
  }
  std::vector<double> sums{plastic_work_, viscous_work_, hourglass_work_, stabilisation_work_,
                           eroded_energy_};
  sums.insert(sums.end(), body_stabilisation_.begin(), body_stabilisation_.end());
  ranks_->sum_in_rank_order(sums);
  RankSums& c = rank_sums_;
  c.plastic = sums[0];
  c.viscous = sums[1];
  c.hourglass = sums[2];
  c.stabilisation = sums[3];
  c.eroded = sums[4];
  c.body_stabilisation.assign(sums.begin() + 5, sums.end());
  c.ready = true;
}

std::vector<ErosionEvent> FeSolver::gather_erosion_events(std::vector<ErosionEvent> mine) const {
  // A node left with no element is found on every rank alike (the flags are shared): rank 0's
  // record is the one kept. Rank 0 puts the records in the order one process gives them.
  std::vector<std::byte> bytes;
  for (const ErosionEvent& ev : mine) {
    const int kind = kind_code(ev.kind);
    if (kind == 2 && rank() != 0) continue;
    put(bytes, ev.time);
    put(bytes, kind);
    put(bytes, static_cast<std::uint64_t>(ev.index));
    put(bytes, ev.id);
    put(bytes, ev.body);
    put(bytes, ev.energy);
    put(bytes, ev.mass);
    put(bytes, static_cast<std::uint64_t>(ev.reason.size()));
    append_bytes(bytes, core::bytes_of(ev.reason));
  }
  const std::vector<std::vector<std::byte>> every = ranks_->gather(bytes, true);
  std::vector<ErosionEvent> out;
  if (rank() != 0) return out;
  for (const std::vector<std::byte>& in : every)
    for (std::size_t at = 0; at < in.size();) {
      ErosionEvent ev;
      ev.time = take<double>(in, at);
      const int kind = take<int>(in, at);
      ev.kind = kKinds[kind];
      ev.index = static_cast<std::size_t>(take<std::uint64_t>(in, at));
      ev.id = take<std::int64_t>(in, at);
      ev.body = take<int>(in, at);
      ev.energy = take<double>(in, at);
      ev.mass = take<double>(in, at);
      const auto length = static_cast<std::size_t>(take<std::uint64_t>(in, at));
      if (at + length > in.size())
        throw std::logic_error("fem element division: a cut erosion record");
      ev.reason.assign(reinterpret_cast<const char*>(in.data() + at), length);
      at += length;
      out.push_back(std::move(ev));
    }
  sort_erosion_events(out);
  return out;
}

void FeSolver::sort_erosion_events(std::vector<ErosionEvent>& events) {
  std::stable_sort(events.begin(), events.end(), [](const ErosionEvent& a, const ErosionEvent& b) {
    if (a.time != b.time) return a.time < b.time;
    const int ka = kind_code(a.kind), kb = kind_code(b.kind);
    if (ka != kb) return ka < kb;
    return a.index < b.index;
  });
}

void FeSolver::truss_axial_range(std::vector<double>& most, std::vector<double>& least) const {
  const std::size_t nb = scene_.bodies.size();
  most.assign(nb, -std::numeric_limits<double>::infinity());
  least.assign(nb, std::numeric_limits<double>::infinity());
  const auto& t = trusses_;
  for (const ElementBatch& b : t.batches)
    for_each_share(b, rank_, [&](std::size_t first, std::size_t last) {
      for (std::size_t e = first; e < last; ++e) {
        if (!t.alive[e]) continue;
        const double axial = t.axial_force(b, e, nodes_.position);
        const auto body = static_cast<std::size_t>(b.body);
        most[body] = std::max(most[body], axial);
        least[body] = std::min(least[body], axial);
      }
    });
  if (ranks_ == nullptr) return;
  for (std::size_t body = 0; body < nb; ++body) {
    most[body] = ranks_->max_over_ranks(most[body]);
    least[body] = -ranks_->max_over_ranks(-least[body]);
  }
}

}  // namespace afemp::fem
