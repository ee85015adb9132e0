// CHOLMOD behind fem/sparse_cholesky.hpp: the matrix and right-hand side are handed over as
// views of the caller's arrays (CHOLMOD headers that point into them, never freed by CHOLMOD).
#include "fem/sparse_cholesky.hpp"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel.hpp"

namespace afemp::fem {

namespace {

// The supernodal factorisation and the solve call the BLAS for their dense blocks. OpenBLAS,
// which scripts/install-deps makes the system BLAS, runs a pool of its own threads there, as
// many as the process may use cores (or OPENBLAS_NUM_THREADS), and the blocks' rounding follows
// their number: a run's phase then gave other bits in a process that a launcher bound to one
// core (each MPI rank) than unbound. Its count is set to the run's (--threads, OpenMP's), so
// that a solve gives the same bits for the same thread count however the process is placed.
// openblas_set_num_threads is OpenBLAS's own call (OpenBLAS README, "Setting the number of
// threads at runtime"); under another BLAS it is absent and nothing is set. A count asked for
// (the reproducible mode's 1) replaces the run's.
void set_blas_threads(int asked) {
  using SetThreads = void (*)(int);
  static const auto set =
      reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set) set(asked > 0 ? asked : core::thread_count());
}

}  // namespace

NotPositiveDefinite::NotPositiveDefinite(int column)
    : std::runtime_error("matrix not positive definite at column " + std::to_string(column)),
      column_(column) {}

// CHOLMOD's long-integer interface (cholmod_l_*): its int one refuses a factor of 2^31 values or
// more, which a 10^6-dof cube of hexahedra reaches (nnz(L) 2.25e9). The pattern is copied once
// per analysis into the long indices it needs; the values are viewed in place.
struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  int size = 0;
  std::vector<SuiteSparse_long> column_start, row;  // the analysed pattern
  int blas_threads = 0;

  Impl() {
    cholmod_l_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.print = 0;  // failures come back as exceptions, not as CHOLMOD's messages
  }
  ~Impl() {
    cholmod_l_free_factor(&factor, &common);
    cholmod_l_finish(&common);
  }

  // A CHOLMOD view of a (stype 1: the upper triangle holds the matrix) on the analysed pattern.
  cholmod_sparse view(const SymmetricCsc& a) const {
    if (a.size != size || a.row.size() != row.size())
      throw std::invalid_argument("sparse Cholesky: the matrix is not of the analysed pattern");
    cholmod_sparse s{};
    s.nrow = s.ncol = static_cast<std::size_t>(a.size);
    s.nzmax = a.row.size();
    s.p = const_cast<SuiteSparse_long*>(column_start.data());
    s.i = const_cast<SuiteSparse_long*>(row.data());
    s.x = const_cast<double*>(a.value.data());
    s.stype = 1;
    s.itype = CHOLMOD_LONG;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  void check(const char* what) const {
    if (common.status < CHOLMOD_OK)
      throw std::runtime_error(std::string("CHOLMOD ") + what + " failed (status " +
                               std::to_string(common.status) + ")");
  }
};

SparseCholesky::SparseCholesky(int blas_threads) : impl_(std::make_unique<Impl>()) {
  impl_->blas_threads = blas_threads;
}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyse(const SymmetricCsc& a) {
  cholmod_l_free_factor(&impl_->factor, &impl_->common);
  impl_->size = a.size;
  impl_->column_start.assign(a.column_start.begin(), a.column_start.end());
  impl_->row.assign(a.row.begin(), a.row.end());
  cholmod_sparse s = impl_->view(a);
  impl_->factor = cholmod_l_analyze(&s, &impl_->common);
  impl_->check("analyse");
}

void SparseCholesky::factorise(const SymmetricCsc& a) {
  cholmod_sparse s = impl_->view(a);
  set_blas_threads(impl_->blas_threads);
  cholmod_l_factorize(&s, impl_->factor, &impl_->common);
  impl_->check("factorise");
  // CHOLMOD's minor is the column of the factor's (permuted) order; report the matrix's.
  if (impl_->common.status == CHOLMOD_NOT_POSDEF) {
    const auto minor = static_cast<std::size_t>(impl_->factor->minor);
    const auto* perm = static_cast<const SuiteSparse_long*>(impl_->factor->Perm);
    throw NotPositiveDefinite(static_cast<int>(perm ? perm[minor] : static_cast<long>(minor)));
  }
}

void SparseCholesky::solve(std::span<const double> b, std::span<double> x) const {
  cholmod_dense rhs{};
  rhs.nrow = rhs.d = rhs.nzmax = static_cast<std::size_t>(impl_->size);
  rhs.ncol = 1;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  set_blas_threads(impl_->blas_threads);
  cholmod_dense* sol = cholmod_l_solve(CHOLMOD_A, impl_->factor, &rhs, &impl_->common);
  impl_->check("solve");
  const double* v = static_cast<const double*>(sol->x);
  std::copy(v, v + impl_->size, x.begin());
  cholmod_l_free_dense(&sol, &impl_->common);
}

CholeskyStatistics SparseCholesky::statistics() const {
  static constexpr const char* kOrdering[] = {"natural", "given",  "AMD",        "METIS",
                                              "NESDIS",  "COLAMD", "postordered"};
  const cholmod_common& c = impl_->common;
  const cholmod_factor* f = impl_->factor;
  CholeskyStatistics s;
  if (f && f->ordering >= 0 && f->ordering <= CHOLMOD_POSTORDERED)
    s.ordering = kOrdering[f->ordering];
  s.factor_nonzeros = c.lnz;
  s.flops = c.fl;
  s.factor_values = f ? f->xsize : 0;
  s.peak_bytes = c.memory_usage;
  s.bytes_in_use = c.memory_inuse;
  return s;
}

}  // namespace afemp::fem
