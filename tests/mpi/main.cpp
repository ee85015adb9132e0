// The MPI tests run on every rank of `mpiexec -n N`; rank 0 prints the results, every rank
// exits non-zero when one of its checks failed (and mpiexec with it).
#include <gtest/gtest.h>

#include "core/mpi/ranks.hpp"

int main(int argc, char** argv) {
  afemp::core::MpiSession session(argc, argv);
  testing::InitGoogleTest(&argc, argv);
  if (afemp::core::rank_index() != 0) {
    testing::TestEventListeners& listeners = testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
