// The `afemp` command: a thin layer over the library's public API (include/afemp/), as any
// program would use it. `afemp check` reads a scene and prints the plan (the starter); `afemp
// run` runs it with progress, output and a summary, both through afemp::Simulation; `afemp
// study` runs a study file's variations and writes their error against run time (the study
// layer, analysis/study*.hpp, is not part of the public library); `afemp import` turns an
// LS-DYNA or MPM3D deck into a scene.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "afemp/afemp.hpp"
#include "analysis/study.hpp"
#include "analysis/study_file.hpp"
#include "apps/progress_line.hpp"
#include "core/rank_link.hpp"
#ifdef AFEMP_HAVE_MPI
#include "core/mpi/mpi_rank_link.hpp"
#include "core/mpi/ranks.hpp"
#endif

namespace {

using namespace afemp;

constexpr int exit_input_error = 1;
constexpr int exit_simulation_error = 3;

constexpr int exit_check_failed = 4;  // a reference or tolerance the results miss
constexpr int exit_output_error = 5;  // output or a checkpoint could not be written (disk full)
// A run stopped by SIGINT or SIGTERM after writing its final row, frame and summary exits
// with 128 + the signal's number (130, 143), as a shell reports a process the signal ended.

// A deck given where a scene belongs: say how to import it, not that it is bad TOML.
void refuse_deck(const std::string& path) {
  const DeckFormat format = deck_format(path);
  if (format == DeckFormat::none) return;
  throw InputError({path, 0}, "scene",
                   std::string("this is an ") + to_string(format) +
                       " deck, not a scene; import it with `afemp import " + path +
                       " -o SCENE.toml` and run the scene (docs/import.md)");
}

// This process's rank and the ranks of a run divided among MPI ranks (0 of 1 otherwise): rank 0
// alone prints and writes the run's files.
int this_rank = 0, rank_total = 1;

// How many processes mpirun or mpiexec started, from the launchers' environment: Open MPI's
// OMPI_COMM_WORLD_SIZE, PMI_SIZE (MPICH's Hydra, Intel MPI, Slurm's PMI), MV2_COMM_WORLD_SIZE
// (MVAPICH2); 1 without a launcher.
struct Launch {
  long size = 1;
  std::string variable, value;
};

Launch launch() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MV2_COMM_WORLD_SIZE"}) {
    const char* value = std::getenv(name);
    if (value == nullptr) continue;
    char* end = nullptr;
    const long size = std::strtol(value, &end, 10);
    if (end == value || size <= 1) continue;
    return {size, name, value};
  }
  return {};
}

// Whether this process is one of several that Open MPI's launcher started for `afemp run`,
// which divides the run among them (docs/parallel.md). Any other start as one of several
// processes is refused before anything is read or written: each process would run the whole
// scene and write the same files over the others'.
bool divided_run(bool run_command) {
  const Launch l = launch();
  if (l.size <= 1) return false;
  const std::string started = "started as one of " + std::to_string(l.size) + " MPI processes (" +
                              l.variable + "=" + l.value + "), but ";
#ifdef AFEMP_HAVE_MPI
  if (l.variable != "OMPI_COMM_WORLD_SIZE")
    throw std::runtime_error(started +
                             "this afemp is built with Open MPI: start it with Open MPI's "
                             "mpirun or mpiexec (Debian's openmpi-bin)");
  if (!run_command)
    throw std::runtime_error(started +
                             "only `afemp run` divides among MPI ranks: run the other "
                             "commands as one process, without mpirun");
  return true;
#else
  (void)run_command;
  throw std::runtime_error(
      started +
      "this afemp is built without MPI (AFEMP_MPI=OFF): every process would run the whole scene "
      "and write the same output over the others'. Run one afemp without mpirun; it uses the "
      "machine's cores through OpenMP (--threads N, or OMP_NUM_THREADS)");
#endif
}

