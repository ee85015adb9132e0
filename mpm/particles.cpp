#include "mpm/particles.hpp"

#include <algorithm>
#include <utility>

namespace afemp::mpm {

namespace {
template <class F>
void for_each_array(Particles& p, F&& f) {
  f(p.position);
  f(p.velocity);
  f(p.mass);
  f(p.volume);
  f(p.stress);
  f(p.plastic_strain);
  f(p.temperature);
  f(p.energy);
  f(p.damage);
  f(p.bulk_q);
  f(p.body);
  f(p.material);
  f(p.id);
  // Only when the scene asks for them:
  if (!p.strain.empty()) f(p.strain);
  if (!p.half_width.empty()) f(p.half_width);
  if (!p.affine.empty()) f(p.affine);
  if (!p.length.empty()) f(p.length);
  if (!p.length0.empty()) f(p.length0);
  if (!p.plastic_heat.empty()) f(p.plastic_heat);
  if (!p.viscous_heat.empty()) f(p.viscous_heat);
  if (!p.light_time.empty()) f(p.light_time);
  if (!p.burn.empty()) f(p.burn);
}
template <class F>
void for_each_array(const Particles& p, F&& f) {
  for_each_array(const_cast<Particles&>(p), [&](auto& a) { f(std::as_const(a)); });
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
  id.push_back(static_cast<std::int32_t>(position.size()));
  position.push_back(x);
  velocity.push_back(v);
  mass.push_back(m);
  volume.push_back(vol);
  stress.push_back({});
  if (!strain.empty()) strain.push_back({});
  if (!half_width.empty()) half_width.push_back(0.0);  // the solver sets it from the volume
  if (!affine.empty()) affine.push_back({});
  if (!length.empty()) length.push_back({});  // the solver sets them from the volume
  if (!length0.empty()) length0.push_back({});
  if (!plastic_heat.empty()) plastic_heat.push_back(0.0);
  if (!viscous_heat.empty()) viscous_heat.push_back(0.0);
  if (!light_time.empty()) light_time.push_back(0.0);  // no explosive point is added later
  if (!burn.empty()) burn.push_back(1.0);
  plastic_strain.push_back(0.0);
  temperature.push_back(temp);
  energy.push_back(0.0);
  damage.push_back(0.0);
  bulk_q.push_back(0.0);
  history.resize(history.size() + history_count, 0.0);
  body.push_back(body_id);
  material.push_back(material_id);
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
