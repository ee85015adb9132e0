// Binning: the cell of every particle, the grid blocks that become active, and the colour
// layers that let the particle-to-grid sweep run in parallel without atomics: particles of
// layer L (cells with index L along the sweep axis) touch nodes L and L + 1 only with the
// linear hat (L - 1 .. L + 2 with uGIMP and the B-splines), so layers two (four) apart never
// share a node
// (stencil.hpp). Within a layer, particles keep their memory order, so every node sums its
// contributions in the same order for any thread count.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "afemp/errors.hpp"
#include "core/parallel.hpp"
#include "mpm/mpm_solver.hpp"

namespace afemp::mpm {

void MpmSolver::bin_particles() {
  return_particles_past_faces();
  const Particles& p = particles_;
  const std::size_t n = p.size();
  cell_.resize(n);
  layer_.resize(n);
  layer_order_.resize(n);
  const int nt = core::thread_count();
  thread_bad_.assign(static_cast<std::size_t>(nt), -1);
  const int axis = sweep_axis_;
  const std::size_t layers =
      static_cast<std::size_t>(grid_.cells()[static_cast<std::size_t>(axis)]);
  // Counting sort by layer, in parallel and stable: thread t counts its static range, then
  // writes it behind the counts of threads 0..t-1 in every layer. The result is the same
  // as a serial stable sort, whatever the thread count.
  std::vector<std::int64_t>& counts = scratch_offsets_;
  counts.assign(layers * static_cast<std::size_t>(nt), 0);
#pragma omp parallel num_threads(nt) if (core::worth_threads(n))
  {
    const int t = core::thread_index();
    const int team = core::team_size();
    const auto [b, e] = core::static_range(n, t, team);
    std::int64_t* mine = counts.data() + layers * static_cast<std::size_t>(t);
    std::int64_t bad = -1;
    for (std::size_t i = b; i < e; ++i) {
      const Vec3& x = weight_positions()[i];
      const bool finite = std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
      const auto c = finite ? grid_.cell_of(x) : std::array<int, 3>{-1, -1, -1};
      if (!grid_.inside(c)) {
        if (bad < 0) bad = static_cast<std::int64_t>(i);
        cell_[i] = 0;
        layer_[i] = 0;
      } else {
        cell_[i] = grid_.linear_cell(c);
        layer_[i] = c[static_cast<std::size_t>(axis)];
      }
      ++mine[static_cast<std::size_t>(layer_[i])];
    }
    thread_bad_[static_cast<std::size_t>(t)] = bad;
#pragma omp barrier
#pragma omp single
    {
      layer_offsets_.assign(layers + 1, 0);
      std::int64_t running = 0;
      for (std::size_t l = 0; l < layers; ++l) {
        layer_offsets_[l] = running;
        for (int u = 0; u < team; ++u) {
          std::int64_t& c = counts[layers * static_cast<std::size_t>(u) + l];
          const std::int64_t count = c;
          c = running;  // becomes thread u's next insert position in layer l
          running += count;
        }
      }
      layer_offsets_[layers] = running;
    }
    for (std::size_t i = b; i < e; ++i)
      layer_order_[static_cast<std::size_t>(mine[static_cast<std::size_t>(layer_[i])]++)] =
          static_cast<std::int32_t>(i);
  }
  raise_if_bad("position");
  check_domains();
  if (points_) points_->bin(access(), cell_);
  grid_.activate(cell_);
}

// CPDI (core/grid/cpdi.hpp): every domain must have its corners in its particle's cell or the
// neighbouring ones (the stencil's 4 x 4 x 4 nodes) and be the right way out. The lowest-index
// particle that fails stops the run, the same one for any thread count.
void MpmSolver::check_domains() const {
  if (plan_.total_lagrangian) check_deformation_gradients();
  const bool tracked = plan_.shape == core::ShapeFunction::cpdi2;
  if (plan_.shape != core::ShapeFunction::cpdi1 && !tracked) return;
  const Particles& p = particles_;
  const auto n = static_cast<std::int64_t>(p.size());
  std::int64_t bad = n;
#pragma omp parallel for schedule(static) reduction(min : bad) if (core::worth_threads(p.size()))
  for (std::int64_t q = 0; q < n; ++q) {
    const auto i = static_cast<std::size_t>(q);
    const core::CpdiDomain d =
        tracked ? core::cpdi2_domain(p.corners[i]) : core::cpdi1_domain(p.position[i], p.domain[i]);
    int reach = 0;
    if (d.inverted || !grid_.cpdi_within_reach(d, grid_.cell_of(p.position[i]), reach))
      bad = std::min(bad, q);
  }
  if (bad == n) return;
  const auto i = static_cast<std::size_t>(bad);
  const core::CpdiDomain d =
      tracked ? core::cpdi2_domain(p.corners[i]) : core::cpdi1_domain(p.position[i], p.domain[i]);
  int reach = 0;
  const auto cell = grid_.cell_of(p.position[i]);
  grid_.cpdi_within_reach(d, cell, reach);
  // The domain's extent along each axis, in cells.
  Vec3 lo = d.x[0], hi = d.x[0];
  for (const Vec3& c : d.x)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], c[a]);
      hi[a] = std::max(hi[a], c[a]);
    }
  std::ostringstream who, what;
  who << "particle " << p.id[i] << " of body '"
      << scene_.bodies[static_cast<std::size_t>(p.body[i])].name << "' at (" << p.position[i].x
      << ", " << p.position[i].y << ", " << p.position[i].z << ")";
  const char* name = tracked ? "CPDI2" : "CPDI1";
  if (d.inverted) {
    what << "its " << name << " domain turned inside out (volume " << d.volume
         << "): the material was crushed or sheared through itself within the particle; a "
            "smaller time_step_factor, or shape_function = \"gimp\" or \"bspline2\", which "
            "carry no domain";
  } else if (reach <= 1) {
    what << "its " << name
         << " domain reaches more than a cell past the grid's face (the grid stores one node "
            "beyond it); enlarge [grid] min/max";
  } else {
    what << "its " << name << " domain (" << (hi.x - lo.x) * grid_.inverse_cell() << " x "
         << (hi.y - lo.y) * grid_.inverse_cell() << " x " << (hi.z - lo.z) * grid_.inverse_cell()
         << " cells) reaches " << reach
         << " cells from the particle's cell; its corners must stay in that cell or its "
            "neighbours (a stencil of 4 x 4 x 4 nodes) and on the grid. The material stretched "
            "it that far: more particles per cell, or shape_function = \"gimp\" or "
            "\"bspline2\", whose domains do not stretch";
  }
  throw core::SimulationError(steps_, time_, who.str(), "domain", what.str());
}

