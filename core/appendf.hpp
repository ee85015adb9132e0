// printf-style appending to a string, for the reports `afemp check` prints (describe()).
#pragma once

#include <cstdio>
#include <string>

namespace afemp::core {

template <class... Args>
void appendf(std::string& out, const char* format, Args... args) {
  char buf[512];
  // Every caller passes a literal; clang cannot see it through the template when no argument
  // follows (a "%%" still needs the formatting).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-security"
  std::snprintf(buf, sizeof buf, format, args...);
#pragma GCC diagnostic pop
  out += buf;
}

}  // namespace afemp::core
