// COLUMN-G (bench/README.md): an elastic column settling under gravity, 128,000 particles,
// 500 USL steps of 1e-4 s, no output. Prints the kinetic-energy check against the figures
// four independent codes agree on, then particle-steps per second of the whole process and
// peak resident memory per particle.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/particle_generation.hpp"

int main(int argc, char** argv) {
  using namespace afemp;
  const auto start = std::chrono::steady_clock::now();
  const std::string path = argc > 1 ? argv[1] : AFEMP_BENCH_SCENE;
  const core::Scene scene = core::read_scene(path);
  mpm::MpmSolver solver(scene, mpm::generate_particles(scene));
  const std::size_t n = solver.particles().size();

  // Kinetic energy (J) at t = 0.01 .. 0.05 s from four codes (BENCHMARKS.md), within 2 %.
  const double reference[] = {0.93, 2.70, 3.80, 3.11, 1.39};
  const double dt = scene.run.fixed_time_step;
  const long steps = std::lround(scene.run.end_time / dt);
  int check = 0;
  bool ok = true;
  for (long k = 1; k <= steps; ++k) {
    solver.step(dt);
    if (k % 100 == 0 && check < 5) {
      const double ke = solver.energies().kinetic;
      const double err = ke / reference[check] - 1.0;
      ok = ok && std::abs(err) < 0.02;
      std::printf("t = %.2f s  kinetic %.4f J  reference %.2f J  (%+.2f %%)\n", solver.time(), ke,
                  reference[check], 100.0 * err);
      ++check;
    }
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double rss_bytes = static_cast<double>(usage.ru_maxrss) * 1024.0;
  std::printf("kinetic-energy check: %s\n", ok ? "within 2 %" : "OUTSIDE 2 %");
  for (std::size_t i = 0; i < solver.plan().stages.size(); ++i)
    std::printf("  stage %-28s %7.3f s\n", solver.plan().stages[i].name.c_str(),
                solver.stage_seconds()[i]);
  std::printf("  reorder particles            %7.3f s\n", solver.reorder_seconds());
  std::printf(
      "threads %d  particles %zu  steps %ld  wall %.3f s  %.3f M particle-steps/s  "
      "peak RSS %.1f MiB = %.0f bytes/particle\n",
      core::thread_count(), n, steps, wall,
      static_cast<double>(n) * static_cast<double>(steps) / wall / 1e6,
      rss_bytes / (1024.0 * 1024.0), rss_bytes / static_cast<double>(n));
  return ok ? 0 : 1;
}
