// The MPI ranks (core/mpi/ranks.hpp) on 1 to 4 ranks: sums added in rank order hold the serial
// fold's bits on every rank, and an exchange and a gather deliver what was sent, to the byte. Every
// check is an EXPECT: a rank that failed one still takes part in the collective calls that follow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "core/mpi/ranks.hpp"

namespace afemp::core {
namespace {

// Rank r's value: ranks 1 and 2 hold +-1e16, where a double's spacing is 2, so the order of the
// additions decides the result (k = 1 on 4 ranks: ((v_0 + v_1) + v_2) + v_3 = 2.51, the
// pairwise (v_0 + v_1) + (v_2 + v_3) = 2.0; on 3 ranks the left fold 2.0, v_0 + (v_1 + v_2) 1.1).
double value_of(int r, int k) {
  const double base[] = {1.0 + 0.1 * k, 1e16, -1e16, 0.5 + 0.01 * k};
  return base[r % 4];
}

// Reference: ((v_0 + v_1) + v_2) + v_3 added here in that order, bit for bit; the same on every
// rank (its smallest and largest over the ranks are equal).
TEST(MpiRanks, SumsAreAddedInRankOrderAndAgreeOnEveryRank) {
  const int n = rank_count(), me = rank_index();
  double fold = value_of(0, 0);
  for (int r = 1; r < n; ++r) fold += value_of(r, 0);
  const double sum = sum_in_rank_order(value_of(me, 0));
  EXPECT_EQ(sum, fold);
  EXPECT_EQ(min_over_ranks(sum), -min_over_ranks(-sum));

  std::vector<double> values(5), folds(5);
  for (int k = 0; k < 5; ++k) {
    values[static_cast<std::size_t>(k)] = value_of(me, k);
    folds[static_cast<std::size_t>(k)] = value_of(0, k);
    for (int r = 1; r < n; ++r) folds[static_cast<std::size_t>(k)] += value_of(r, k);
  }
  sum_in_rank_order(values);
  EXPECT_EQ(values, folds);
  EXPECT_EQ(sum_over_ranks(me + 1), static_cast<std::int64_t>(n) * (n + 1) / 2);
}

// Reference: every rank sends rank r + 1 (around the ring) 100 (r + 1) doubles r * 1000 + k and
// rank r + 2 an empty message; each receives exactly those, ordered by sender, and the bytes
// received over all ranks equal the bytes sent.
TEST(MpiRanks, AnExchangeDeliversEveryMessageToTheByte) {
  const int n = rank_count(), me = rank_index();
  auto payload = [](int from) {
    std::vector<double> v(static_cast<std::size_t>(100 * (from + 1)));
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = from * 1000.0 + static_cast<double>(k);
    return v;
  };
  std::vector<RankMessage> out;
  const std::vector<double> mine = payload(me);
  RankMessage next{(me + 1) % n, std::vector<std::byte>(mine.size() * sizeof(double))};
  std::memcpy(next.bytes.data(), mine.data(), next.bytes.size());
  out.push_back(next);
  if (n > 2) out.push_back({(me + 2) % n, {}});
  const std::vector<RankMessage> in = exchange(out);

  std::vector<int> senders;
  for (int s : {(me + n - 1) % n, (me + n - 2) % n})
    if (s == (me + n - 1) % n || n > 2) senders.push_back(s);
  std::sort(senders.begin(), senders.end());
  senders.erase(std::unique(senders.begin(), senders.end()), senders.end());
  EXPECT_EQ(in.size(), senders.size());
  std::int64_t received = 0, sent = 0;
  for (const RankMessage& m : out) sent += static_cast<std::int64_t>(m.bytes.size());
  for (std::size_t i = 0; i < std::min(in.size(), senders.size()); ++i) {
    EXPECT_EQ(in[i].rank, senders[i]);
    received += static_cast<std::int64_t>(in[i].bytes.size());
    if (in[i].rank != (me + n - 1) % n) {
      EXPECT_TRUE(in[i].bytes.empty());
      continue;
    }
    const std::vector<double> expected = payload(in[i].rank);
    EXPECT_EQ(in[i].bytes.size(), expected.size() * sizeof(double));
    if (in[i].bytes.size() == expected.size() * sizeof(double)) {
      EXPECT_EQ(std::memcmp(in[i].bytes.data(), expected.data(), in[i].bytes.size()), 0);
    }
  }
  EXPECT_EQ(sum_over_ranks(received), sum_over_ranks(sent));
}

// Rank r's bytes for a gather: 1000 (r + 1) + 7 k bytes of value (r + 1) x 31 + k mod 256, so
// that each rank's differ in length and content from call to call.
std::vector<std::byte> gather_bytes_of(int r, int k) {
  return std::vector<std::byte>(static_cast<std::size_t>(1000 * (r + 1) + 7 * k),
                                static_cast<std::byte>(((r + 1) * 31 + k) % 256));
}

// Reference: every rank's bytes, as sent. Gathered to every rank, each rank holds every rank's at
// its index; to rank 0, rank 0 holds them all and another rank its own alone. Three calls into
// the same buffers, the sizes changing between them (the buffers are reused, not appended to).
TEST(MpiRanks, AGatherDeliversEveryRanksBytesToEveryRankOrToRankZero) {
  const int n = rank_count(), me = rank_index();
  std::vector<std::vector<std::byte>> every;
  for (int k = 0; k < 3; ++k) {
    const bool to_rank_0 = k == 1;
    gather_bytes(gather_bytes_of(me, k), every, to_rank_0);
    EXPECT_EQ(every.size(), static_cast<std::size_t>(n));
    for (int r = 0; r < n && r < static_cast<int>(every.size()); ++r) {
      const std::vector<std::byte>& got = every[static_cast<std::size_t>(r)];
      if (to_rank_0 && me != 0 && r != me)
        EXPECT_TRUE(got.empty()) << "call " << k << ", from rank " << r;
      else
        EXPECT_EQ(got, gather_bytes_of(r, k)) << "call " << k << ", from rank " << r;
    }
  }
}

}  // namespace
}  // namespace afemp::core