// The output directory of a rank other than 0 in a divided run: its loop writes there what
// rank 0 writes in the run's directory (frames of none of the particles; the same history),
// and the directory goes when the run ends.
struct RankScratch {
  std::string path;
  RankScratch() {
    std::string pattern = (std::filesystem::temp_directory_path() / "afemp-rank-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot create a scratch directory " + pattern + " for rank " +
                               std::to_string(this_rank));
    path = pattern;
  }
  ~RankScratch() { remove(); }
  RankScratch(const RankScratch&) = delete;
  RankScratch& operator=(const RankScratch&) = delete;
  void remove() {
    std::error_code ec;
    if (!path.empty()) std::filesystem::remove_all(path, ec);
  }
};

void print_warnings(const std::vector<std::string>& warnings) {
  if (this_rank != 0) return;
  for (const std::string& w : warnings) std::fprintf(stderr, "afemp: warning: %s\n", w.c_str());
}

int check(const std::string& path) {
  refuse_deck(path);
  // The model built and started without an output directory: what `afemp run` refuses at the
  // start (a probe naming a node the mesh lacks) fails here too, and nothing is written.
  const Simulation sim(afemp::read_scene(path));
  const Scene& scene = sim.scene();
  print_warnings(sim.warnings());
  std::printf("scene %s%s%s\n", path.c_str(), scene.run.title.empty() ? "" : ": ",
              scene.run.title.c_str());
  std::fputs(sim.describe().c_str(), stdout);
  const RunEstimate e = sim.estimate();
  std::printf("time step: %.6g (%s), about %s steps to t = %g\n", e.time_step,
              scene.run.fixed_time_step > 0.0 ? "fixed" : "stable step x time_step_factor",
              readable_count(e.steps).c_str(), scene.run.end_time);
  print_warnings(e.warnings);
  const double points = static_cast<double>(e.points);
  std::printf("memory estimate: %.1f MiB (%.0f bytes per particle or element)\n",
              static_cast<double>(e.bytes) / (1024.0 * 1024.0),
              static_cast<double>(e.bytes) / points);
  std::printf(
      "wall time estimate: about %s on %d thread(s) (%s point-steps at a nominal 1.5 "
      "million per thread and second; plasticity, contact and coupling cost more, simple "
      "elastic particles less)\n",
      readable_duration(e.wall_seconds).c_str(), e.threads,
      readable_count(points * e.planned_steps).c_str());
  return 0;
}

// Who prints: "afemp", or on a rank other than 0 of a divided run "afemp (rank K of N)".
std::string who() {
  return this_rank == 0 ? "afemp"
                        : "afemp (rank " + std::to_string(this_rank) + " of " +
                              std::to_string(rank_total) + ")";
}

// A divided run that failed after its start may have failed on one rank alone, while the others
// wait for it in a sum: every rank is stopped (MPI_Abort) once this one has said why; the files
// rank 0 wrote so far stay. A run in one process just returns the code.
int stop_ranks(int code, RankScratch* scratch) {
#ifdef AFEMP_HAVE_MPI
  if (rank_total > 1) {
    std::fflush(stdout);
    std::fflush(stderr);
    if (scratch) scratch->remove();
    core::abort_ranks(code);
  }
#endif
  (void)scratch;
  return code;
}

