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

// The table of text that starts at the line `header` ("[materials.copper]", "[[bodies]]"), to
// the next line that starts a table; for an array of tables, the first whose lines contain
// `containing` (e.g. "name = \"liner\""). The test fails if there is none.
inline std::string table(const std::string& text, const std::string& header,
                         const std::string& containing = "") {
  for (std::size_t at = text.find(header + "\n"); at != std::string::npos;
       at = text.find(header + "\n", at + 1)) {
    if (at != 0 && text[at - 1] != '\n') continue;
    const std::size_t end = text.find("\n[", at + header.size());
    const std::string t = text.substr(at, end == std::string::npos ? end : end + 1 - at);
    if (t.find(containing) != std::string::npos) return t;
  }
  ADD_FAILURE() << header << " " << containing;
  return {};
}

}  // namespace afemp::test
