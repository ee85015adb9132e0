// Solver cost (bench/README.md): time and memory of the sparse factorisation behind afemp's
// implicit solves, CHOLMOD's supernodal L L^T (fem/sparse_cholesky.hpp) against Eigen's
// up-looking SimplicialLDLT with its AMD ordering, on the same stiffness matrices: elastic steel
// blocks of fully integrated B-bar hexahedra (fem/hexahedron_stiffness.hpp) fixed on the face
// z = 0, assembled by fem/sparse_assembly.hpp. Every solve is checked (||K u - f|| / ||f|| at most
// 1e-8, or the program exits non-zero); a factorisation that would exceed the memory cap, or the
// time cap at the flop rate measured at the previous size, is reported "not run" with the
// estimate instead of being attempted.
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "afemp/material.hpp"
#include "core/materials/small_strain_tangent.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_stiffness.hpp"
#include "fem/sparse_assembly.hpp"
#include "fem/sparse_cholesky.hpp"

namespace {

using namespace afemp;
using EigenMatrix = Eigen::SparseMatrix<double>;  // column-major, int indices, as CHOLMOD's view

constexpr double kResidualLimit = 1e-8;
constexpr const char* kNotAsked = "not asked for (--solvers)";
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

struct Options {
  std::vector<double> dofs{1e4, 1e5, 1e6};
  bool cholmod = true, eigen = true;
  double aspect = 1.0;      // block length over width: 1 for cubes
  double time_cap = 600.0;  // s, per factorisation
  double memory_cap = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGESIZE);
};

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

// Bytes of /proc/self/status's `key` (VmRSS, VmHWM).
double status_bytes(const char* key) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) == 0) return 1024.0 * std::atof(line.c_str() + std::strlen(key) + 1);
  return 0.0;
}

// The peak resident set of what f does beyond the resident set before it: VmHWM reset through
// /proc/self/clear_refs (Linux 4.0 on), after the heap's free pages are handed back to the system
// (else f reuses them unseen). Empty where the reset is refused.
template <class F>
std::optional<double> peak_rss_growth(F&& f) {
  malloc_trim(0);
  const bool reset = static_cast<bool>(std::ofstream("/proc/self/clear_refs") << "5");
  const double before = status_bytes("VmRSS:");
  f();
  if (!reset) return std::nullopt;
  return status_bytes("VmHWM:") - before;
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Wall and CPU seconds (all threads) of f.
struct Timed {
  double wall = 0.0, cpu = 0.0;
};
template <class F>
Timed timed(F&& f) {
  const double cpu0 = cpu_seconds();
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
          cpu_seconds() - cpu0};
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

// An n x n x l block of 1 mm hexahedra (l = round(aspect n) along z), nodes (i, j, k) numbered
// i fastest, the face z = 0 fixed: 3 (n + 1)^2 l free dofs, numbered node by node.
struct Block {
  int n = 0, l = 0;
  std::vector<fem::Hexahedron> hexahedra;
  std::vector<core::Vec3> nodes;
  std::vector<int> equation;
  int equations = 0;
  std::vector<double> load;  // per equation: (0.1, 0, -1) N on every node of the face z = l
};

int length_for(int n, double aspect) {
  return std::max(1, static_cast<int>(std::lround(aspect * n)));
}

Block make_block(int n, double aspect) {
  Block b;
  b.n = n;
  b.l = length_for(n, aspect);
  const int m = n + 1;
  auto node = [m](int i, int j, int k) { return i + m * (j + m * k); };
  for (int k = 0; k <= b.l; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) b.nodes.push_back({double(i), double(j), double(k)});
  for (int k = 0; k < b.l; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        b.hexahedra.push_back({node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                               node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                               node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)});
  b.equation.assign(3 * b.nodes.size(), -1);
  for (std::size_t a = 0; a < b.nodes.size(); ++a) {
    if (b.nodes[a].z == 0.0) continue;
    for (int c = 0; c < 3; ++c) {
      b.equation[3 * a + c] = b.equations++;
      b.load.push_back(b.nodes[a].z == b.l ? (c == 0 ? 0.1 : c == 2 ? -1.0 : 0.0) : 0.0);
    }
  }
  return b;
}

// The cross-section n whose block has the free dofs nearest `dofs`.
int section_for(double dofs, double aspect) {
  auto free_dofs = [aspect](int n) { return 3.0 * (n + 1.0) * (n + 1.0) * length_for(n, aspect); };
  int best = 1;
  for (int n = 1; free_dofs(n) < 4.0 * dofs; ++n)
    if (std::abs(free_dofs(n) - dofs) < std::abs(free_dofs(best) - dofs)) best = n;
  return best;
}

// ||K u - f|| / ||f|| with K's upper triangle a.
double relative_residual(const fem::SymmetricCsc& a, const std::vector<double>& u,
                         const std::vector<double>& f) {
  std::vector<double> r(f.size());
  for (int j = 0; j < a.size; ++j)
    for (int p = a.column_start[j]; p < a.column_start[j + 1]; ++p) {
      const int i = a.row[p];
      r[i] += a.value[p] * u[j];
      if (i != j) r[j] += a.value[p] * u[i];
    }
  double rr = 0.0, ff = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    rr += (r[i] - f[i]) * (r[i] - f[i]);
    ff += f[i] * f[i];
  }
  return std::sqrt(rr / ff);
}