// `ranks`: the link of a run divided among MPI ranks (docs/parallel.md), else nullptr.
int run(const std::string& path, std::string out_dir, const std::string& restart_dir,
        core::RankLink* ranks, const RankBalance& balance) {
  refuse_deck(path);
  Scene read = afemp::read_scene(path);
  std::string checkpoint;
  if (!restart_dir.empty()) {
    if (!out_dir.empty() && out_dir != restart_dir)
      throw std::runtime_error("--restart " + restart_dir +
                               " continues that run's files; leave "
                               "out -o " +
                               out_dir);
    out_dir = restart_dir;
    // The scene check first, before the model is built: a refused restart touches nothing.
    checkpoint = restart_checkpoint(restart_dir, read);
  }
  if (out_dir.empty()) out_dir = default_output_directory(path);
  std::unique_ptr<RankScratch> scratch;
  if (this_rank != 0) scratch = std::make_unique<RankScratch>();
  apps::ProgressReporter progress(stdout);
  SimulationOptions options;
  options.output_directory = scratch ? scratch->path : out_dir;
  options.restart_from = checkpoint;
  options.progress = [&](const Progress& pr) { progress(pr); };
  options.progress_seconds = progress.interval();
  options.stop_requested = [] { return interrupt_signal() != 0; };
  options.checkpoint_requested = [] { return take_checkpoint_request(); };
  options.phase_log = &std::cout;
  if (ranks) {
    // Every rank stops, or writes a checkpoint, at the same step once any has the signal.
    options.stop_requested = [ranks] {
      return ranks->max_over_ranks(interrupt_signal() != 0 ? 1.0 : 0.0) > 0.0;
    };
    options.checkpoint_requested = [ranks] {
      return ranks->max_over_ranks(take_checkpoint_request() ? 1.0 : 0.0) > 0.0;
    };
    options.ranks = ranks;
    options.balance = balance;
  }
  // Started below, once the warnings and the plan are printed: what start() throws is the
  // run's (an output directory that cannot be written), reported as the run's.
  options.defer_start = true;
  Simulation sim(std::move(read), options);
  const Scene& scene = sim.scene();
  print_warnings(sim.warnings());
  if (ranks && checkpoint.empty()) {
    print_warnings(sim.estimate().warnings);
    std::printf("afemp run %s -> %s (%d MPI ranks x %d thread(s))\n", path.c_str(), out_dir.c_str(),
                rank_total, thread_count());
  } else if (ranks) {
    // A checkpoint holds the whole run, whatever wrote it: it is divided anew among these ranks.
    const CheckpointInfo h = read_checkpoint_info(checkpoint);
    std::printf(
        "afemp run %s -> %s (%d MPI ranks x %d thread(s)), continuing from %s (step %ld, "
        "t = %.6g; written by %d rank(s) x %d thread(s))\n",
        path.c_str(), out_dir.c_str(), rank_total, thread_count(), checkpoint.c_str(), h.step,
        h.time, h.ranks, h.threads);
  } else if (checkpoint.empty()) {
    print_warnings(sim.estimate().warnings);
    std::printf("afemp run %s -> %s (%d thread(s))\n", path.c_str(), out_dir.c_str(),
                thread_count());
  } else {
    const CheckpointInfo h = read_checkpoint_info(checkpoint);
    std::printf("afemp run %s -> %s (%d thread(s)), continuing from %s (step %ld, t = %.6g)\n",
                path.c_str(), out_dir.c_str(), thread_count(), checkpoint.c_str(), h.step, h.time);
    if (h.ranks > 1)
      std::fprintf(stderr,
                   "afemp: note: the checkpoint was written by %d MPI ranks; this process runs the "
                   "whole of it (the results go on to round-off, not bit for bit)\n",
                   h.ranks);
    else if (h.threads != thread_count())
      std::fprintf(stderr,
                   "afemp: warning: the checkpoint was written with %d thread(s), this run has "
                   "%d: the results go on correctly but not bit for bit as an uninterrupted run "
                   "(the sums of the grid transfer are added in another order); give --threads %d "
                   "for that\n",
                   h.threads, thread_count(), h.threads);
  }
  const InterruptHandler interrupts;
  try {
    sim.start();
    const RunSummary s = sim.run();
    progress.finish();
    apps::print_summary(stdout, scene, s);
    if (s.interrupted && this_rank != 0) return 128 + interrupt_signal();
    if (s.interrupted) {
      const int signal = interrupt_signal();
      std::fprintf(stderr,
                   "afemp: stopped by %s after step %ld (t = %.6g of %.6g): the final history "
                   "row, frame and summary are written in %s\n",
                   signal_name(signal), s.steps, s.time, scene.run.end_time, out_dir.c_str());
      if (!s.checkpoint.empty())
        std::fprintf(stderr, "afemp: checkpoint %s; continue with: afemp run %s --restart %s\n",
                     s.checkpoint.c_str(), path.c_str(), out_dir.c_str());
      else
        std::fprintf(stderr, "afemp: no checkpoint could be written: %s\n",
                     s.checkpoint_error.c_str());
      return 128 + signal;
    }
    const OutputPaths paths;
    std::printf("output: %s/%s.xmf (%zu frames), %s/%s, %s/%s (%zu warnings)\n", out_dir.c_str(),
                paths.fields_stem.c_str(), s.field_frames, out_dir.c_str(),
                paths.history_file.c_str(), out_dir.c_str(), paths.warnings_file.c_str(),
                s.warnings.size());
    if (!s.probes.empty())
      std::printf("probes: %s/probes/NAME.csv (%zu files)\n", out_dir.c_str(), s.probes.size());
    if (!s.checks_passed()) return exit_check_failed;
  } catch (const SimulationError& e) {
    progress.finish();
    std::fprintf(stderr, "%s: simulation stopped: %s\n", who().c_str(), e.what());
    std::fprintf(stderr, "%s: output written so far is kept in %s\n", who().c_str(),
                 out_dir.c_str());
    return stop_ranks(exit_simulation_error, scratch.get());
  } catch (const InputError& e) {
    if (rank_total == 1) throw;
    std::fprintf(stderr, "%s: %s\n", who().c_str(), e.what());
    return stop_ranks(exit_input_error, scratch.get());
  } catch (const std::runtime_error& e) {
    // Output that cannot be written (a full disk, a removed directory): what was written stays.
    progress.finish();
    const std::string what = e.what();
    std::fprintf(
        stderr, "%s: run stopped: %s%s\n", who().c_str(), what.c_str(),
        what.find("it is full") == std::string::npos ? disk_full_note(out_dir).c_str() : "");
    const std::vector<std::string> saved = list_checkpoints(out_dir);
    std::fprintf(stderr, "%s: output written so far is kept in %s; %s\n", who().c_str(),
                 out_dir.c_str(),
                 saved.empty() ? "no checkpoint was written"
                               : ("the newest checkpoint is " + saved.back() + " (afemp run " +
                                  path + " --restart " + out_dir + ")")
                                     .c_str());
    return stop_ranks(exit_output_error, scratch.get());
  } catch (const std::exception& e) {
    if (rank_total == 1) throw;
    std::fprintf(stderr, "%s: %s\n", who().c_str(), e.what());
    return stop_ranks(exit_input_error, scratch.get());
  }
  return 0;
}

