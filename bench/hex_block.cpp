// HEX-BLOCK (bench/README.md): a clamped steel block, 128,000 one-point hexahedra, every node
// but the clamped face starting at 50 m/s towards it; 500 automatic steps, no output.
// Checks first, then prints element-steps per second of the whole process and of the steps
// alone, and peak resident memory per element.
//
// Check (references in closed form, uniaxial strain along the centre line x = y = 50 before
// any release wave from the sides or the top arrives there):
// - initial kinetic energy 1/2 m v^2 of the lumped mass that moves: 2.39e6 N mm to 0.1 %;
// - the elastic precursor at c_L = sqrt((K + 4G/3) / rho) carrying the Hugoniot elastic
//   limit Y (1 - nu) / (1 - 2 nu), i.e. a velocity jump of HEL / (rho c_L), and behind it the
//   plastic front at c_p = sqrt((K + 4/3 G H / (H + 3G)) / rho) that brings the material to
//   rest: each front's half-jump crossing within one element (1.25 mm) of c t;
// - the material behind the plastic front at rest to 2 % of 50 m/s;
// - energy balance (no external work: the clamped nodes do none) within 1 % after 500 steps.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace {

using afemp::core::Vec3;

// Height z where the velocity along the centre line first crosses `level` coming down from
// the top (linear interpolation between nodes), or -1.
double crossing(const std::vector<std::pair<double, double>>& line, double level) {
  for (std::size_t i = line.size() - 1; i > 0; --i) {
    const auto [z1, v1] = line[i];
    const auto [z0, v0] = line[i - 1];
    if ((v1 - level) * (v0 - level) <= 0.0 && v1 != v0)
      return z1 + (level - v1) * (z0 - z1) / (v0 - v1);
  }
  return -1.0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace afemp;
  const auto start = std::chrono::steady_clock::now();
  const std::string path = argc > 1 ? argv[1] : AFEMP_BENCH_SCENE;
  const core::Scene scene = core::read_scene(path);
  fem::FeSolver solver(scene);
  const std::size_t n = solver.hexahedra().size();
  const long steps = 500;

  const core::Material& steel = scene.materials.front();
  const double rho = steel.density, e_mod = steel.youngs_modulus, nu = steel.poisson_ratio;
  const double bulk = e_mod / (3.0 * (1.0 - 2.0 * nu)), shear = e_mod / (2.0 * (1.0 + nu));
  const double yield = 500.0, tangent = 1000.0, hardening = e_mod * tangent / (e_mod - tangent);
  const double c_l = std::sqrt((bulk + 4.0 * shear / 3.0) / rho);
  const double c_p =
      std::sqrt((bulk + 4.0 / 3.0 * shear * hardening / (hardening + 3.0 * shear)) / rho);
  const double hel = yield * (1.0 - nu) / (1.0 - 2.0 * nu);
  const double v0 = 50.0, dv_elastic = hel / (rho * c_l), h = 25.0 / 20.0;

  // Nodes on the centre line x = y = 50, by height.
  std::vector<std::size_t> centre;
  for (std::size_t i = 0; i < solver.nodes().size(); ++i) {
    const Vec3& p = solver.nodes().position[i];
    if (std::abs(p.x - 50.0) < 1e-9 && std::abs(p.y - 50.0) < 1e-9) centre.push_back(i);
  }
  std::sort(centre.begin(), centre.end(), [&](std::size_t a, std::size_t b) {
    return solver.nodes().position[a].z < solver.nodes().position[b].z;
  });

  bool ok = true;
  auto report = [&](const char* what, double got, double want, double tol) {
    const bool pass = std::abs(got - want) <= tol;
    ok = ok && pass;
    std::printf("  %-46s %12.5g  expected %12.5g +- %.3g  %s\n", what, got, want, tol,
                pass ? "ok" : "FAILED");
  };
  const core::Energies e0 = solver.energies();
  std::printf("check:\n");
  report("initial kinetic energy (N mm)", e0.kinetic, 2.39e6, 0.001 * 2.39e6);

  // The fronts are measured at the last step before the elastic front is 2 elements from the
  // top (after that the reflection from the free top comes back down).
  const double t_check = (25.0 - 2.0 * h) / c_l;
  bool checked = false;
  const auto step_start = std::chrono::steady_clock::now();
  for (long k = 1; k <= steps; ++k) {
    const double dt = solver.stable_time_step();
    if (!checked && solver.time() + dt > t_check) {
      checked = true;
      const double t = solver.time();
      std::vector<std::pair<double, double>> line;
      for (std::size_t i : centre)
        line.emplace_back(solver.nodes().position[i].z, solver.nodes().velocity[i].z);
      std::printf("  fronts at t = %.4g ms (step %ld)\n", t, solver.step_count());
      report("elastic front height (mm)", crossing(line, -v0 + 0.5 * dv_elastic), c_l * t, h);
      report("plastic front height (mm)", crossing(line, 0.5 * (-v0 + dv_elastic)), c_p * t, h);
      double behind = 0.0;
      for (const auto& [z, v] : line)
        if (z < c_p * t - 2.0 * h) behind = std::max(behind, std::abs(v));
      report("speed behind the plastic front (m/s)", behind, 0.0, 0.02 * v0);
    }
    solver.step(dt);
  }
  const auto end = std::chrono::steady_clock::now();
  const core::Energies e1 = solver.energies();
  report("energy balance after 500 steps (relative)", (e1.total() - e0.total()) / e0.total(), 0.0,
         0.01);
  std::printf("  t = %.4g ms, kinetic %.4g N mm, internal %.4g, hourglass %.4g\n", solver.time(),
              e1.kinetic, e1.internal, e1.hourglass);
  // The final node state as a hash of its bits: the same for every run at one thread count.
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  auto mix = [&](const Vec3& v) {
    for (int i = 0; i < 3; ++i) {
      std::uint64_t bits;
      const double c = v[i];
      std::memcpy(&bits, &c, sizeof bits);
      hash = (hash ^ bits) * 1099511628211ull;
    }
  };
  for (std::size_t i = 0; i < solver.nodes().size(); ++i) {
    mix(solver.nodes().position[i]);
    mix(solver.nodes().velocity[i]);
  }
  std::printf("  final node state hash %016llx\n", static_cast<unsigned long long>(hash));
  std::printf("check: %s\n", ok ? "passed" : "FAILED");

  const double wall = std::chrono::duration<double>(end - start).count();
  const double stepping = std::chrono::duration<double>(end - step_start).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double rss_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;
  for (std::size_t i = 0; i < solver.plan().stages.size(); ++i)
    std::printf("  stage %-28s %7.3f s\n", solver.plan().stages[i].name.c_str(),
                solver.stage_seconds()[i]);
  const double element_steps = static_cast<double>(n) * static_cast<double>(steps);
  std::printf(
      "threads %d  elements %zu  steps %ld  wall %.3f s (steps %.3f s)  %.3f M "
      "element-steps/s (steps alone %.3f M)  peak RSS %.1f MiB = %.0f bytes/element\n",
      core::thread_count(), n, steps, wall, stepping, element_steps / wall / 1e6,
      element_steps / stepping / 1e6, rss_bytes / (1024.0 * 1024.0),
      rss_bytes / static_cast<double>(n));
  return ok ? 0 : 1;
}
