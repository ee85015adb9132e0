// Where a run writes its results. By default a scene "some/where/NAME.toml" writes into
// "runs/where-NAME" relative to the current working directory, so runs never litter the
// examples tree and rerunning a scene replaces its previous results.
#pragma once

#include <cstdint>
#include <string>

#include "afemp/run_directory.hpp"  // OutputPaths

namespace afemp::core {

// "runs/<stem of scene_path>" (relative, resolved against the cwd when used); the stem is the
// file name without its last extension: "examples/taylor_bar/mpm.toml" -> "runs/mpm".
// Two scenes with the same file name share a directory: pass an explicit directory then.
// An empty or stem-less path gives "runs/run".
std::string default_output_directory(const std::string& scene_path);

// The default paths for a scene.
OutputPaths default_output_paths(const std::string& scene_path);

// DIR/STEM.h5, DIR/STEM.xmf, DIR/history.csv and DIR/warnings.txt.
std::string fields_h5_path(const OutputPaths& paths);
std::string fields_xmf_path(const OutputPaths& paths);
std::string history_path(const OutputPaths& paths);
std::string warnings_path(const OutputPaths& paths);

// A restart (core/checkpoint.hpp): cuts a run file back to its length `bytes` at the
// checkpoint, dropping what was written after it, before the caller appends. Throws
// std::runtime_error naming the file when it is missing, shorter, or cannot be cut.
void cut_to_checkpoint(const std::string& path, std::uintmax_t bytes);

}  // namespace afemp::core