int study(const std::string& path, std::string out_dir, int threads) {
  analysis::StudyPlan plan = analysis::read_study(path);
  if (threads > 0) plan.threads = threads;
  if (out_dir.empty()) out_dir = default_output_directory(path);
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

// `afemp import DECK -o SCENE [--units U] [--allow-untranslated]`: writes the scene and its
// side files, and lists what the deck holds that the scene does not carry as the deck meant it.
int import_command(const std::string& deck_path, const std::string& scene_path,
                   const DeckImportOptions& options) {
  const DeckImport deck = import_deck(deck_path, scene_path, options);
  write_deck_import(deck, scene_path);
  std::printf("afemp import %s -> %s (%s deck", deck_path.c_str(), scene_path.c_str(),
              to_string(deck_format(deck_path)));
  for (const DeckFile& f : deck.files) std::printf(", %s", f.name.c_str());
  std::printf(")\nunits: %s\n", deck.units.c_str());
  std::size_t untranslated = 0, changing = 0;
  for (const DeckNote& n : deck.notes) {
    std::printf("  %s\n", describe(n).c_str());
    if (!n.approximated) ++untranslated;
    if (n.changes_run) ++changing;
  }
  if (changing > 0)
    std::printf("%zu of them change the run (--allow-untranslated): the scene warns of them\n",
                changing);
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
  std::string balance = "particles";
  RankBalance rank_balance;
  run_cmd
      ->add_option("--balance", balance,
                   "under mpirun: what the ranks' loads are kept even by as the material "
                   "moves: particles (the default; a run repeats itself bit for bit), time "
                   "(each rank's measured seconds: faster where particles differ in cost, "
                   "repeats to round-off) or off (docs/parallel.md)")
      ->check(CLI::IsMember({"particles", "time", "off"}));
  run_cmd
      ->add_option("--imbalance", rank_balance.imbalance,
                   "under mpirun: rebalance when the slowest rank's cost exceeds the ranks' mean "
                   "by this factor, checked every 100 steps (default 1.1)")
      ->check(CLI::Range(1.0, 100.0));

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

  DeckImportOptions import_options;
  auto* import_cmd = app.add_subcommand(
      "import", "turn an LS-DYNA keyword deck or an MPM3D deck into a scene (docs/import.md)");
  import_cmd->add_option("DECK", scene_path, "deck (.k, .key, .dyn; .mpm)")->required();
  import_cmd->add_option("-o,--output", out_dir, "the scene to write (TOML)")->required();
  import_cmd->add_option("--units", import_options.units,
                         "the deck's unit system, converted into mm, ms, g, N, MPa: mm-ms-g, "
                         "m-s-kg, mm-s-t, mm-ms-kg, cm-us-g (default: numbers kept as they are)");
  import_cmd->add_flag("--allow-untranslated", import_options.allow_untranslated,
                       "write the scene even when the deck holds a keyword that changes the run "
                       "and is not translated (contact, initial conditions, loads, ...); the "
                       "scene then warns of it");

  CLI11_PARSE(app, argc, argv);
  // A file-size limit (ulimit -f) then fails the write like a full disk, which the run reports
  // and survives, instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
  skip_hdf5_exit_cleanup();
  if (!*study_cmd) set_thread_count(threads);
  bool divided = false;
  try {
    divided = divided_run(static_cast<bool>(*run_cmd));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  }
  core::RankLink* ranks = nullptr;
#ifdef AFEMP_HAVE_MPI
  // A run divided among MPI ranks: every rank reads the scene and runs the loop; rank 0 prints
  // and writes the run's files, the others' standard output goes nowhere.
  std::unique_ptr<core::MpiSession> session;
  core::MpiRankLink link;
  if (divided) {
    try {
      session = std::make_unique<core::MpiSession>(argc, argv);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "afemp: %s\n", e.what());
      return exit_input_error;
    }
    ranks = &link;
    this_rank = link.rank();
    rank_total = link.ranks();
    if (this_rank != 0 && std::freopen("/dev/null", "w", stdout) == nullptr) std::fclose(stdout);
  }
#endif
  (void)divided;
  // The errors caught here come before a divided run starts its loop, on every rank alike:
  // rank 0 says why.
  try {
    rank_balance.cost = balance == "time"  ? RankBalance::Cost::time
                        : balance == "off" ? RankBalance::Cost::off
                                           : RankBalance::Cost::particles;
    if (*run_cmd) return run(scene_path, out_dir, restart_dir, ranks, rank_balance);
    if (*study_cmd) return study(scene_path, out_dir, threads);
    if (*import_cmd) return import_command(scene_path, out_dir, import_options);
    return check(scene_path);
  } catch (const InputError& e) {
    if (this_rank == 0) std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  } catch (const std::exception& e) {
    if (this_rank == 0) std::fprintf(stderr, "afemp: %s\n", e.what());
    return exit_input_error;
  }
}
