// Packing particles for another rank (particle_migration.hpp): a header (count, kept fields,
// history width), then each kept array's values of the points in order, then their history.
#include "mpm/particle_migration.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace afemp::mpm {
namespace {

struct Header {
  std::uint64_t count;
  std::uint64_t history_count;
  std::uint32_t optional_fields;
  std::uint32_t pad;
};

}  // namespace

std::vector<std::byte> pack_particles(const Particles& p, std::span<const std::int32_t> which) {
  std::size_t per_point = p.history_count * sizeof(double);
  p.for_each_field([&](const ParticleField& field, const auto& a) {
    if (p.has(field)) per_point += sizeof(a[0]);
  });
  std::vector<std::byte> out(sizeof(Header) + which.size() * per_point);
  const Header h{which.size(), p.history_count, p.optional_fields, 0};
  std::memcpy(out.data(), &h, sizeof h);
  std::byte* at = out.data() + sizeof h;
  p.for_each_field([&](const ParticleField& field, const auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    static_assert(std::is_trivially_copyable_v<T>);
    if (!p.has(field)) return;
    for (std::int32_t i : which) {
      std::memcpy(at, &a[static_cast<std::size_t>(i)], sizeof(T));
      at += sizeof(T);
    }
  });
  for (std::int32_t i : which) {
    const std::size_t bytes = p.history_count * sizeof(double);
    if (bytes > 0)
      std::memcpy(at, &p.history[static_cast<std::size_t>(i) * p.history_count], bytes);
    at += bytes;
  }
  return out;
}

void unpack_particles(Particles& p, std::span<const std::byte> bytes) {
  Header h{};
  if (bytes.size() < sizeof h) throw std::invalid_argument("unpack_particles: no header");
  std::memcpy(&h, bytes.data(), sizeof h);
  if (h.optional_fields != p.optional_fields || h.history_count != p.history_count)
    throw std::invalid_argument(
        "unpack_particles: the points keep optional fields " + std::to_string(h.optional_fields) +
        " and " + std::to_string(h.history_count) + " history values, the receiver " +
        std::to_string(p.optional_fields) + " and " + std::to_string(p.history_count));
  std::size_t per_point = p.history_count * sizeof(double);
  p.for_each_field([&](const ParticleField& field, const auto& a) {
    if (p.has(field)) per_point += sizeof(a[0]);
  });
  if (bytes.size() != sizeof h + h.count * per_point)
    throw std::invalid_argument("unpack_particles: " + std::to_string(bytes.size()) +
                                " bytes for " + std::to_string(h.count) + " points of " +
                                std::to_string(per_point) + " bytes");
  const std::size_t first = p.size(), n = h.count;
  const std::byte* at = bytes.data() + sizeof h;
  p.for_each_field([&](const ParticleField& field, auto& a) {
    using T = typename std::decay_t<decltype(a)>::value_type;
    if (!p.has(field)) return;
    a.resize(first + n);
    if (n > 0) std::memcpy(&a[first], at, n * sizeof(T));
    at += n * sizeof(T);
  });
  p.history.resize((first + n) * p.history_count);
  if (n * p.history_count > 0)
    std::memcpy(&p.history[first * p.history_count], at, n * p.history_count * sizeof(double));
}

}  // namespace afemp::mpm
