// The `afemp` command: a thin layer over the library. `afemp check` reads a scene and prints
// the plan (the starter); `afemp run` runs it with progress, output and a summary; `afemp
// study` runs a study file's variations and writes their error against run time; `afemp
// import` turns an LS-DYNA or MPM3D deck into a scene.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "afemp/deck_import.hpp"
#include "afemp/errors.hpp"
#include "analysis/reference_checks.hpp"
#include "analysis/study.hpp"
#include "analysis/study_file.hpp"
#include "apps/progress_line.hpp"
#include "core/checkpoint.hpp"
#include "core/contact_warnings.hpp"
#include "core/interrupt.hpp"
#include "core/output/field_writer.hpp"
#include "core/output/run_directory.hpp"
#include "core/parallel.hpp"
#include "core/plausibility.hpp"
#include "core/resource_guard.hpp"
#include "core/time_loop.hpp"
#include "coupling/make_model.hpp"

namespace {

using namespace afemp;

constexpr int exit_input_error = 1;
constexpr int exit_simulation_error = 3;

constexpr int exit_check_failed = 4;  // a reference or tolerance the results miss
constexpr int exit_output_error = 5;  // output or a checkpoint could not be written (disk full)
// A run stopped by SIGINT or SIGTERM after writing its final row, frame and summary exits
// with 128 + the signal's number (130, 143), as a shell reports a process the signal ended.

using coupling::make_model;

// A deck given where a scene belongs: say how to import it, not that it is bad TOML.
void refuse_deck(const std::string& path) {
  const core::DeckFormat format = core::deck_format(path);
  if (format == core::DeckFormat::none) return;
  throw core::InputError({path, 0}, "scene",
                         std::string("this is an ") + core::to_string(format) +
                             " deck, not a scene; import it with `afemp import " + path +
                             " -o SCENE.toml` and run the scene (docs/import.md)");
}

// A step count past a billion is a unit slip far more often than a plan: say so (the scene's
// max_steps, when set, bounds the run anyway).
void warn_step_count(const core::Scene& scene, const core::Model& model, double dt) {
  const double steps = scene.run.end_time / dt;
  if (!(steps > 1e9) || scene.run.max_steps > 0) return;
  const double points = static_cast<double>(model.particle_count() + model.element_count());
  std::fprintf(stderr,
               "afemp: warning: about %s steps to end_time = %g at dt = %.3g: %s point-steps, "
               "days of computing at tens of millions a second; check end_time and the units "
               "(mm, ms, g: 1 s is 1000), or bound the run with [run] max_steps\n",
               core::readable_count(steps).c_str(), scene.run.end_time, dt,
               core::readable_count(steps * points).c_str());
}

// A run estimated to take more than a day at the nominal pace (core/resource_guard.hpp); not
// where the step count has been warned of already.
void warn_wall_time(const core::Scene& scene, const core::Model& model, double dt) {
  const double steps = core::planned_steps(scene, dt);
  if (scene.run.max_steps <= 0 && steps > 1e9) return;
  const double points = static_cast<double>(model.particle_count() + model.element_count());
  const std::string w = core::wall_time_warning(points * steps, core::thread_count());
  if (!w.empty()) std::fprintf(stderr, "afemp: warning: %s\n", w.c_str());
}

int check(const std::string& path) {
  refuse_deck(path);
  const core::Scene scene = core::read_scene(path);
  const std::unique_ptr<core::Model> model = make_model(scene);
  model->resolve_probes(scene.probes);  // a probe naming a node the mesh lacks fails here too
  for (const std::string& w : core::contact_warnings(scene, *model))
    std::fprintf(stderr, "afemp: warning: %s\n", w.c_str());
  for (const core::SceneWarning& w : core::plausibility_warnings(scene))
    std::fprintf(stderr, "afemp: warning: %s\n", w.text().c_str());
  std::printf("scene %s%s%s\n", path.c_str(), scene.run.title.empty() ? "" : ": ",
              scene.run.title.c_str());
  std::fputs(model->describe().c_str(), stdout);
  const double dt = model->stable_time_step();
  std::printf("time step: %.6g (%s), about %s steps to t = %g\n", dt,
              scene.run.fixed_time_step > 0.0 ? "fixed" : "stable step x time_step_factor",
              core::readable_count(scene.run.end_time / dt).c_str(), scene.run.end_time);
  warn_step_count(scene, *model, dt);
  warn_wall_time(scene, *model, dt);
  const double points = static_cast<double>(model->particle_count() + model->element_count());
  std::printf("memory estimate: %.1f MiB (%.0f bytes per particle or element)\n",
              static_cast<double>(model->bytes()) / (1024.0 * 1024.0),
              static_cast<double>(model->bytes()) / points);
  const double point_steps = points * core::planned_steps(scene, dt);
  std::printf(
      "wall time estimate: about %s on %d thread(s) (%s point-steps at a nominal 1.5 "
      "million per thread and second; plasticity, contact and coupling cost more, simple "
      "elastic particles less)\n",
      core::readable_duration(core::estimated_wall_seconds(point_steps, core::thread_count()))
          .c_str(),
      core::thread_count(), core::readable_count(point_steps).c_str());
  return 0;
}

int run(const std::string& path, std::string out_dir, const std::string& restart_dir) {
  refuse_deck(path);
  const core::Scene scene = core::read_scene(path);
  std::string checkpoint;
  if (!restart_dir.empty()) {
    if (!out_dir.empty() && out_dir != restart_dir)
      throw std::runtime_error("--restart " + restart_dir +
                               " continues that run's files; leave "
                               "out -o " +
                               out_dir);
    out_dir = restart_dir;
    checkpoint = core::newest_checkpoint(restart_dir);
    // The scene check first, before the model is built: a refused restart touches nothing.
    const std::vector<std::string> changes =
        core::scene_changes(core::read_checkpoint_header(checkpoint), scene);
    if (!changes.empty()) {
      std::string text = "cannot restart from " + checkpoint +
                         ": the scene changed since the checkpoint (only the end time, output, "
                         "history and checkpoint settings may):";
      for (const std::string& c : changes) text += "\n  " + c;
      throw std::runtime_error(text);
    }
  }
  if (out_dir.empty()) out_dir = core::default_output_directory(path);
  const std::unique_ptr<core::Model> model = make_model(scene);
  for (const std::string& w : core::contact_warnings(scene, *model))
    std::fprintf(stderr, "afemp: warning: %s\n", w.c_str());
  for (const core::SceneWarning& w : core::plausibility_warnings(scene))
    std::fprintf(stderr, "afemp: warning: %s\n", w.text().c_str());
  apps::ProgressReporter progress(stdout);
  core::RunOptions options;
  options.output_directory = out_dir;
  options.restart_from = checkpoint;
  options.progress = [&](const core::Progress& pr) { progress(pr); };
  options.progress_seconds = progress.interval();
  if (checkpoint.empty()) {
    warn_step_count(scene, *model, model->stable_time_step());
    warn_wall_time(scene, *model, model->stable_time_step());
    std::printf("afemp run %s -> %s (%d thread(s))\n", path.c_str(), out_dir.c_str(),
                core::thread_count());
  } else {
    const core::CheckpointHeader h = core::read_checkpoint_header(checkpoint);
    std::printf("afemp run %s -> %s (%d thread(s)), continuing from %s (step %ld, t = %.6g)\n",
                path.c_str(), out_dir.c_str(), core::thread_count(), checkpoint.c_str(), h.step,
                h.time);
    if (h.threads != core::thread_count())
      std::fprintf(stderr,
                   "afemp: warning: the checkpoint was written with %d thread(s), this run has "
                   "%d: the results go on correctly but not bit for bit as an uninterrupted run "
                   "(the sums of the grid transfer are added in another order); give --threads %d "
                   "for that\n",
                   h.threads, core::thread_count(), h.threads);
  }
  const core::InterruptHandler interrupts;
  options.stop_requested = [] { return core::interrupt_signal() != 0; };
  options.checkpoint_requested = [] { return core::take_checkpoint_request(); };
  try {
    const core::RunSummary s = analysis::run(*model, scene, options);
    progress.finish();
    apps::print_summary(stdout, scene, s);
    if (s.interrupted) {
      const int signal = core::interrupt_signal();
      std::fprintf(stderr,
                   "afemp: stopped by %s after step %ld (t = %.6g of %.6g): the final history "
                   "row, frame and summary are written in %s\n",
                   core::signal_name(signal), s.steps, s.time, scene.run.end_time, out_dir.c_str());
      if (!s.checkpoint.empty())
        std::fprintf(stderr, "afemp: checkpoint %s; continue with: afemp run %s --restart %s\n",
                     s.checkpoint.c_str(), path.c_str(), out_dir.c_str());
      else
        std::fprintf(stderr, "afemp: no checkpoint could be written: %s\n",
                     s.checkpoint_error.c_str());
      return 128 + signal;
    }
    core::OutputPaths paths;
    std::printf("output: %s/%s.xmf (%zu frames), %s/%s\n", out_dir.c_str(),
                paths.fields_stem.c_str(), s.field_frames, out_dir.c_str(),
                paths.history_file.c_str());
    if (!s.probes.empty())
      std::printf("probes: %s/probes/NAME.csv (%zu files)\n", out_dir.c_str(), s.probes.size());
    if (!s.checks_passed()) return exit_check_failed;
  } catch (const core::SimulationError& e) {
    progress.finish();
    std::fprintf(stderr, "afemp: simulation stopped: %s\n", e.what());
    std::fprintf(stderr, "afemp: output written so far is kept in %s\n", out_dir.c_str());
    return exit_simulation_error;
  } catch (const core::InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // Output that cannot be written (a full disk, a removed directory): what was written stays.
    progress.finish();
    const std::string what = e.what();
    std::fprintf(
        stderr, "afemp: run stopped: %s%s\n", what.c_str(),
        what.find("it is full") == std::string::npos ? core::disk_full_note(out_dir).c_str() : "");
    const std::vector<std::string> saved = core::list_checkpoints(out_dir);
    std::fprintf(stderr, "afemp: output written so far is kept in %s; %s\n", out_dir.c_str(),
                 saved.empty() ? "no checkpoint was written"
                               : ("the newest checkpoint is " + saved.back() + " (afemp run " +
                                  path + " --restart " + out_dir + ")")
                                     .c_str());
    return exit_output_error;
  }
  return 0;
}

int study(const std::string& path, std::string out_dir, int threads) {
  analysis::StudyPlan plan = analysis::read_study(path);
  if (threads > 0) plan.threads = threads;
  if (out_dir.empty()) out_dir = core::default_output_directory(path);
  std::printf("afemp study %s -> %s: %zu runs\n", path.c_str(), out_dir.c_str(), plan.runs.size());
  std::size_t done = 0;
  const analysis::StudyResult result = analysis::run_study(
      plan, [&](const analysis::StudyResult& so_far, const analysis::StudyRow& row) {
        std::printf("[%zu/%zu] %s\n", ++done, plan.runs.size(),
                    analysis::describe_row(so_far, row).c_str());
        std::fflush(stdout);
      });
  analysis::write_study(plan, result, out_dir);
  const analysis::StudyFiles files;
  std::printf("output: %s/%s, %s/%s, %s/%s", out_dir.c_str(), files.csv.c_str(), out_dir.c_str(),
              files.markdown.c_str(), out_dir.c_str(), files.plot.c_str());
  if (!plan.plot_value.empty()) std::printf(", %s/%s", out_dir.c_str(), files.value_plot.c_str());
  std::printf("\n");
  const bool all_ok = std::all_of(result.rows.begin(), result.rows.end(),
                                  [](const analysis::StudyRow& r) { return r.ok(); });
  return all_ok ? 0 : exit_check_failed;
}

// `afemp import DECK -o SCENE [--units U]`: writes the scene and its side files, and lists
// what the deck holds that the scene does not carry as the deck meant it.
int import_command(const std::string& deck_path, const std::string& scene_path,
                   const std::string& units) {
  const core::DeckImport deck = core::import_deck(deck_path, scene_path, {units});
  core::write_deck_import(deck, scene_path);
  std::printf("afemp import %s -> %s (%s deck", deck_path.c_str(), scene_path.c_str(),
              core::to_string(core::deck_format(deck_path)));
  for (const core::DeckFile& f : deck.files) std::printf(", %s", f.name.c_str());
  std::printf(")\nunits: %s\n", deck.units.c_str());
  std::size_t untranslated = 0;
  for (const core::DeckNote& n : deck.notes) {
    std::printf("  %s\n", core::describe(n).c_str());
    if (!n.approximated) ++untranslated;
  }
  std::printf(
      "%zu not translated, %zu approximated (listed at the top of the scene too); check "
      "it with `afemp check %s`\n",
      untranslated, deck.notes.size() - untranslated, scene_path.c_str());
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
  std::string restart_dir;
  run_cmd->add_option("--restart", restart_dir,
                      "continue the run in this directory from its newest checkpoint "
                      "(docs/restart.md)");

  auto* check_cmd = app.add_subcommand("check", "read and validate a scene, print the plan");
  check_cmd->add_option("SCENE", scene_path, "scene file (TOML)")->required();
  check_cmd->add_option("--threads", threads, "OpenMP threads")->check(CLI::PositiveNumber);

  auto* study_cmd = app.add_subcommand(
      "study",
      "run a study file's variations; write a CSV, a Markdown table and an error-vs-time plot");
  study_cmd->add_option("STUDY", scene_path, "study file (TOML, docs/study-format.md)")->required();
  study_cmd->add_option("-o,--output", out_dir, "output directory (default runs/<study name>)");
  study_cmd->add_option("--threads", threads, "OpenMP threads for every run (default: the study's)")
      ->check(CLI::PositiveNumber);

  std::string units;
  auto* import_cmd = app.add_subcommand(
      "import", "turn an LS-DYNA keyword deck or an MPM3D deck into a scene (docs/import.md)");
  import_cmd->add_option("DECK", scene_path, "deck (.k, .key, .dyn; .mpm)")->required();
  import_cmd->add_option("-o,--output", out_dir, "the scene to write (TOML)")->required();
  import_cmd->add_option("--units", units,
                         "the deck's unit system, converted into mm, ms, g, N, MPa: mm-ms-g, "
                         "m-s-kg, mm-s-t, mm-ms-kg, cm-us-g (default: numbers kept as they are)");

  CLI11_PARSE(app, argc, argv);
  // A file-size limit (ulimit -f) then fails the write like a full disk, which the run reports
  // and survives, instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
  core::skip_hdf5_exit_cleanup();
  if (!*study_cmd) core::set_thread_count(threads);
  try {
    if (*run_cmd) return run(scene_path, out_dir, restart_dir);
    if (*study_cmd) return study(scene_path, out_dir, threads);
    if (*import_cmd) return import_command(scene_path, out_dir, units);
    return check(scene_path);
  } catch (const core::InputError& e) {
    std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  }
}
