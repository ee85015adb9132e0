// The `afemp` command: a thin layer over the library. `afemp check` reads a scene and prints
// the plan (the starter); `afemp run` runs it with progress, output and a summary.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "apps/progress_line.hpp"
#include "core/error.hpp"
#include "core/output/run_directory.hpp"
#include "core/parallel.hpp"
#include "mpm/simulation.hpp"

namespace {

using namespace afemp;

constexpr int exit_input_error = 1;
constexpr int exit_simulation_error = 3;

void set_threads(int threads) {
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

const char* shape_name(const core::Shape& s) {
  switch (s.index()) {
    case 0: return "box";
    case 1: return "cylinder";
    case 2: return "sphere";
    default: return "points";
  }
}

int check(const std::string& path) {
  const core::Scene scene = core::read_scene(path);
  mpm::Simulation sim(scene);
  mpm::MpmSolver& solver = sim.solver();
  solver.prepare();
  const auto& g = solver.grid();
  const auto& p = solver.particles();

  std::printf("scene %s%s%s\n", path.c_str(), scene.run.title.empty() ? "" : ": ",
              scene.run.title.c_str());
  std::printf("grid: cell %g, %d x %d x %d cells over [%g, %g] x [%g, %g] x [%g, %g]\n",
              g.cell(), g.cells()[0], g.cells()[1], g.cells()[2], scene.mpm.grid.min.x,
              scene.mpm.grid.max.x, scene.mpm.grid.min.y, scene.mpm.grid.max.y,
              scene.mpm.grid.min.z, scene.mpm.grid.max.z);
  std::printf("faces:");
  for (int f = 0; f < 6; ++f)
    std::printf(" %s=%s", core::to_string(static_cast<core::Face>(f)),
                core::to_string(scene.mpm.grid.faces[static_cast<std::size_t>(f)]));
  std::printf("\n");
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    std::size_t count = 0;
    double mass = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body[i] == static_cast<int>(b)) {
        ++count;
        mass += p.mass[i];
      }
    const auto& body = scene.bodies[b];
    std::printf("body %s: %s of %s, %zu particles (%d per cell per direction), mass %.6g\n",
                body.name.c_str(), shape_name(body.shape),
                scene.materials[static_cast<std::size_t>(body.material)].name.c_str(), count,
                body.particles_per_cell, mass);
  }
  std::printf("particles: %zu; active cells: %zu; active grid blocks: %zu (%zu node slots)\n",
              p.size(), solver.active_cells(), g.active_block_count(), g.slot_count());
  std::fputs(solver.plan().describe().c_str(), stdout);
  const double dt = solver.stable_time_step();
  std::printf("time step: %.6g (%s), about %.0f steps to t = %g\n", dt,
              scene.run.fixed_time_step > 0.0 ? "fixed" : "stable step x time_step_factor",
              scene.run.end_time / dt, scene.run.end_time);
  std::printf("memory estimate: %.1f MiB (%.0f bytes per particle)\n",
              static_cast<double>(solver.bytes()) / (1024.0 * 1024.0),
              static_cast<double>(solver.bytes()) / static_cast<double>(p.size()));
  return 0;
}

int run(const std::string& path, std::string out_dir) {
  const core::Scene scene = core::read_scene(path);
  if (out_dir.empty()) out_dir = core::default_output_directory(path);
  mpm::Simulation sim(scene);
  apps::ProgressReporter progress(stdout);
  mpm::RunOptions options;
  options.output_directory = out_dir;
  options.progress = [&](const mpm::Progress& pr) { progress(pr); };
  options.progress_seconds = progress.interval();
  std::printf("afemp run %s -> %s (%d thread(s))\n", path.c_str(), out_dir.c_str(),
              core::thread_count());
  try {
    const mpm::RunSummary s = sim.run(options);
    progress.finish();
    apps::print_summary(stdout, scene, sim.solver().plan(), s);
    std::printf("output: %s/particles.xmf (%zu frames), %s/history.csv\n", out_dir.c_str(),
                s.field_frames, out_dir.c_str());
    if (s.taylor && scene.taylor_reference && scene.taylor_reference->tolerance > 0.0 &&
        s.taylor_error > scene.taylor_reference->tolerance)
      return 4;
  } catch (const core::SimulationError& e) {
    progress.finish();
    std::fprintf(stderr, "afemp: simulation stopped: %s\n", e.what());
    std::fprintf(stderr, "afemp: output written so far is kept in %s\n", out_dir.c_str());
    return exit_simulation_error;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"afemp: explicit FE and MPM dynamics of impact and penetration"};
  app.require_subcommand(1);
  std::string scene_path, out_dir;
  int threads = 0;

  auto* run_cmd = app.add_subcommand("run", "run a scene");
  run_cmd->add_option("SCENE", scene_path, "scene file (TOML)")->required();
  run_cmd->add_option("-o,--output", out_dir, "output directory (default runs/<scene name>)");
  run_cmd->add_option("--threads", threads, "OpenMP threads (default: OMP_NUM_THREADS or all)")
      ->check(CLI::PositiveNumber);

  auto* check_cmd = app.add_subcommand("check", "read and validate a scene, print the plan");
  check_cmd->add_option("SCENE", scene_path, "scene file (TOML)")->required();
  check_cmd->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);

  CLI11_PARSE(app, argc, argv);
  set_threads(threads);
  try {
    if (*run_cmd) return run(scene_path, out_dir);
    return check(scene_path);
  } catch (const core::InputError& e) {
    std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  }
}