// nnz(L), diagonal included, and flops (the sum of squared column counts, CHOLMOD's measure) of
// SimplicialLDLT on the upper triangle k, before it runs: Eigen's own AMD ordering of the full
// pattern and the elimination-tree walk of SimplicialCholeskyBase::analyzePattern_preordered,
// counted in 64 bits, where Eigen's int column pointers would overflow past 2^31 entries.
struct Symbolic {
  double nonzeros = 0.0, flops = 0.0;
};
Symbolic eigen_symbolic(const EigenMatrix& k) {
  const int n = static_cast<int>(k.rows());
  using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  Permutation inverse;
  {
    const EigenMatrix full = k.selfadjointView<Eigen::Upper>();
    Eigen::AMDOrdering<int>()(full, inverse);
  }
  const Permutation permutation = inverse.inverse();
  EigenMatrix ap(n, n);
  ap.selfadjointView<Eigen::Upper>() = k.selfadjointView<Eigen::Upper>().twistedBy(permutation);
  std::vector<int> parent(n, -1), tag(n);
  std::vector<std::int64_t> count(n, 0);
  for (int c = 0; c < n; ++c) {
    tag[c] = c;
    for (EigenMatrix::InnerIterator it(ap, c); it; ++it)
      if (int i = it.index(); i < c)
        for (; tag[i] != c; i = parent[i]) {
          if (parent[i] == -1) parent[i] = c;
          ++count[i];
          tag[i] = c;
        }
  }
  Symbolic s;
  for (std::int64_t c : count) {
    s.nonzeros += static_cast<double>(c + 1);
    s.flops += static_cast<double>(c + 1) * static_cast<double>(c + 1);
  }
  return s;
}

// One solver's figures at one size; `not_run` says why it was not attempted.
struct Run {
  std::string ordering, not_run;
  double analyse = 0.0, factorise = 0.0, solve = 0.0, cpu_per_wall = 0.0;
  double factor_nonzeros = 0.0, flops = 0.0, own_bytes = 0.0, residual = 0.0;
  std::optional<double> rss_growth;
  std::string load;  // /proc/loadavg after the factorisation
};

// "not run: ..." when the estimate passes a cap, else empty. rate: the flop rate measured at the
// previous size (0: none yet, no time estimate).
std::string refusal(const Options& o, double estimated_bytes, double flops, double rate) {
  const double resident = status_bytes("VmRSS:");
  if (resident + estimated_bytes > o.memory_cap)
    return format(
        "not run: needs an estimated %.1f GiB beside the %.1f GiB resident, over the "
        "memory cap of %.1f GiB",
        estimated_bytes / kGiB, resident / kGiB, o.memory_cap / kGiB);
  if (rate > 0.0 && flops / rate > o.time_cap)
    return format("not run: %.3g flops at the previous size's %.3g GFlop/s take an estimated ",
                  flops, rate * 1e-9) +
           format("%.0f s, over the time cap of %.0f s", flops / rate, o.time_cap);
  return {};
}

