// Shared blocks' nodal sums across ranks (shared_block_sums.hpp). A message holds, per block,
// its directory index and then each array's values of the block's 64 nodes field by field.
#include "core/mpi/shared_block_sums.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/mpi/ranks.hpp"

namespace afemp::core {
namespace {

constexpr std::size_t block_nodes = BackgroundGrid::block_nodes;

// The velocity fields an array holds: the grid's, or one (NodalArray::one_field).
int fields_of(const BackgroundGrid& g, const NodalArray& a) {
  return a.one_field ? 1 : g.field_count();
}

// Doubles per block over all arrays and fields.
std::size_t block_values(const BackgroundGrid& g, std::span<const NodalArray> arrays) {
  std::size_t n = 0;
  for (const NodalArray& a : arrays)
    n += static_cast<std::size_t>(a.components) * block_nodes *
         static_cast<std::size_t>(fields_of(g, a));
  return n;
}

// Copies active block a's values out of the grid (to) or into it (from).
void copy_block(const BackgroundGrid& g, std::span<const NodalArray> arrays, std::size_t a,
                double* to, const double* from) {
  for (const NodalArray& array : arrays) {
    const auto c = static_cast<std::size_t>(array.components);
    for (int f = 0; f < fields_of(g, array); ++f) {
      double* at =
          array.data + (static_cast<std::size_t>(f) * g.slot_count() + a * block_nodes) * c;
      const std::size_t n = block_nodes * c;
      if (to != nullptr) {
        std::memcpy(to, at, n * sizeof(double));
        to += n;
      } else {
        std::memcpy(at, from, n * sizeof(double));
        from += n;
      }
    }
  }
}

// Adds a rank's part of a block into `total` (the same layout as copy_block's), or keeps the
// larger value for an array of maxima.
void combine(const BackgroundGrid& g, std::span<const NodalArray> arrays, double* total,
             const double* part) {
  for (const NodalArray& array : arrays) {
    const std::size_t n =
        block_nodes * static_cast<std::size_t>(array.components * fields_of(g, array));
    if (array.largest) {
      for (std::size_t i = 0; i < n; ++i) total[i] = std::max(total[i], part[i]);
    } else if (array.fixed) {  // pairs of doubles' bytes holding one 128-bit integer each
      for (std::size_t i = 0; i < n; i += 2) {
        Fixed a = 0, b = 0;
        std::memcpy(&a, total + i, sizeof a);
        std::memcpy(&b, part + i, sizeof b);
        a += b;
        std::memcpy(total + i, &a, sizeof a);
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) total[i] += part[i];
    }
    total += n;
    part += n;
  }
}

// Appends one block's record: its directory index, then its values.
void append(std::vector<std::byte>& bytes, std::int64_t block, const std::vector<double>& values) {
  const auto* b = reinterpret_cast<const std::byte*>(&block);
  bytes.insert(bytes.end(), b, b + sizeof block);
  const auto* v = reinterpret_cast<const std::byte*>(values.data());
  bytes.insert(bytes.end(), v, v + values.size() * sizeof(double));
}

// The per-rank buffers that are not empty, as messages; exchanged.
std::vector<RankMessage> send(std::vector<std::vector<std::byte>>& to) {
  std::vector<RankMessage> out;
  for (std::size_t r = 0; r < to.size(); ++r)
    if (!to[r].empty()) out.push_back({static_cast<int>(r), std::move(to[r])});
  return exchange(out);
}

}  // namespace

void sum_shared_blocks(BackgroundGrid& grid, std::span<const NodalArray> arrays,
                       const BlockPartition& partition, std::vector<char>* books) {
  const int ranks = rank_count(), me = rank_index();
  if (books) {
    books->resize(grid.active_block_count());
    for (std::size_t a = 0; a < books->size(); ++a)
      (*books)[a] = partition.rank_of(grid.block_coord(grid.active_block(a))) == me ? 1 : 0;
  }
  if (ranks == 1) return;
  const std::size_t per = block_values(grid, arrays);
  const std::size_t record = sizeof(std::int64_t) + per * sizeof(double);
  std::vector<std::vector<std::byte>> to(static_cast<std::size_t>(ranks));
  std::vector<double> values(per);
  for (std::size_t a = 0; a < grid.active_block_count(); ++a) {
    const std::int64_t block = grid.active_block(a);
    const int home = partition.rank_of(grid.block_coord(block));
    if (home == me) continue;
    copy_block(grid, arrays, a, values.data(), nullptr);
    append(to[static_cast<std::size_t>(home)], block, values);
  }
  const std::vector<RankMessage> in = send(to);

  // Each owned block's partial sums, by rank: the senders' in the order received (ascending
  // rank), this rank's own inserted at its place.
  struct Part {
    int rank;
    const double* values;
  };
  std::map<std::int64_t, std::vector<Part>> parts;
  std::size_t records = 0;
  for (const RankMessage& m : in) records += m.bytes.size() / record;
  std::vector<double> received(records * per), own;
  double* next = received.data();
  for (const RankMessage& m : in)
    for (std::size_t at = 0; at < m.bytes.size(); at += record, next += per) {
      std::int64_t block = 0;
      std::memcpy(&block, m.bytes.data() + at, sizeof block);
      std::memcpy(next, m.bytes.data() + at + sizeof block, per * sizeof(double));
      parts[block].push_back({m.rank, next});
    }
  own.resize(parts.size() * per);
  std::vector<std::vector<std::byte>> reply(static_cast<std::size_t>(ranks));
  std::vector<double> total(per);
  std::size_t k = 0;
  for (auto& [block, list] : parts) {
    const std::int32_t a = grid.active_number(block);
    if (a >= 0) {
      double* mine = own.data() + k * per;
      copy_block(grid, arrays, static_cast<std::size_t>(a), mine, nullptr);
      list.push_back({me, mine});
      std::stable_sort(list.begin(), list.end(),
                       [](const Part& x, const Part& y) { return x.rank < y.rank; });
    }
    ++k;
    std::copy_n(list.front().values, per, total.data());
    for (std::size_t p = 1; p < list.size(); ++p)
      combine(grid, arrays, total.data(), list[p].values);
    if (a >= 0) copy_block(grid, arrays, static_cast<std::size_t>(a), nullptr, total.data());
    // A block this rank owns but does not hold is booked by the lowest rank that holds it
    // (list is in rank order): its reply names the block as -(index + 1).
    for (const Part& p : list)
      if (p.rank != me)
        append(reply[static_cast<std::size_t>(p.rank)],
               a < 0 && p.rank == list.front().rank ? -block - 1 : block, total);
  }
  for (const RankMessage& m : send(reply))
    for (std::size_t at = 0; at < m.bytes.size(); at += record) {
      std::int64_t block = 0;
      std::memcpy(&block, m.bytes.data() + at, sizeof block);
      const bool booked_here = block < 0;
      if (booked_here) block = -block - 1;
      std::memcpy(values.data(), m.bytes.data() + at + sizeof block, per * sizeof(double));
      const auto a = static_cast<std::size_t>(grid.active_number(block));
      copy_block(grid, arrays, a, nullptr, values.data());
      if (books && booked_here) (*books)[a] = 1;
    }
}

}  // namespace afemp::core
