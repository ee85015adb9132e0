// The MPI ranks a run divides among (MPI_COMM_WORLD), and what the domain decomposition needs of
// MPI: reductions whose order is fixed (rank 0's value first), so that every rank holds the same
// bits and a run on N ranks repeats itself, and the exchange of byte buffers among neighbours. No
// MPI type appears here: the modules that use it need no MPI headers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/rank_link.hpp"

namespace afemp::core {

// Starts MPI (threads funneled: a rank's OpenMP threads make no MPI call) and ends it; one per
// process, in main, before any other call here.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

int rank_index();  // this process's rank
int rank_count();

// The sum of one value per rank, added in rank order: ((v_0 + v_1) + v_2) + ... on every rank.
double sum_in_rank_order(double value);
// The same for each element (every rank passes as many).
void sum_in_rank_order(std::span<double> values);
double min_over_ranks(double value);
std::int64_t sum_over_ranks(std::int64_t value);

// Every rank calls it with what it sends (at most one message per rank); each receives
// what was sent to it, ordered by sender, the ranks that sent it nothing left out.
std::vector<RankMessage> exchange(std::span<const RankMessage> outgoing);

// Every rank's `mine` into every[r] (RankLink::gather_into): on every rank, or with to_rank_0
// on rank 0 alone. The buffers are resized in place, so that a gather repeated each step
// allocates nothing once their sizes settle.
void gather_bytes(std::span<const std::byte> mine, std::vector<std::vector<std::byte>>& every,
                  bool to_rank_0);

// Rank 0's `bytes` on every rank, in pieces of at most 2^30 bytes (MPI's counts are ints).
void broadcast_bytes(std::vector<std::byte>& bytes);

// Stops every rank of the run with exit status `code` (MPI_Abort): a rank that failed alone
// while the others wait for it in a sum.
[[noreturn]] void abort_ranks(int code);

}  // namespace afemp::core
