// Helpers for tests of input errors: where a text sits in a scene or mesh file, and the
// message a scene text raises (header only; not a test file itself).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "afemp/errors.hpp"
#include "core/scene.hpp"

namespace afemp::test {

// 1-based number of the line of `text` holding the first occurrence of `needle`.
inline int line_of(const std::string& text, const std::string& needle) {
  const auto pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << needle;
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// what() of the InputError that parsing `text` throws ("" and a failure when none is thrown).
inline std::string error_of(const std::string& text, const std::string& path = "scene.toml") {
  try {
    core::parse_scene(text, path);
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return "";
}

// what() of the InputError that parsing `text` or checking the parsed scene as a whole
// (core::check_scene: rules across tables) throws ("" and a failure when neither throws).
inline std::string checked_error_of(const std::string& text,
                                    const std::string& path = "scene.toml") {
  try {
    core::check_scene(core::parse_scene(text, path));
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return "";
}

}  // namespace afemp::test