Run run_cholmod(const Options& o, const fem::SymmetricCsc& k, const std::vector<double>& f,
                double rate) {
  Run r;
  std::vector<double> u(f.size());
  r.rss_growth = peak_rss_growth([&] {
    fem::SparseCholesky cholesky;
    try {
      r.analyse = timed([&] { cholesky.analyse(k); }).wall;
    } catch (const std::runtime_error& e) {
      // An analysis CHOLMOD could not finish (out of memory: status -2, too large: -3); the
      // counts are those of the last ordering it tried, 8 bytes a value the least L would need.
      r.factor_nonzeros = cholesky.statistics().factor_nonzeros;
      r.flops = cholesky.statistics().flops;
      r.own_bytes = 8.0 * r.factor_nonzeros;
      r.not_run = std::string("not run: ") + e.what();
      return;
    }
    const fem::CholeskyStatistics s = cholesky.statistics();
    r.ordering = s.ordering;
    r.factor_nonzeros = s.factor_nonzeros;
    r.flops = s.flops;
    // What factorise adds to the resident set: the supernodal values and CHOLMOD's permuted
    // copy of K (long indices: 16 bytes an entry).
    const double estimate =
        8.0 * static_cast<double>(s.factor_values) + 16.0 * static_cast<double>(k.row.size());
    r.not_run = refusal(o, estimate, s.flops, rate);
    if (!r.not_run.empty()) {
      r.own_bytes = static_cast<double>(s.bytes_in_use) + estimate;
      return;
    }
    const Timed t = timed([&] { cholesky.factorise(k); });
    r.load = load_average();
    r.factorise = t.wall;
    r.cpu_per_wall = t.cpu / t.wall;
    r.solve = timed([&] { cholesky.solve(f, u); }).wall;
    r.own_bytes = static_cast<double>(cholesky.statistics().peak_bytes);
  });
  if (r.not_run.empty()) r.residual = relative_residual(k, u, f);
  return r;
}

// Eigen holds, while it factorises, L's values and row indices (12 bytes an off-diagonal entry),
// its permuted copy of K (12 bytes an entry) and ten arrays of n ints or doubles (column
// pointers of L and of the copy, D, both permutations, the elimination tree, the column counts
// and its work vectors): 48 bytes a dof.
double eigen_bytes(double factor_nonzeros, double n, double k_nonzeros) {
  return 12.0 * (factor_nonzeros - n) + 12.0 * k_nonzeros + 48.0 * n;
}

Run run_eigen(const Options& o, const fem::SymmetricCsc& k, const std::vector<double>& f,
              double rate, bool& nonzeros_agree) {
  Run r;
  r.ordering = "AMD";
  const EigenMatrix matrix =
      Eigen::Map<const EigenMatrix>(k.size, k.size, static_cast<Eigen::Index>(k.row.size()),
                                    k.column_start.data(), k.row.data(), k.value.data());
  const Symbolic symbolic = eigen_symbolic(matrix);
  r.factor_nonzeros = symbolic.nonzeros;
  r.flops = symbolic.flops;
  r.own_bytes = eigen_bytes(symbolic.nonzeros, k.size, static_cast<double>(k.row.size()));
  r.not_run = refusal(o, r.own_bytes, symbolic.flops, rate);
  if (!r.not_run.empty()) return r;
  Eigen::VectorXd u;
  r.rss_growth = peak_rss_growth([&] {
    Eigen::SimplicialLDLT<EigenMatrix, Eigen::Upper> ldlt;
    r.analyse = timed([&] { ldlt.analyzePattern(matrix); }).wall;
    const Timed t = timed([&] { ldlt.factorize(matrix); });
    r.load = load_average();
    r.factorise = t.wall;
    r.cpu_per_wall = t.cpu / t.wall;
    if (ldlt.info() != Eigen::Success) {
      std::fprintf(stderr, "Eigen's SimplicialLDLT failed (info %d)\n", int(ldlt.info()));
      std::exit(1);
    }
    const Eigen::Map<const Eigen::VectorXd> b(f.data(), static_cast<Eigen::Index>(f.size()));
    r.solve = timed([&] { u = ldlt.solve(b); }).wall;
    const double eigen_nonzeros =
        static_cast<double>(ldlt.matrixL().nestedExpression().nonZeros()) + k.size;
    nonzeros_agree = eigen_nonzeros == symbolic.nonzeros;
    if (!nonzeros_agree)
      std::printf("  Eigen's nnz(L) %.0f differs from the estimate %.0f\n", eigen_nonzeros,
                  symbolic.nonzeros);
  });
  r.residual = relative_residual(k, std::vector<double>(u.data(), u.data() + u.size()), f);
  return r;
}

