// Checkpoint files, their header and the restart's scene comparison (core/checkpoint.hpp).
#include "core/checkpoint.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/parallel.hpp"
#include "core/phases.hpp"
#include "core/state_archive.hpp"

namespace afemp::core {

namespace fs = std::filesystem;

std::uint64_t file_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  std::uint64_t h = 14695981039346656037ull;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[i]);
      h *= 1099511628211ull;
    }
  }
  return h;
}

std::string disk_full_note(const std::string& directory) {
  std::error_code ec;
  const fs::space_info s = fs::space(directory, ec);
  if (ec || s.available > (std::uintmax_t{64} << 20)) return "";
  return " (the disk holding " + directory + " has " + std::to_string(s.available) +
         " bytes free: it is full)";
}

CheckpointHeader checkpoint_header(const Scene& scene, long step, double time, std::string reason) {
  CheckpointHeader h;
  h.scene_path = scene.path;
  h.scene_text = scene.source;
  for (const BodySpec& b : scene.bodies) {
    std::string path;
    if (const auto* list = std::get_if<PointListShape>(&b.shape)) path = list->path;
    if (const auto* mesh = std::get_if<MeshFileShape>(&b.shape)) path = mesh->path;
    if (path.empty() || std::ranges::find(h.files, path) != h.files.end()) continue;
    h.files.push_back(path);
    h.file_hash.push_back(file_hash(path));
  }
  h.threads = thread_count();
  h.step = step;
  h.time = time;
  h.reason = std::move(reason);
  return h;
}

void visit_header(StateArchive& a, CheckpointHeader& h) {
  const StateArchive::Group group(a, "header");
  a.item("format", h.format);
  if (a.loading() && h.format != checkpoint_format)
    throw CheckpointError(a.path() + ": checkpoint format " + std::to_string(h.format) +
                          ", this afemp reads format " + std::to_string(checkpoint_format));
  a.item("scene_path", h.scene_path);
  a.item("scene_text", h.scene_text);
  a.item("files", h.files);
  a.item("file_hash", h.file_hash);
  a.item("threads", h.threads);
  if (!a.loading() || a.has("ranks")) a.item("ranks", h.ranks);
  a.item("step", h.step);
  a.item("time", h.time);
  a.item("reason", h.reason);
  if (a.loading() && h.file_hash.size() != h.files.size())
    throw CheckpointError(a.where("file_hash") + ": one hash per file expected");
}

CheckpointHeader read_checkpoint_header(const std::string& path) {
  StateArchive a(path, StateArchive::Mode::load);
  CheckpointHeader h;
  visit_header(a, h);
  return h;
}

std::string checkpoint_directory(const std::string& run_directory) {
  return (fs::path(run_directory) / "checkpoints").string();
}

std::string checkpoint_path(const std::string& run_directory, long step) {
  char name[40];
  std::snprintf(name, sizeof name, "step_%012ld.h5", step);
  return (fs::path(checkpoint_directory(run_directory)) / name).string();
}

