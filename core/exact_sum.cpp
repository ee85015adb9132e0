// Exact sums (exact_sum.hpp): carries, rounding, and the sum over the ranks.
#include "core/exact_sum.hpp"

#include <cstring>
#include <stdexcept>

#include "core/rank_link.hpp"

namespace afemp::core {

void ExactSum::normalise() {
  // Each digit's excess over 32 bits (an arithmetic shift: the floor, for negative digits too)
  // carried into the next; the top digit keeps the sign.
  for (std::size_t i = 0; i + 1 < digits; ++i) {
    const std::int64_t carry = d_[i] >> 32;
    d_[i] -= carry * (std::int64_t{1} << 32);
    d_[i + 1] += carry;
  }
  pending_ = 0;
}

void ExactSum::add(const ExactSum& other) {
  ExactSum o = other;
  o.normalise();
  normalise();
  for (std::size_t i = 0; i < digits; ++i) d_[i] += o.d_[i];
  pending_ = 2;  // each digit now below 2^33 in magnitude: as after two terms
  finite_ = finite_ & o.finite_;
}

double ExactSum::value() const {
  if (finite_ == 0) return std::nan("");
  ExactSum a = *this;
  a.normalise();
  double sign = 1.0;
  if (a.d_[digits - 1] < 0) {  // negative: its magnitude, digit by digit, normalised again
    for (std::int64_t& d : a.d_) d = -d;
    a.normalise();
    sign = -1.0;
  }
  // From the top digit down, every digit now in [0, 2^32): four digits past the first that is
  // not zero hold 128 bits, more than a double's 53 and its rounding need; the rest is cut.
  double sum = 0.0;
  int left = -1;
  for (int i = digits - 1; i >= 0 && left != 0; --i) {
    const std::int64_t d = a.d_[static_cast<std::size_t>(i)];
    if (left < 0 && d == 0) continue;
    if (left < 0) left = 4;
    sum += std::ldexp(static_cast<double>(d), 32 * i - 1074);
    --left;
  }
  return sign * sum;
}

std::array<std::int64_t, ExactSum::digits + 1> ExactSum::words() const {
  ExactSum a = *this;
  a.normalise();
  std::array<std::int64_t, digits + 1> w{};
  std::memcpy(w.data(), a.d_.data(), sizeof a.d_);
  w[digits] = finite_;
  return w;
}

ExactSum ExactSum::from_words(std::span<const std::int64_t> words) {
  if (words.size() != static_cast<std::size_t>(digits) + 1)
    throw std::invalid_argument("ExactSum::from_words: " + std::to_string(words.size()) +
                                " words, not " + std::to_string(digits + 1));
  ExactSum s;
  std::memcpy(s.d_.data(), words.data(), sizeof s.d_);
  s.finite_ = words[digits];
  s.pending_ = 1;
  return s;
}

void sum_over_ranks(RankLink& link, std::span<ExactSum> sums) {
  constexpr std::size_t width = ExactSum::digits + 1;
  std::vector<std::int64_t> mine(width * sums.size());
  for (std::size_t k = 0; k < sums.size(); ++k) {
    const auto w = sums[k].words();
    std::memcpy(mine.data() + k * width, w.data(), sizeof w);
  }
  const std::vector<std::vector<std::byte>> every =
      link.gather(std::as_bytes(std::span<const std::int64_t>(mine)));
  for (ExactSum& s : sums) s.clear();
  std::vector<std::int64_t> words(width * sums.size());
  for (const std::vector<std::byte>& bytes : every) {
    if (bytes.size() != words.size() * sizeof(std::int64_t))
      throw std::logic_error("sum_over_ranks: the ranks passed different numbers of sums");
    std::memcpy(words.data(), bytes.data(), bytes.size());
    for (std::size_t k = 0; k < sums.size(); ++k)
      sums[k].add(ExactSum::from_words(std::span(words).subspan(k * width, width)));
  }
}

std::vector<double> exact_values(RankLink* link, std::span<ExactSum> sums) {
  if (link != nullptr) sum_over_ranks(*link, sums);
  std::vector<double> out(sums.size());
  for (std::size_t k = 0; k < sums.size(); ++k) out[k] = sums[k].value();
  return out;
}

}  // namespace afemp::core
