// Recursive coordinate bisection of the grid's blocks (Berger & Bokhari 1987) and the halo it
// leaves each rank (block_partition.hpp).
#include "core/grid/block_partition.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace afemp::core {
namespace {

struct Bisection {
  std::span<const BlockCoord> blocks;
  std::span<const double> weights;
  BlockPartition& result;

  // Blocks `ids` to ranks [first, first + count); returns the child that names them (a cut's
  // index, or -1 - rank).
  int split(std::vector<std::size_t>& ids, int first, int count) {
    if (count == 1) {
      for (std::size_t i : ids) {
        result.owner[i] = first;
        result.load[static_cast<std::size_t>(first)] += weights[i];
      }
      return -1 - first;
    }
    BlockCoord lo = blocks[ids.front()], hi = lo;
    for (std::size_t i : ids)
      for (std::size_t a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], blocks[i][a]);
        hi[a] = std::max(hi[a], blocks[i][a]);
      }
    std::size_t axis = 0;
    for (std::size_t a = 1; a < 3; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    const std::size_t b = (axis + 1) % 3, c = (axis + 2) % 3;
    std::sort(ids.begin(), ids.end(), [&](std::size_t p, std::size_t q) {
      const BlockCoord& u = blocks[p];
      const BlockCoord& v = blocks[q];
      if (u[axis] != v[axis]) return u[axis] < v[axis];
      if (u[b] != v[b]) return u[b] < v[b];
      return u[c] < v[c];
    });
    const int lower = count / 2;
    double total = 0.0;
    for (std::size_t i : ids) total += weights[i];
    const double share = total * lower / count;
    // The cut k (blocks [0, k) below) nearest the share, with at least one block per rank on
    // each side.
    const std::size_t least = static_cast<std::size_t>(lower);
    const std::size_t most = ids.size() - static_cast<std::size_t>(count - lower);
    std::size_t cut = least;
    double below = 0.0;
    for (std::size_t k = 0; k < least; ++k) below += weights[ids[k]];
    double best = std::abs(below - share);
    for (std::size_t k = least; k < most; ++k) {
      below += weights[ids[k]];
      if (std::abs(below - share) < best) {
        best = std::abs(below - share);
        cut = k + 1;
      }
    }
    const auto index = static_cast<int>(result.cuts.size());
    result.cuts.push_back({static_cast<int>(axis), blocks[ids[cut]], 0, 0});
    std::vector<std::size_t> upper(ids.begin() + static_cast<std::ptrdiff_t>(cut), ids.end());
    ids.resize(cut);
    const int lower_child = split(ids, first, lower);
    const int upper_child = split(upper, first + lower, count - lower);
    result.cuts[static_cast<std::size_t>(index)].lower = lower_child;
    result.cuts[static_cast<std::size_t>(index)].upper = upper_child;
    return index;
  }
};

std::uint64_t key_of(const BlockCoord& b) {
  // 21 bits per axis (grids of up to 2^21 - 2 blocks, 8 million cells, along each), shifted
  // past the halo's -1.
  const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) + 1); };
  return (u(b[2]) << 42) | (u(b[1]) << 21) | u(b[0]);
}

}  // namespace

BlockPartition bisect_blocks(std::span<const BlockCoord> blocks, std::span<const double> weights,
                             int ranks) {
  if (ranks < 1 || blocks.size() < static_cast<std::size_t>(ranks) ||
      weights.size() != blocks.size())
    throw std::invalid_argument("bisect_blocks: " + std::to_string(blocks.size()) +
                                " blocks cannot be divided among " + std::to_string(ranks) +
                                " ranks (each rank needs one)");
  BlockPartition result;
  result.owner.assign(blocks.size(), 0);
  result.load.assign(static_cast<std::size_t>(ranks), 0.0);
  std::vector<std::size_t> ids(blocks.size());
  std::iota(ids.begin(), ids.end(), std::size_t{0});
  Bisection{blocks, weights, result}.split(ids, 0, ranks);
  return result;
}

int BlockPartition::rank_of(const BlockCoord& b) const {
  int node = cuts.empty() ? -1 : 0;
  while (node >= 0) {
    const Cut& c = cuts[static_cast<std::size_t>(node)];
    const auto axis = static_cast<std::size_t>(c.axis);
    bool below = false;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = (axis + k) % 3;
      if (b[a] != c.first_upper[a]) {
        below = b[a] < c.first_upper[a];
        break;
      }
    }
    node = below ? c.lower : c.upper;
  }
  return -1 - node;
}

std::vector<RankHalo> rank_halos(std::span<const BlockCoord> blocks, std::span<const int> owner,
                                 int ranks) {
  // Each reached block's reaching ranks, as a sorted list (few per block).
  std::unordered_map<std::uint64_t, std::vector<int>> reached;
  reached.reserve(blocks.size() * 4);
  std::vector<RankHalo> halo(static_cast<std::size_t>(ranks));
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    ++halo[static_cast<std::size_t>(owner[i])].owned;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          std::vector<int>& who =
              reached[key_of({blocks[i][0] + dx, blocks[i][1] + dy, blocks[i][2] + dz})];
          const auto at = std::lower_bound(who.begin(), who.end(), owner[i]);
          if (at == who.end() || *at != owner[i]) who.insert(at, owner[i]);
        }
  }
  std::vector<std::vector<int>> partners(static_cast<std::size_t>(ranks));
  for (const auto& [key, who] : reached)
    for (int r : who) {
      RankHalo& h = halo[static_cast<std::size_t>(r)];
      ++h.reached;
      if (who.size() < 2) continue;
      ++h.shared;
      for (int s : who)
        if (s != r) partners[static_cast<std::size_t>(r)].push_back(s);
    }
  for (std::size_t r = 0; r < partners.size(); ++r) {
    std::vector<int>& p = partners[r];
    std::sort(p.begin(), p.end());
    halo[r].neighbours = static_cast<int>(std::unique(p.begin(), p.end()) - p.begin());
  }
  return halo;
}

}  // namespace afemp::core
