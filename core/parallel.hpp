// OpenMP helpers: thread count and index without OpenMP, and the static partition used by
// every reduction so that partial sums combine in thread order (same bits for a given
// thread count).
#pragma once

#include <cstddef>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

// Forces a hot loop's helper lambda inline (write it after the parameter list). A loop body
// split into lambdas must compile to the code of the fused loop: left out of line, values
// pass through memory, the compiler contracts fewer a * b + c into fused multiply-adds, and
// the results change in their last bits.
#if defined(__GNUC__)
#define AFEMP_INLINE __attribute__((always_inline))
#else
#define AFEMP_INLINE
#endif

namespace afemp::core {

inline int thread_count() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

inline int thread_index() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

// Sets the threads of the parallel regions that follow (n > 0; no effect without OpenMP).
inline void set_thread_count(int n) {
#ifdef _OPENMP
  if (n > 0) omp_set_num_threads(n);
#else
  (void)n;
#endif
}

// Threads actually running the current parallel region.
inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

// [begin, end) of thread t among T for n items.
inline std::pair<std::size_t, std::size_t> static_range(std::size_t n, int t, int T) {
  const std::size_t tt = static_cast<std::size_t>(t), nt = static_cast<std::size_t>(T);
  return {n * tt / nt, n * (tt + 1) / nt};
}

// Whether a loop over this many items is worth a parallel region: below it, thread start-up
// and barriers cost more than the work, and on a loaded machine far more (a waiting thread
// spins on a core another process needs). Decided per loop from its size, so a given scene
// and thread count always take the same path.
inline bool worth_threads(std::size_t items) {
  return items >= 2048;
}

// Runs body(begin, end, thread) over the static partition of [0, n) among the threads, or as
// one serial chunk (thread 0) when n is not worth_threads: the sweep shape of every loop that
// keeps per-thread partial results.
template <class Body>
void parallel_chunks(std::size_t n, Body&& body) {
  if (!worth_threads(n)) {
    body(std::size_t{0}, n, 0);
    return;
  }
#pragma omp parallel
  {
    const auto [begin, end] = static_range(n, thread_index(), team_size());
    body(begin, end, thread_index());
  }
}
// Bytes a thread's slot is padded to, so partial sums do not share cache lines.
inline constexpr std::size_t cache_line_doubles = 8;

}  // namespace afemp::core
