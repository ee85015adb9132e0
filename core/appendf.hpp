// printf-style appending to a string, for the reports `afemp check` prints (describe()).
#pragma once

#include <cstdio>
#include <string>

namespace afemp::core {

template <class... Args>
void appendf(std::string& out, const char* format, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, format, args...);
  out += buf;
}

}  // namespace afemp::core
