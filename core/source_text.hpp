// Text input files read line by line: numbered lines for messages, fields split at blanks or
// separators, and numbers that must parse completely (mesh readers, deck importers).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "afemp/errors.hpp"

namespace afemp::core {

// The lines of a file ('\r' removed), line i numbered i + 1 in messages. The lines are views
// into `text`, which must outlive this object.
class SourceText {
 public:
  SourceText(const std::string& text, std::string path);
  std::size_t size() const { return lines_.size(); }
  std::string_view line(std::size_t i) const { return lines_[i]; }
  SourceLocation at(std::size_t i) const { return {path_, static_cast<int>(i) + 1}; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string_view> lines_;
};

std::string_view trim(std::string_view s);
std::string upper(std::string_view s);
std::vector<std::string_view> split_words(std::string_view line);  // on blanks and tabs
// Fields between separators, each trimmed; "a,,b," gives {"a", "", "b", ""}.
std::vector<std::string_view> split_fields(std::string_view line, char separator);

// The whole field as a number ("what" names it in the message), or an InputError at `at`.
// Reals accept the Fortran exponent letter D, as LS-DYNA decks written by old tools use it.
std::int64_t to_integer(std::string_view field, const SourceLocation& at, const std::string& key,
                        const std::string& what);
double to_real(std::string_view field, const SourceLocation& at, const std::string& key,
               const std::string& what);
// A count as a person reads it: "12,345" below 1e9, "1.0e+300" above, "more than 1e+308"
// past the doubles, "nan" for NaN.
std::string readable_count(double count);

}  // namespace afemp::core