// Total-Lagrangian: the reference weights hold a particle's neighbourhood as long as the map F
// from it is one to one; det F <= 0 (the material turned inside out, as where a penetrator
// shears it through itself) or a non-finite F stops the run at the lowest such particle.
void MpmSolver::check_deformation_gradients() const {
  const Particles& p = particles_;
  const auto n = static_cast<std::int64_t>(p.size());
  std::int64_t bad = n;
#pragma omp parallel for schedule(static) reduction(min : bad) if (core::worth_threads(p.size()))
  for (std::int64_t q = 0; q < n; ++q) {
    const double j = core::determinant(p.deformation_gradient[static_cast<std::size_t>(q)]);
    if (!(j > 0.0) || !std::isfinite(j)) bad = std::min(bad, q);
  }
  if (bad == n) return;
  const auto i = static_cast<std::size_t>(bad);
  std::ostringstream who, what;
  who << "particle " << p.id[i] << " of body '"
      << scene_.bodies[static_cast<std::size_t>(p.body[i])].name << "' at (" << p.position[i].x
      << ", " << p.position[i].y << ", " << p.position[i].z << "), reference ("
      << p.reference_position[i].x << ", " << p.reference_position[i].y << ", "
      << p.reference_position[i].z << ")";
  what << "det F = " << core::determinant(p.deformation_gradient[i])
       << ": the material turned inside out where the particle is, and the total-Lagrangian "
          "weights, taken in the reference configuration, no longer describe its neighbourhood; "
          "formulation = \"updated-lagrangian\" follows such deformation (the "
          "total-Lagrangian form is for solids that stay in one piece)";
  throw core::SimulationError(steps_, time_, who.str(), "deformation gradient", what.str());
}

}  // namespace afemp::mpm
