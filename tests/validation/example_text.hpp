// The validation runs start from the example scenes and vary one value at a time.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace afemp::test {

// The text of examples/PATH (e.g. "taylor_bar/afemp.toml").
inline std::string example_text(const std::string& path) {
  std::ifstream in(std::string(AFEMP_SOURCE_DIR) + "/examples/" + path);
  EXPECT_TRUE(in.good()) << path;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Replaces the first `from` in text by `to` (the test fails if it is missing).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace afemp::test
