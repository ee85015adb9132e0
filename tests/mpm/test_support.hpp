// Helpers shared by the MPM unit tests (header only; not a test file itself): scenes built
// from TOML text, unique scratch directories and running the `afemp` command.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "core/scene.hpp"

namespace afemp::mpm::test {

// A fresh, empty directory under the system temp directory, unique per process and test,
// removed again when the object goes out of scope.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "afemp_mpm_";
    if (info != nullptr) name += std::string(info->test_suite_name()) + "_" + info->name();
    name += "_" + std::to_string(::getpid());
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // Writes text to DIR/name and returns the full path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = file(name);
    std::ofstream(p) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs `AFEMP_BINARY args` through the shell with stdout and stderr captured in files of dir.
inline CommandResult run_afemp(const std::string& args, const ScratchDir& dir) {
  const std::string out = dir.file("cmd.stdout"), err = dir.file("cmd.stderr");
  const std::string cmd = std::string("\"") + AFEMP_BINARY + "\" " + args + " >\"" + out +
                          "\" 2>\"" + err + "\"";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

inline std::string vec(double x, double y, double z) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", x, y, z);
  return buf;
}

}  // namespace afemp::mpm::test
