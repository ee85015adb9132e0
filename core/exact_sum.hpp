// Sums that do not depend on the order of their terms, for the reproducible mode of a run
// (`[run] reproducible = true`, docs/parallel.md "The reproducible mode"): the same bits
// whatever the thread count, the rank count or the particles' order in memory.
//
// ExactSum holds the sum of any number of doubles exactly, as one long fixed-point integer
// spanning the whole range of doubles (2^-1074 to past 2^1024) in 32-bit digits kept in 64-bit
// words, so that 2^31 terms add before the carries must be passed on: the "small
// superaccumulator" of Neal (2015), "Fast exact summation using small and large
// superaccumulators", arXiv:1505.05571, section 3. Integer addition is associative, so the sum
// is the same for any order and any grouping; value() rounds it to a double the same way
// every time (within one unit in the last place of the exact sum).
//
// The grid's nodal sums use the narrower 128-bit fixed point below (one scale per array, agreed
// by the ranks): the same associativity, at 16 bytes a value instead of 544.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/parallel.hpp"

namespace afemp::core {

class RankLink;

class ExactSum {
 public:
  static constexpr int digits = 68;  // 68 x 32 bits from 2^-1074: past 2^1024 with room to carry

  void add(double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    auto e = static_cast<int>((bits >> 52) & 0x7ffU);
    if (e == 0x7ff) {  // inf or NaN: the sum is not finite
      finite_ = 0;
      return;
    }
    std::uint64_t m = bits & ((std::uint64_t{1} << 52) - 1U);
    if (e != 0)
      m |= std::uint64_t{1} << 52;  // x = m 2^(e - 1075)
    else
      e = 1;  // subnormal: x = m 2^-1074
    // x = m 2^(offset - 1074): digit i = offset / 32 holds its low bits, shifted by offset % 32.
    const int offset = e - 1;
    const auto i = static_cast<std::size_t>(offset >> 5);
    const int s = offset & 31;
    const std::uint64_t low = m << s;                        // bits 0..63 of m 2^s
    const std::uint64_t high = s == 0 ? 0U : m >> (64 - s);  // bits 64..84
    const auto d0 = static_cast<std::int64_t>(low & 0xffffffffU);
    const auto d1 = static_cast<std::int64_t>(low >> 32);
    const auto d2 = static_cast<std::int64_t>(high);
    if ((bits >> 63) != 0U) {
      d_[i] -= d0;
      d_[i + 1] -= d1;
      d_[i + 2] -= d2;
    } else {
      d_[i] += d0;
      d_[i + 1] += d1;
      d_[i + 2] += d2;
    }
    if (++pending_ == max_pending) normalise();
  }

  void add(const ExactSum& other);
  ExactSum& operator+=(const ExactSum& other) {
    add(other);
    return *this;
  }

  // The sum rounded to a double: a function of the exact sum alone (NaN once a term was not
  // finite).
  double value() const;

  void clear() { *this = ExactSum{}; }

  // Each digit below 2^32 and the top one signed: one form for each sum, so that the words
  // themselves (words(), from_words) carry the sum between ranks and checkpoints.
  void normalise();
  // digits + 1 words: the digits (normalised), then 1 if finite.
  std::array<std::int64_t, digits + 1> words() const;
  static ExactSum from_words(std::span<const std::int64_t> words);

 private:
  // A digit moves by less than 2^32 per term: 2^30 terms stay well inside 64 bits.
  static constexpr int max_pending = 1 << 30;
  std::array<std::int64_t, digits> d_{};
  int pending_ = 0;
  std::int64_t finite_ = 1;
};

// Each element the exact sum over the ranks (collective: every rank passes as many); on every
// rank the same bits, whatever the rank count and whatever each rank held.
void sum_over_ranks(RankLink& link, std::span<ExactSum> sums);

// The values of `sums` rounded, after sum_over_ranks where `link` is given.
std::vector<double> exact_values(RankLink* link, std::span<ExactSum> sums);

// 128-bit fixed point for the grid's nodal sums: a term x is held as the integer x 2^k cut
// towards zero, with 2^k set per array from a bound on the terms agreed over the ranks
// (fixed_scale), so that a term reaches about 2^62 (one conversion to a 64-bit integer) and a
// node's sum of 2^64 such terms stays below 2^127. The cut is the same on every rank, so the
// sums stay independent of order; it is below 2^-61 (4.3e-19) of the bound, under the
// rounding of the largest term as a double (2^-53 of it).
__extension__ typedef __int128 Fixed;

struct FixedScale {
  double to = 1.0;    // 2^k
  double from = 1.0;  // 2^-k
};

// The scale for terms of magnitude up to `bound` (> 0; 0 or not finite: the scale of 1).
inline FixedScale fixed_scale(double bound) {
  if (!(bound > 0.0) || !std::isfinite(bound)) return {};
  const int k = 62 - std::ilogb(bound) - 1;
  return {std::ldexp(1.0, k), std::ldexp(1.0, -k)};
}

// A term up to twice its bound takes one conversion; past it, 128 bits. A term past 2^116
// (2^54 over its bound) would let a node's sum overflow: `ok` turns false and the caller stops
// the run.
AFEMP_INLINE inline Fixed to_fixed(double x, const FixedScale& s, bool& ok) {
  const double y = x * s.to;
  if (std::fabs(y) < 0x1p63) return static_cast<std::int64_t>(y);  // cut towards zero
  constexpr double limit = 0x1p116;
  if (!(std::fabs(y) < limit)) {
    ok = false;
    return 0;
  }
  // |y| = hi 2^64 + lo with hi = floor(|y| 2^-64) and 0 <= lo < 2^64, each step exact; lo's
  // fraction cut (towards zero).
  const double a = std::fabs(y);
  const double hi = std::floor(a * 0x1p-64);
  const double lo = a - hi * 0x1p64;
  const Fixed v = (static_cast<Fixed>(static_cast<std::uint64_t>(hi)) << 64) +
                  static_cast<Fixed>(static_cast<std::uint64_t>(lo));
  return y < 0.0 ? -v : v;
}

// Rounded from its magnitude (a negative value as minus its magnitude's double).
inline double from_fixed(Fixed v, const FixedScale& s) {
  const Fixed a = v < 0 ? -v : v;
  const auto hi = static_cast<std::uint64_t>(a >> 64);
  const auto lo = static_cast<std::uint64_t>(a);
  const double magnitude = static_cast<double>(hi) * 0x1p64 + static_cast<double>(lo);
  return (v < 0 ? -magnitude : magnitude) * s.from;
}

}  // namespace afemp::core
