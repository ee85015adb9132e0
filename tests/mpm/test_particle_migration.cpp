// Packing particles for another rank (mpm/particle_migration.hpp): the points arrive with every
// field of the schema and their history, bit for bit, and a receiver that keeps other fields
// refuses them.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include "mpm/particle_migration.hpp"
#include "particle_batch.hpp"

namespace afemp::mpm {
namespace {

// Whether point i of a and point j of b hold the same bits in every kept field and history.
bool same_point(const Particles& a, std::size_t i, const Particles& b, std::size_t j) {
  bool same = true;
  for_each_particle_field([&](const ParticleField& field, auto member) {
    if (!a.has(field)) return;
    const auto& x = (a.*member)[i];
    const auto& y = (b.*member)[j];
    same = same && std::memcmp(&x, &y, sizeof x) == 0;
  });
  for (std::size_t k = 0; k < a.history_count; ++k)
    same = same && a.history[i * a.history_count + k] == b.history[j * b.history_count + k];
  return same;
}

// Reference: identity. Points 3, 0 and 5 of a batch, packed and appended to another batch of 2,
// are its points 2, 3 and 4 with the same bits in every field (the optional ones and the history
// included); its own 2 points are unchanged.
TEST(ParticleMigration, PackedPointsArriveBitForBit) {
  const Particles from = test::particle_batch(100, 6);
  Particles to = test::particle_batch(0, 2);
  const Particles before = to;
  const std::vector<std::int32_t> which{3, 0, 5};
  unpack_particles(to, pack_particles(from, which));
  ASSERT_EQ(to.size(), 5u);
  for (std::size_t k = 0; k < which.size(); ++k)
    EXPECT_TRUE(same_point(from, static_cast<std::size_t>(which[k]), to, 2 + k)) << k;
  for (std::size_t k = 0; k < 2; ++k) EXPECT_TRUE(same_point(before, k, to, k));
  EXPECT_EQ(to.id[2], 103);
  EXPECT_EQ(to.history[2 * 2], 7.0 * 103);
}

// Reference: a receiver that does not keep the affine velocity (a run of other fields) refuses
// the points, naming both sets, and keeps its own unchanged.
TEST(ParticleMigration, AReceiverKeepingOtherFieldsRefusesThePoints) {
  const Particles from = test::particle_batch(100, 3);
  Particles to;
  to.history_count = 2;
  to.push_back({}, {}, 1.0, 1.0, 293.0, 0, 0);
  const std::vector<std::int32_t> which{0, 1};
  EXPECT_THROW(unpack_particles(to, pack_particles(from, which)), std::invalid_argument);
  EXPECT_EQ(to.size(), 1u);
  EXPECT_EQ(to.history.size(), 2u);
}

}  // namespace
}  // namespace afemp::mpm
