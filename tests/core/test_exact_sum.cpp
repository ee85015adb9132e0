// Order-independent sums (core/exact_sum.hpp). Reference: the exact sum of the terms, known in
// closed form where the test builds it (cancellations, powers of two), and otherwise computed
// in 113-bit binary floating point (__float128) where that is exact; the order must not change
// a bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/exact_sum.hpp"

namespace afemp::core {
namespace {

double exact_of(const std::vector<double>& terms) {
  ExactSum s;
  for (const double x : terms) s.add(x);
  return s.value();
}

// Terms of mixed signs over 40 binary orders of magnitude.
std::vector<double> spread_terms(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-20, 20);
  std::vector<double> t(n);
  for (double& x : t) x = std::ldexp(mantissa(rng), exponent(rng));
  return t;
}

TEST(ExactSum, AnyOrderAndGroupingGivesTheSameBits) {
  std::vector<double> t = spread_terms(20000, 7);
  const double forward = exact_of(t);
  std::reverse(t.begin(), t.end());
  EXPECT_EQ(exact_of(t), forward);
  std::shuffle(t.begin(), t.end(), std::mt19937_64(3));
  EXPECT_EQ(exact_of(t), forward);
  // Split among 3 partial sums (as ranks or threads), added in two orders.
  ExactSum part[3];
  for (std::size_t i = 0; i < t.size(); ++i) part[i % 3].add(t[i]);
  ExactSum a = part[2], b = part[0];
  a += part[0];
  a += part[1];
  b += part[1];
  b += part[2];
  EXPECT_EQ(a.value(), forward);
  EXPECT_EQ(b.value(), forward);
  // The plain double sum in order differs with the order (it is what the mode replaces).
  double plain = 0.0;
  for (const double x : t) plain += x;
  EXPECT_NEAR(plain, forward, 1e-9 * std::fabs(forward) + 1e-9);
}

TEST(ExactSum, CancellationsLeaveTheSmallTermsExactly) {
  // 1e300 + 1 + 2^-1000 - 1e300: the plain sum gives 0; the exact sum 1 + 2^-1000, whose double
  // is 1.
  ExactSum s;
  s.add(1e300);
  s.add(1.0);
  s.add(std::ldexp(1.0, -1000));
  s.add(-1e300);
  EXPECT_EQ(s.value(), 1.0);
  s.add(-1.0);
  EXPECT_EQ(s.value(), std::ldexp(1.0, -1000));
  // The smallest subnormal, and a negative total.
  ExactSum tiny;
  const double d = std::numeric_limits<double>::denorm_min();
  for (int i = 0; i < 5; ++i) tiny.add(d);
  tiny.add(-6.0 * d);
  EXPECT_EQ(tiny.value(), -d);
  // The largest doubles: their sum overflows to infinity as the double does, the exact sum
  // holding it until a term takes it back.
  ExactSum big;
  const double m = std::numeric_limits<double>::max();
  big.add(m);
  big.add(m);
  EXPECT_TRUE(std::isinf(big.value()));
  big.add(-m);
  EXPECT_EQ(big.value(), m);
}

TEST(ExactSum, RoundsWithinOneUnitOfTheExactSum) {
  // Terms of 2^-20..2^20 with 53-bit mantissas: their exact sum fits __float128's 113 bits
  // (the terms span 40 + 53 bits, and 20000 terms add 15 more).
  const std::vector<double> t = spread_terms(20000, 11);
  __extension__ __float128 reference = 0;
  for (const double x : t) reference += static_cast<__float128>(x);
  const double r = static_cast<double>(reference);
  const double v = exact_of(t);
  EXPECT_LE(std::fabs(v - r), std::ldexp(std::fabs(r), -52));
}

TEST(ExactSum, PassesThroughWordsAndFlagsNonFiniteTerms) {
  const std::vector<double> t = spread_terms(1000, 5);
  ExactSum s;
  for (const double x : t) s.add(x);
  const auto w = s.words();
  EXPECT_EQ(ExactSum::from_words(w).value(), s.value());
  s.add(std::nan(""));
  EXPECT_TRUE(std::isnan(s.value()));
}

TEST(FixedPoint, SumsDoNotDependOnOrderAndStayWithinTheTermsCuts) {
  // Node sums as the grid's reproducible mode makes them: terms up to the bound, a scale per
  // array; the sum the same bits in any order, and within the terms' cuts of the exact sum
  // (each below 2^-61 of the bound: 2.2e-15 of it for 5,000 terms).
  const std::vector<double> t = spread_terms(5000, 13);
  double bound = 0.0;
  for (const double x : t) bound = std::max(bound, std::fabs(x));
  const FixedScale s = fixed_scale(bound);
  bool ok = true;
  Fixed forward = 0, backward = 0;
  for (const double x : t) forward += to_fixed(x, s, ok);
  for (auto i = t.rbegin(); i != t.rend(); ++i) backward += to_fixed(*i, s, ok);
  EXPECT_TRUE(ok);
  EXPECT_TRUE(forward == backward);
  EXPECT_NEAR(from_fixed(forward, s), exact_of(t),
              static_cast<double>(t.size()) * std::ldexp(bound, -61) + 1e-16 * bound);
  // A single term comes back within 2^-61 of the bound; one 2^30 times the bound (past the
  // 64-bit conversion) too, within 2^-61 of the bound.
  for (const double x : {bound, -bound, 0.3 * bound, -1e-20 * bound})
    EXPECT_NEAR(from_fixed(to_fixed(x, s, ok), s), x, std::ldexp(bound, -60));
  EXPECT_NEAR(from_fixed(to_fixed(std::ldexp(bound, 30), s, ok), s), std::ldexp(bound, 30),
              std::ldexp(bound, -60));
  EXPECT_TRUE(ok);
  // A term 2^54 past its bound would let a sum overflow: refused.
  to_fixed(std::ldexp(bound, 55), s, ok);
  EXPECT_FALSE(ok);
}

}  // namespace
}  // namespace afemp::core