std::vector<std::string> list_checkpoints(const std::string& run_directory) {
  std::vector<std::string> out;
  std::error_code ec;
  const fs::path dir = checkpoint_directory(run_directory);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // step_ + 12 digits + .h5: the zero-padded step sorts them by name.
    if (name.size() == 20 && name.rfind("step_", 0) == 0 && name.ends_with(".h5") &&
        it->is_regular_file(ec))
      out.push_back(it->path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string newest_checkpoint(const std::string& run_directory) {
  std::error_code ec;
  if (!fs::is_directory(run_directory, ec))
    throw CheckpointError(run_directory +
                          ": no such run directory (--restart takes the "
                          "directory a run wrote, e.g. runs/NAME)");
  const std::vector<std::string> all = list_checkpoints(run_directory);
  if (all.empty())
    throw CheckpointError(run_directory + ": no checkpoint in " +
                          checkpoint_directory(run_directory) +
                          " (a run writes one at [run] checkpoint_every, every "
                          "checkpoint_wall_every seconds, on SIGUSR1, and when stopped by "
                          "SIGINT or SIGTERM)");
  return all.back();
}

namespace {

struct FlatValue {
  std::string text;
  int line = 0;
};

// Every leaf of a TOML document by its dotted key (arrays of tables by index: bodies[1].name);
// an array of plain values is one leaf.
void flatten(const toml::node& node, const std::string& key,
             std::map<std::string, FlatValue>& out) {
  if (const toml::table* t = node.as_table()) {
    for (const auto& [k, v] : *t)
      flatten(v, key.empty() ? std::string(k.str()) : key + "." + std::string(k.str()), out);
    return;
  }
  if (const toml::array* a = node.as_array()) {
    const bool tables = !a->empty() && std::all_of(a->begin(), a->end(), [](const toml::node& n) {
      return n.is_table();
    });
    if (tables) {
      for (std::size_t i = 0; i < a->size(); ++i)
        flatten(*a->get(i), key + "[" + std::to_string(i) + "]", out);
      return;
    }
  }
  std::ostringstream text;
  node.visit([&](const auto& n) { text << n; });
  out[key] = {text.str(), static_cast<int>(node.source().begin.line)};
}

bool may_change(const std::string& key) {
  static const std::set<std::string> allowed = {"run.end_time",
                                                "run.max_steps",
                                                "run.output_every",
                                                "run.output_times",
                                                "run.history_every",
                                                "run.history_interval",
                                                "run.title",
                                                "run.quiet",
                                                "run.untranslated",
                                                "run.units",
                                                "run.energy_error_limit",
                                                "run.checkpoint_every",
                                                "run.checkpoint_wall_every",
                                                "run.checkpoint_keep"};
  return allowed.contains(key);
}

// A static or implicit phase's solver settings may change while the phase has not started at
// the checkpoint's time: a restart from the checkpoint written at its start (before a solve that
// failed) runs it with the new ones.
bool phase_setting_may_change(const std::string& key, double time, const Scene& now) {
  static const std::set<std::string> settings = {"load_steps", "max_iterations", "tolerance",
                                                 "time_step", "alpha"};
  if (key.rfind("phases[", 0) != 0) return false;
  const std::size_t close = key.find("].");
  if (close == std::string::npos) return false;
  std::size_t k = 0;
  try {
    k = static_cast<std::size_t>(std::stoul(key.substr(7, close - 7)));
  } catch (const std::exception&) {
    return false;
  }
  if (k >= now.phases.size() || !settings.contains(key.substr(close + 2))) return false;
  return phase_start(now, k) >= time * (1.0 - 1e-12);
}

std::map<std::string, FlatValue> flat_scene(const std::string& text, const std::string& path) {
  std::map<std::string, FlatValue> out;
  if (text.empty()) return out;
  try {
    flatten(toml::parse(std::string_view(text), std::string_view(path)), "", out);
  } catch (const toml::parse_error&) {
    // The scene parsed when the run began; a checkpoint's copy that does not is no scene.
    out["(scene text)"] = {"unreadable", 0};
  }
  return out;
}

}  // namespace

std::vector<std::string> scene_changes(const CheckpointHeader& saved, const Scene& now) {
  std::vector<std::string> out;
  const auto before = flat_scene(saved.scene_text, saved.scene_path);
  const auto after = flat_scene(now.source, now.path);
  const std::string file = now.path.empty() ? std::string("the scene") : now.path;
  auto allowed = [&](const std::string& key) {
    return may_change(key) || phase_setting_may_change(key, saved.time, now);
  };
  for (const auto& [key, was] : before) {
    if (allowed(key)) continue;
    const auto it = after.find(key);
    if (it == after.end())
      out.push_back(key + ": " + was.text + " in the checkpoint, absent now");
    else if (it->second.text != was.text)
      out.push_back(key + ": " + was.text + " in the checkpoint, " + it->second.text + " now (" +
                    file + " line " + std::to_string(it->second.line) + ")");
  }
  for (const auto& [key, is] : after)
    if (!allowed(key) && !before.contains(key))
      out.push_back(key + ": absent in the checkpoint, " + is.text + " now (" + file + " line " +
                    std::to_string(is.line) + ")");
  for (std::size_t f = 0; f < saved.files.size(); ++f) {
    const std::uint64_t h = file_hash(saved.files[f]);
    if (h != saved.file_hash[f])
      out.push_back("file " + saved.files[f] + ": " +
                    (h == 0 ? std::string("cannot be read now")
                            : std::string("its contents changed since the checkpoint")));
  }
  return out;
}

}  // namespace afemp::core
