// Output path conventions in one place, so the app, the tests and the tools agree on where
// a run's files are.
#include "core/output/run_directory.hpp"

#include <filesystem>
#include <stdexcept>

namespace afemp::core {

std::string default_output_directory(const std::string& scene_path) {
  const std::filesystem::path path(scene_path);
  std::string stem = path.stem().string();
  // "." and ".." are not names a results directory should take.
  if (stem.empty() || stem == "." || stem == "..") stem = "run";
  // The folder name goes in front: examples keep one folder per case with scenes named
  // after the method (taylor_bar/mpm.toml, elastic_bar/mpm.toml), which must not collide.
  const std::string folder = path.parent_path().filename().string();
  if (!folder.empty() && folder != "." && folder != "..") stem = folder + "-" + stem;
  return (std::filesystem::path("runs") / stem).string();
}

OutputPaths default_output_paths(const std::string& scene_path) {
  OutputPaths paths;
  paths.directory = default_output_directory(scene_path);
  return paths;
}

std::string fields_h5_path(const OutputPaths& paths) {
  return (std::filesystem::path(paths.directory) / (paths.fields_stem + ".h5")).string();
}

std::string fields_xmf_path(const OutputPaths& paths) {
  return (std::filesystem::path(paths.directory) / (paths.fields_stem + ".xmf")).string();
}

std::string history_path(const OutputPaths& paths) {
  return (std::filesystem::path(paths.directory) / paths.history_file).string();
}

std::string warnings_path(const OutputPaths& paths) {
  return (std::filesystem::path(paths.directory) / paths.warnings_file).string();
}

void cut_to_checkpoint(const std::string& path, std::uintmax_t bytes) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error(path + ": cannot continue from the checkpoint: " + ec.message());
  if (size < bytes)
    throw std::runtime_error(path + ": cannot continue from the checkpoint: the file has " +
                             std::to_string(size) + " bytes, the checkpoint counts " +
                             std::to_string(bytes));
  std::filesystem::resize_file(path, bytes, ec);
  if (ec) throw std::runtime_error(path + ": cannot cut to the checkpoint: " + ec.message());
}

}  // namespace afemp::core
