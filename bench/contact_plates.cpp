// CONTACT-PLATES (bench/README.md): two steel plates, 150 x 150 x 10 and 149 x 149 x 10
// one-point hexahedra (meshes that do not match across the interface), meeting at 1 m/s each
// with their backs driven on at that speed; the contact between them searches 101,598 faces (every
// boundary face of both plates) both ways each step. 100 automatic steps, no output. Checks first,
// then prints the contact search's seconds per step against the element update's, and the
// element-steps per second.
//
// Check (references in closed form, uniaxial strain in the plates' middle before the release
// from the plates' edges and backs returns):
// - at step 12 (t = 1.7 us, the compressive fronts 10 mm / 5.9 mm/us from the interface
//   have not yet returned from the backs) the contact force is the interface pressure
//   rho c_L v of a 1 m/s impact, over the 150 x 150 mm face: within 5 %;
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/parallel.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

int main(int argc, char** argv) {
  using namespace afemp;
  const auto start = std::chrono::steady_clock::now();
  const std::string path = argc > 1 ? argv[1] : AFEMP_BENCH_SCENE;
  const core::Scene scene = core::read_scene(path);
  fem::FeSolver solver(scene);
  const std::size_t n = solver.hexahedra().size();
  const long steps = 100;
  std::size_t faces = 0;
  for (const fem::ContactPass& p : solver.mesh_contacts().at(0).passes) faces += p.faces.size();

  const core::Material& steel = scene.materials.front();
  const double rho = steel.density, e_mod = steel.youngs_modulus, nu = steel.poisson_ratio;
  const double c_l = std::sqrt(e_mod * (1 - nu) / ((1 + nu) * (1 - 2 * nu) * rho));
  bool ok = true;
  auto report = [&](const char* what, double got, double want, double tol) {
    const bool pass = std::abs(got - want) <= tol;
    ok = ok && pass;
    std::printf("  %-46s %12.5g  expected %12.5g +- %.3g  %s\n", what, got, want, tol,
                pass ? "ok" : "FAILED");
  };
  std::printf("check (%zu contact faces, %zu elements):\n", faces, n);
  const auto step_start = std::chrono::steady_clock::now();
  for (long k = 1; k <= steps; ++k) {
    solver.step(solver.stable_time_step());
    if (k == 12) {
      const double force = solver.mesh_contacts()[0].normal_force.z;
      std::printf("  t = %.4g us\n", 1e3 * solver.time());
      const double want = rho * c_l * 1.0 * 150.0 * 150.0;
      report("contact force on the upper plate (N)", std::abs(force), std::abs(want),
             0.05 * std::abs(want));
    }
  }
  const auto end = std::chrono::steady_clock::now();
  double search = solver.contact_search_seconds(), hexahedra = 0.0, contact = 0.0;
  for (std::size_t i = 0; i < solver.plan().stages.size(); ++i) {
    std::printf("  stage %-28s %7.3f s\n", solver.plan().stages[i].name.c_str(),
                solver.stage_seconds()[i]);
    if (solver.plan().stages[i].kind == fem::FeStageKind::hexahedra)
      hexahedra = solver.stage_seconds()[i];
    if (solver.plan().stages[i].kind == fem::FeStageKind::mesh_contact)
      contact = solver.stage_seconds()[i];
  }
  std::printf("check: %s\n", ok ? "passed" : "FAILED");
  const double wall = std::chrono::duration<double>(end - start).count();
  const double stepping = std::chrono::duration<double>(end - step_start).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "threads %d  contact faces %zu  search %.2f ms/step (%.1f %% of the element update "
      "%.2f ms/step; whole contact stage %.2f ms/step)  elements %zu  wall %.3f s (steps "
      "%.3f s)  %.3f M element-steps/s  peak RSS %.0f MiB\n",
      core::thread_count(), faces, 1e3 * search / steps, 100.0 * search / hexahedra,
      1e3 * hexahedra / steps, 1e3 * contact / steps, n, wall, stepping,
      static_cast<double>(n) * steps / stepping / 1e6,
      static_cast<double>(usage.ru_maxrss) / 1024.0);
  return ok ? 0 : 1;
}
