// Sparse Cholesky factorisation of a symmetric positive definite matrix by CHOLMOD (SuiteSparse,
// supernodal; Chen, Davis, Hager & Rajamanickam, ACM TOMS 35 (2008) 22): the fill-reducing
// ordering and symbolic factorisation once per pattern, the numeric factorisation per matrix,
// through CHOLMOD's long-integer interface (a factor may hold 2^31 values or more).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

namespace afemp::fem {

// A symmetric matrix in compressed sparse column form, its upper triangle only: column j holds
// the rows i <= j, sorted, at row[column_start[j] .. column_start[j + 1]).
struct SymmetricCsc {
  int size = 0;
  std::vector<int> column_start;  // size + 1 entries
  std::vector<int> row;
  std::vector<double> value;
};

// The factorisation met a pivot that is not positive: column `column` (0-based) of the matrix
// as given, the first where the leading minor stops being positive definite.
class NotPositiveDefinite : public std::runtime_error {
 public:
  explicit NotPositiveDefinite(int column);
  int column() const { return column_; }

 private:
  int column_;
};

// What CHOLMOD reports of the last analysis and factorisation (for bench/solver_cost.cpp).
struct CholeskyStatistics {
  const char* ordering = "";      // the fill-reducing ordering it chose ("AMD", "METIS", ...)
  double factor_nonzeros = 0.0;   // nnz(L), diagonal included, of that ordering
  double flops = 0.0;             // sum over L's columns of their count squared
  std::size_t factor_values = 0;  // values the supernodal L stores (nnz(L) and padding zeros)
  std::size_t peak_bytes = 0;     // the most CHOLMOD has held at once since construction
  std::size_t bytes_in_use = 0;   // what it holds now
};

class SparseCholesky {
 public:
  // blas_threads: the BLAS's threads in factorise() and solve() (OpenBLAS); 0 the run's
  // (core::thread_count(), --threads).
  explicit SparseCholesky(int blas_threads = 0);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // The ordering and symbolic factorisation of a's pattern; factorise() reuses it for every
  // matrix of that pattern (the values may differ).
  void analyse(const SymmetricCsc& a);
  // L L^T = a (a of the analysed pattern: std::invalid_argument otherwise). Throws
  // NotPositiveDefinite.
  void factorise(const SymmetricCsc& a);
  // x = a^-1 b with the last factorisation (x and b of a's size; they may not overlap).
  void solve(std::span<const double> b, std::span<double> x) const;
  // After analyse(); peak_bytes counts CHOLMOD's own allocations only (not the caller's matrix,
  // which it views, nor METIS' internal workspace).
  CholeskyStatistics statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace afemp::fem
