#include "mpm/particles.hpp"

#include <algorithm>
#include <type_traits>
#include <utility>

namespace afemp::mpm {

namespace {
// The arrays the points keep: every one that is not optional, and the optional ones this run
// keeps.
template <class P, class F>
void for_each_array(P& p, F&& f) {
  p.for_each_field([&](const ParticleField& field, auto& a) {
    if (p.has(field)) f(a);
  });
}
}  // namespace

void Particles::resize(std::size_t n) {
  for_each_array(*this, [n](auto& a) { a.resize(n); });
  history.resize(n * history_count);
}

void Particles::reserve(std::size_t n) {
  for_each_array(*this, [n](auto& a) { a.reserve(n); });
  history.reserve(n * history_count);
}

void Particles::push_back(const Vec3& x, const Vec3& v, double m, double vol, double temp,
                          std::int32_t body_id, std::int32_t material_id) {
  const std::size_t i = position.size();
  for_each_field([this](const ParticleField& field, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (!has(field)) return;
    if constexpr (std::is_same_v<T, double>)
      a.push_back(field.rest);
    else
      a.push_back(T{});
  });
  history.resize(history.size() + history_count, 0.0);
  position[i] = x;
  velocity[i] = v;
  mass[i] = m;
  volume[i] = vol;
  temperature[i] = temp;
  body[i] = body_id;
  material[i] = material_id;
  id[i] = static_cast<std::int32_t>(i);
}

void Particles::permute(const std::vector<std::int32_t>& perm) {
  for_each_array(*this, [&perm](auto& a) {
    auto copy = a;
    for (std::size_t i = 0; i < perm.size(); ++i) a[i] = copy[static_cast<std::size_t>(perm[i])];
  });
  if (history_count == 0) return;
  const std::vector<double> copy = history;
  for (std::size_t i = 0; i < perm.size(); ++i)
    std::copy_n(&copy[static_cast<std::size_t>(perm[i]) * history_count], history_count,
                &history[i * history_count]);
}

void Particles::select(const std::vector<std::int32_t>& kept) {
  // kept increases, so the points before the first dropped one stay where they are and the
  // others move down in place: a few particles leaving at the end of the order touch little.
  std::size_t first = 0;
  while (first < kept.size() && kept[first] == static_cast<std::int32_t>(first)) ++first;
  for_each_array(*this, [&](auto& a) {
    for (std::size_t i = first; i < kept.size(); ++i) a[i] = a[static_cast<std::size_t>(kept[i])];
  });
  for (std::size_t i = first; i < kept.size() && history_count > 0; ++i)
    std::copy_n(&history[static_cast<std::size_t>(kept[i]) * history_count], history_count,
                &history[i * history_count]);
  resize(kept.size());
}

std::size_t Particles::bytes() const {
  std::size_t total = 0;
  for_each_array(*this, [&total](const auto& a) { total += a.capacity() * sizeof(a[0]); });
  return total + history.capacity() * sizeof(double);
}

}  // namespace afemp::mpm
