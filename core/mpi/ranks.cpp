// The MPI ranks (ranks.hpp) over MPI_COMM_WORLD. The sums gather every rank's values to rank 0,
// which adds them in rank order and sends the result back: MPI_Allreduce may add in any order,
// and different ranks may receive different bits.
#include "core/mpi/ranks.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace afemp::core {
namespace {

void check(int code, const char* call) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string(call) + " failed: " + std::string(text, length));
}

int as_count(std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("an MPI message of " + std::to_string(n) +
                            " items is past MPI's int count");
  return static_cast<int>(n);
}

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  // Errors come back as codes and are thrown, naming the call.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

MpiSession::~MpiSession() {
  MPI_Finalize();
}

int rank_index() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int rank_count() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

double sum_in_rank_order(double value) {
  sum_in_rank_order(std::span<double>(&value, 1));
  return value;
}

void sum_in_rank_order(std::span<double> values) {
  const int ranks = rank_count();
  const int n = as_count(values.size());
  std::vector<double> all(rank_index() == 0 ? values.size() * static_cast<std::size_t>(ranks) : 0);
  check(MPI_Gather(values.data(), n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, 0, MPI_COMM_WORLD),
        "MPI_Gather");
  if (rank_index() == 0)
    for (std::size_t i = 0; i < values.size(); ++i) {
      double sum = all[i];
      for (int r = 1; r < ranks; ++r) sum += all[static_cast<std::size_t>(r) * values.size() + i];
      values[i] = sum;
    }
  check(MPI_Bcast(values.data(), n, MPI_DOUBLE, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

void abort_ranks(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();  // MPI_Abort does not return; should it, this process still stops
}

double min_over_ranks(double value) {
  double out = value;
  check(MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

std::int64_t sum_over_ranks(std::int64_t value) {
  std::int64_t out = value;
  check(MPI_Allreduce(&value, &out, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

std::vector<RankMessage> exchange(std::span<const RankMessage> outgoing) {
  const int ranks = rank_count();
  std::vector<std::int64_t> send_sizes(static_cast<std::size_t>(ranks), 0);
  std::vector<std::int64_t> receive_sizes(static_cast<std::size_t>(ranks), 0);
  for (const RankMessage& m : outgoing) {
    if (m.rank < 0 || m.rank >= ranks)
      throw std::invalid_argument("exchange: no rank " + std::to_string(m.rank) + " among " +
                                  std::to_string(ranks));
    std::int64_t& size = send_sizes[static_cast<std::size_t>(m.rank)];
    if (size != 0)
      throw std::invalid_argument("exchange: two messages to rank " + std::to_string(m.rank));
    size = static_cast<std::int64_t>(m.bytes.size()) + 1;
  }
  // A size of s + 1 says "a message of s bytes", 0 "none": an empty message still arrives.
  check(MPI_Alltoall(send_sizes.data(), 1, MPI_INT64_T, receive_sizes.data(), 1, MPI_INT64_T,
                     MPI_COMM_WORLD),
        "MPI_Alltoall");
  std::vector<RankMessage> incoming;
  std::vector<MPI_Request> requests;
  for (int r = 0; r < ranks; ++r) {
    const std::int64_t size = receive_sizes[static_cast<std::size_t>(r)];
    if (size == 0) continue;
    incoming.push_back({r, std::vector<std::byte>(static_cast<std::size_t>(size - 1))});
  }
  requests.reserve(incoming.size() + outgoing.size());
  for (RankMessage& m : incoming) {
    requests.emplace_back();
    check(MPI_Irecv(m.bytes.data(), as_count(m.bytes.size()), MPI_BYTE, m.rank, 0, MPI_COMM_WORLD,
                    &requests.back()),
          "MPI_Irecv");
  }
  for (const RankMessage& m : outgoing) {
    requests.emplace_back();
    check(MPI_Isend(m.bytes.data(), as_count(m.bytes.size()), MPI_BYTE, m.rank, 0, MPI_COMM_WORLD,
                    &requests.back()),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
        "MPI_Waitall");
  return incoming;
}

void gather_bytes(std::span<const std::byte> mine, std::vector<std::vector<std::byte>>& every,
                  bool to_rank_0) {
  const int ranks = rank_count(), me = rank_index();
  const auto mine_size = static_cast<std::int64_t>(mine.size());
  std::vector<std::int64_t> sizes(static_cast<std::size_t>(ranks), 0);
  if (to_rank_0)
    check(MPI_Gather(&mine_size, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, 0, MPI_COMM_WORLD),
          "MPI_Gather");
  else
    check(MPI_Allgather(&mine_size, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, MPI_COMM_WORLD),
          "MPI_Allgather");
  every.resize(static_cast<std::size_t>(ranks));
  const bool receives = !to_rank_0 || me == 0;
  std::vector<MPI_Request> requests;
  for (int r = 0; r < ranks; ++r) {
    std::vector<std::byte>& in = every[static_cast<std::size_t>(r)];
    if (r == me) {
      in.assign(mine.begin(), mine.end());
    } else if (!receives) {
      in.clear();
    } else {
      in.resize(static_cast<std::size_t>(sizes[static_cast<std::size_t>(r)]));
      requests.emplace_back();
      check(MPI_Irecv(in.data(), as_count(in.size()), MPI_BYTE, r, 1, MPI_COMM_WORLD,
                      &requests.back()),
            "MPI_Irecv");
    }
  }
  for (int r = 0; r < ranks; ++r) {
    if (r == me || (to_rank_0 && r != 0)) continue;
    requests.emplace_back();
    check(MPI_Isend(mine.data(), as_count(mine.size()), MPI_BYTE, r, 1, MPI_COMM_WORLD,
                    &requests.back()),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE),
        "MPI_Waitall");
}

void broadcast_bytes(std::vector<std::byte>& bytes) {
  auto size = static_cast<std::int64_t>(bytes.size());
  check(MPI_Bcast(&size, 1, MPI_INT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  bytes.resize(static_cast<std::size_t>(size));
  constexpr std::size_t piece = std::size_t{1} << 30;
  for (std::size_t at = 0; at < bytes.size(); at += piece)
    check(MPI_Bcast(bytes.data() + at, as_count(std::min(piece, bytes.size() - at)), MPI_BYTE, 0,
                    MPI_COMM_WORLD),
          "MPI_Bcast");
}

}  // namespace afemp::core
