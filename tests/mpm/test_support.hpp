// Helpers shared by the MPM unit tests (header only; not a test file itself): scenes built
// from TOML text, unique scratch directories and running the `afemp` command.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/scene.hpp"
#include "scratch_dir.hpp"

namespace afemp::mpm::test {

using afemp::test::ScratchDir;

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs `command` (shell syntax) with stdout and stderr captured in files of dir; the exit code
// is the shell's (a process a signal ended: 128 + the signal).
inline CommandResult run_captured(const std::string& command, const ScratchDir& dir) {
  const std::string out = dir.file("cmd.stdout"), err = dir.file("cmd.stderr");
  const std::string cmd = command + " >\"" + out + "\" 2>\"" + err + "\"";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// Runs `AFEMP_BINARY args` through the shell.
inline CommandResult run_afemp(const std::string& args, const ScratchDir& dir) {
  return run_captured(std::string("\"") + AFEMP_BINARY + "\" " + args, dir);
}

// Runs a shell command line (background jobs, kill, wait) under sh -c.
inline CommandResult run_shell(const std::string& line, const ScratchDir& dir) {
  return run_captured("sh -c '" + line + "'", dir);
}

inline std::string vec(double x, double y, double z) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", x, y, z);
  return buf;
}

}  // namespace afemp::mpm::test