std::string mib(double bytes) {
  return format("%.0f", bytes / (1024.0 * 1024.0));
}

void print_run(const char* name, const Run& r) {
  if (r.not_run == kNotAsked) return;
  std::printf("  %-8s %-6s", name, r.ordering.c_str());
  if (!r.not_run.empty()) {
    std::printf(" nnz(L) %.3g, %.3g flops, estimated %s MiB: %s\n", r.factor_nonzeros, r.flops,
                mib(r.own_bytes).c_str(), r.not_run.c_str());
    return;
  }
  std::printf(
      " analyse %.3f s, factorise %.3f s (%.3g GFlop/s, CPU/wall %.2f), solve %.3f s, nnz(L) "
      "%.4g, own memory %s MiB, peak RSS growth %s MiB, residual %.2e (load %s)\n",
      r.analyse, r.factorise, r.flops / r.factorise * 1e-9, r.cpu_per_wall, r.solve,
      r.factor_nonzeros, mib(r.own_bytes).c_str(),
      r.rss_growth ? mib(*r.rss_growth).c_str() : "n/a", r.residual, r.load.c_str());
}

std::vector<double> parse_list(const std::string& s) {
  std::vector<double> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::atof(item.c_str()));
  return out;
}

int usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s [--dofs 1e4,1e5,1e6] [--aspect A] [--solvers cholmod,eigen] [--time-cap "
               "SECONDS]\n          [--memory-cap GIB]\n"
               "  --dofs       target free dofs, one block each, run in increasing order\n"
               "  --aspect     n x n x A n elements, z = 0 fixed (default 1: cubes)\n"
               "  --solvers    which to run (default both)\n"
               "  --time-cap   longest estimated factorisation attempted (default 600 s)\n"
               "  --memory-cap largest resident set attempted (default: physical memory)\n",
               program);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (a + 1 == argc) return usage(argv[0]);
    const char* value = argv[++a];
    if (arg == "--dofs")
      o.dofs = parse_list(value);
    else if (arg == "--solvers") {
      const std::string list = std::string(",") + value + ",";
      o.cholmod = list.find(",cholmod,") != std::string::npos;
      o.eigen = list.find(",eigen,") != std::string::npos;
    } else if (arg == "--aspect")
      o.aspect = std::atof(value);
    else if (arg == "--time-cap")
      o.time_cap = std::atof(value);
    else if (arg == "--memory-cap")
      o.memory_cap = std::atof(value) * kGiB;
    else
      return usage(argv[0]);
  }
  std::sort(o.dofs.begin(), o.dofs.end());
  if (o.dofs.empty() || o.dofs.front() < 1.0 || !(o.aspect > 0.0) || !(o.cholmod || o.eigen) ||
      !(o.time_cap > 0.0) || !(o.memory_cap > 0.0))
    return usage(argv[0]);

  core::Material steel;
  steel.name = "steel";
  steel.density = 7.85e-3;
  steel.youngs_modulus = 200e3;  // MPa: N and mm
  steel.poisson_ratio = 0.3;
  std::array<core::VoigtMatrix, 8> d;
  d.fill(core::small_strain_update(steel, {}, {}).tangent);

  std::printf("solver cost: time cap %.0f s, memory cap %.1f GiB\n", o.time_cap,
              o.memory_cap / kGiB);
  bool failed = false;
  double cholmod_rate = 0.0, eigen_rate = 0.0;
  struct Row {
    int dofs;
    double k_nonzeros, assembly;
    std::string load;
    Run cholmod, eigen;
  };
  std::vector<Row> rows;
  for (double target : o.dofs) {
    Row row{};
    row.load = load_average();
    const Block block = make_block(section_for(target, o.aspect), o.aspect);
    row.dofs = block.equations;
    std::optional<fem::SparseAssembly> assembly;
    row.assembly = timed([&] {
                     assembly.emplace(block.hexahedra, std::span<const fem::Line>{}, block.equation,
                                      block.equations);
                     fem::HexMatrix ke;
                     for (const fem::Hexahedron& h : block.hexahedra) {
                       fem::HexVectors x;
                       for (int a = 0; a < 8; ++a) x[a] = block.nodes[h[a]];
                       fem::hexahedron_stiffness_bbar(fem::full_hex(x), d, ke);
                       assembly->add(h, ke);
                     }
                   }).wall;
    const fem::SymmetricCsc& k = assembly->matrix();
    row.k_nonzeros = static_cast<double>(k.row.size());
    std::printf(
        "%d x %d x %d hexahedra, %d free dofs, nnz(K) %.4g (upper triangle), assembled in %.2f s "
        "(load %s)\n",
        block.n, block.n, block.l, row.dofs, row.k_nonzeros, row.assembly, row.load.c_str());
    std::fflush(stdout);

    Run skipped;
    skipped.not_run = kNotAsked;
    row.cholmod = o.cholmod ? run_cholmod(o, k, block.load, cholmod_rate) : skipped;
    print_run("CHOLMOD", row.cholmod);
    std::fflush(stdout);
    bool agree = true;
    row.eigen = o.eigen ? run_eigen(o, k, block.load, eigen_rate, agree) : skipped;
    print_run("Eigen", row.eigen);
    for (const Run* r : {&row.cholmod, &row.eigen})
      if (r->not_run.empty() && !(r->residual <= kResidualLimit)) {
        std::printf("  FAILED: residual %.2e above %.0e\n", r->residual, kResidualLimit);
        failed = true;
      }
    failed = failed || !agree;
    if (row.cholmod.not_run.empty()) cholmod_rate = row.cholmod.flops / row.cholmod.factorise;
    if (row.eigen.not_run.empty()) eigen_rate = row.eigen.flops / row.eigen.factorise;
    std::fflush(stdout);
    rows.push_back(row);
  }

  std::printf(
      "\n| dofs | nnz(K) | solver | ordering | analyse s | factorise s | GFlop/s | solve s "
      "| nnz(L) | own MiB | RSS growth MiB | residual | load after factorising |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows) {
    const std::pair<const char*, const Run*> runs[] = {{"CHOLMOD", &row.cholmod},
                                                       {"Eigen", &row.eigen}};
    for (const auto& [name, r] : runs) {
      if (r->not_run == kNotAsked) continue;
      std::printf("| %d | %.3g | %s | %s | ", row.dofs, row.k_nonzeros, name, r->ordering.c_str());
      if (!r->not_run.empty()) {
        std::printf("%s (nnz(L) %.3g, %.3g flops, estimated %s MiB) | | | | | | | | |\n",
                    r->not_run.c_str(), r->factor_nonzeros, r->flops, mib(r->own_bytes).c_str());
        continue;
      }
      std::printf("%.3f | %.3f | %.3g | %.3f | %.4g | %s | %s | %.1e | %s |\n", r->analyse,
                  r->factorise, r->flops / r->factorise * 1e-9, r->solve, r->factor_nonzeros,
                  mib(r->own_bytes).c_str(), r->rss_growth ? mib(*r->rss_growth).c_str() : "n/a",
                  r->residual, r->load.c_str());
    }
    const Run &c = row.cholmod, &e = row.eigen;
    if (c.not_run.empty() && e.not_run.empty())
      std::printf("| | | Eigen / CHOLMOD | | %.2f | %.2f | | %.2f | %.2f | %.2f | %s | | |\n",
                  e.analyse / c.analyse, e.factorise / c.factorise, e.solve / c.solve,
                  e.factor_nonzeros / c.factor_nonzeros, e.own_bytes / c.own_bytes,
                  c.rss_growth && e.rss_growth
                      ? format("%.2f", *e.rss_growth / *c.rss_growth).c_str()
                      : "n/a");
  }
  return failed ? 1 : 0;
}
