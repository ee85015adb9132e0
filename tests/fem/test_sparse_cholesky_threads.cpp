// The sparse solve's BLAS threads follow the run's thread count (fem/sparse_cholesky.cpp): the
// supernodal factorisation's dense blocks round by how many threads OpenBLAS splits them over,
// and OpenBLAS keeps a pool of its own, as large as the process may use cores. Reference: the
// same matrix factorised and solved at one thread of the run with OpenBLAS's pool left at one
// thread and at two before the solve: the solutions the same bits, and each solving the system
// (the residual within 1e-12 of the right-hand side). Under another BLAS there is nothing to set.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/parallel.hpp"
#include "fem/sparse_cholesky.hpp"

namespace afemp::fem {
namespace {

// The 7-point Laplacian plus the identity on an n^3 lattice (upper triangle, columns sorted):
// its separators (n^2 unknowns) give supernodes whose dense blocks OpenBLAS splits among
// threads.
SymmetricCsc lattice_laplacian(int n) {
  SymmetricCsc a;
  a.size = n * n * n;
  a.column_start.push_back(0);
  auto at = [n](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int c = at(i, j, k);
        // Rows below the diagonal's column in increasing order: -z, -y, -x neighbours, then c.
        if (k > 0) a.row.push_back(at(i, j, k - 1)), a.value.push_back(-1.0);
        if (j > 0) a.row.push_back(at(i, j - 1, k)), a.value.push_back(-1.0);
        if (i > 0) a.row.push_back(at(i - 1, j, k)), a.value.push_back(-1.0);
        a.row.push_back(c);
        a.value.push_back(7.0);
        a.column_start.push_back(static_cast<int>(a.row.size()));
      }
  return a;
}

// a x for the upper triangle's symmetric matrix.
std::vector<double> times(const SymmetricCsc& a, const std::vector<double>& x) {
  std::vector<double> y(x.size(), 0.0);
  for (int c = 0; c < a.size; ++c)
    for (int p = a.column_start[static_cast<std::size_t>(c)];
         p < a.column_start[static_cast<std::size_t>(c) + 1]; ++p) {
      const auto r = static_cast<std::size_t>(a.row[static_cast<std::size_t>(p)]);
      const double v = a.value[static_cast<std::size_t>(p)];
      y[r] += v * x[static_cast<std::size_t>(c)];
      if (r != static_cast<std::size_t>(c)) y[static_cast<std::size_t>(c)] += v * x[r];
    }
  return y;
}

TEST(SparseCholesky, TheBlasRunsTheRunsThreadCountWhateverItsPoolWasLeftAt) {
  using SetThreads = void (*)(int);
  const auto pool = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (pool == nullptr) GTEST_SKIP() << "the BLAS is not OpenBLAS: no pool of its own to set";
  const SymmetricCsc a = lattice_laplacian(24);  // 13,824 unknowns
  std::vector<double> b(static_cast<std::size_t>(a.size));
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::sin(0.37 * static_cast<double>(i));
  const int threads = core::thread_count();
  core::set_thread_count(1);
  auto solve_after_pool = [&](int left_at) {
    pool(left_at);
    SparseCholesky c;
    c.analyse(a);
    c.factorise(a);
    std::vector<double> x(b.size());
    c.solve(b, x);
    return x;
  };
  const std::vector<double> one = solve_after_pool(1);
  const std::vector<double> two = solve_after_pool(2);
  core::set_thread_count(threads);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0)
      << "the solution follows the pool OpenBLAS was left at";
  double largest = 0.0, worst = 0.0;
  const std::vector<double> ax = times(a, two);
  for (std::size_t i = 0; i < b.size(); ++i) {
    largest = std::max(largest, std::abs(b[i]));
    worst = std::max(worst, std::abs(ax[i] - b[i]));
  }
  EXPECT_LE(worst, 1e-12 * largest);
}

}  // namespace
}  // namespace afemp::fem
