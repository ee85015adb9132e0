// Particles migrating among 1 to 4 ranks (mpm/particle_migration.hpp over core/mpi/ranks.hpp):
// each rank sends every point to the rank its id names; none is lost or altered.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/mpi/ranks.hpp"
#include "mpm/particle_batch.hpp"
#include "mpm/particle_migration.hpp"

namespace afemp::mpm {
namespace {

// Reference: rank r starts with ids 1000 r .. 1000 r + 49 and keeps or sends each point to rank
// id mod N. Afterwards rank r holds exactly the ids = r mod N among 0 .. 1000 (N - 1) + 49, each
// point's fields the closed-form values of its id (test::particle_batch, bit for bit: a batch
// made from the id alone compares equal), and the total momentum sum m v over all ranks is that of
// the 50 N points (within 1e-13 relative: the sums add in another order).
TEST(MpiParticleMigration, EveryPointReachesTheRankItsIdNamesUnchanged) {
  const int n = core::rank_count(), me = core::rank_index();
  const Particles start = test::particle_batch(1000 * me, 50);
  std::vector<std::vector<std::int32_t>> to(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < start.size(); ++i)
    to[static_cast<std::size_t>(start.id[i] % n)].push_back(static_cast<std::int32_t>(i));
  std::vector<core::RankMessage> out;
  for (int r = 0; r < n; ++r)
    if (r != me && !to[static_cast<std::size_t>(r)].empty())
      out.push_back({r, pack_particles(start, to[static_cast<std::size_t>(r)])});
  Particles mine;
  mine.history_count = start.history_count;
  mine.keep(&Particles::affine, core::Mat3{});
  mine.keep(&Particles::light_time, 0.0);
  mine.keep(&Particles::burn, 1.0);
  unpack_particles(mine, pack_particles(start, to[static_cast<std::size_t>(me)]));
  for (const core::RankMessage& m : core::exchange(out)) unpack_particles(mine, m.bytes);

  std::vector<int> expected;
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < 50; ++k)
      if ((1000 * r + k) % n == me) expected.push_back(1000 * r + k);
  std::vector<int> held(mine.id.begin(), mine.id.end());
  std::sort(held.begin(), held.end());
  EXPECT_EQ(held, expected);
  double momentum = 0.0, reference = 0.0;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const Particles one = test::particle_batch(mine.id[i], 1);
    EXPECT_EQ(mine.position[i].x, one.position[0].x);
    EXPECT_EQ(mine.velocity[i].z, one.velocity[0].z);
    EXPECT_EQ(mine.mass[i], one.mass[0]);
    EXPECT_EQ(mine.stress[i].zz, one.stress[0].zz);
    EXPECT_EQ(mine.affine[i].m[0][1], one.affine[0].m[0][1]);
    EXPECT_EQ(mine.burn[i], one.burn[0]);
    EXPECT_EQ(mine.history[2 * i], one.history[0]);
    EXPECT_EQ(mine.history[2 * i + 1], one.history[1]);
    momentum += mine.mass[i] * mine.velocity[i].x;
  }
  for (int r = 0; r < n; ++r) {
    const Particles all = test::particle_batch(1000 * r, 50);
    for (std::size_t i = 0; i < all.size(); ++i) reference += all.mass[i] * all.velocity[i].x;
  }
  const double total = core::sum_in_rank_order(momentum);
  EXPECT_NEAR(total, reference, 1e-13 * reference);
  EXPECT_EQ(core::sum_over_ranks(static_cast<std::int64_t>(mine.size())), 50 * n);
}

}  // namespace
}  // namespace afemp::mpm
