// Text input files read line by line (core/source_text.hpp).
#include "core/source_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace afemp::core {

SourceText::SourceText(const std::string& text, std::string path) : path_(std::move(path)) {
  const std::string_view all(text);
  std::size_t begin = 0;
  while (begin < all.size()) {
    std::size_t end = all.find('\n', begin);
    if (end == std::string_view::npos) end = all.size();
    std::string_view line = all.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines_.push_back(line);
    begin = end + 1;
  }
}

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::vector<std::string_view> split_fields(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = line.find(separator, begin);
    fields.push_back(trim(line.substr(begin, end == std::string_view::npos ? end : end - begin)));
    if (end == std::string_view::npos) return fields;
    begin = end + 1;
  }
}

namespace {

std::string not_a_number(std::string_view field, const char* kind, const std::string& what) {
  return "expected " + std::string(kind) + " for " + what + ", found '" + std::string(field) + "'";
}

}  // namespace

std::int64_t to_integer(std::string_view field, const SourceLocation& at, const std::string& key,
                        const std::string& what) {
  std::string_view s = trim(field);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    throw InputError(at, key, not_a_number(field, "an integer", what));
  return v;
}

double to_real(std::string_view field, const SourceLocation& at, const std::string& key,
               const std::string& what) {
  std::string s(trim(field));
  if (!s.empty() && s.front() == '+') s.erase(0, 1);
  std::replace_if(
      s.begin(), s.end(), [](char c) { return c == 'd' || c == 'D'; }, 'e');
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
    throw InputError(at, key, not_a_number(field, "a finite number", what));
  return v;
}

std::string readable_count(double count) {
  char buf[64];
  if (std::isnan(count)) return "nan";
  if (!std::isfinite(count)) return "more than 1e+308";
  if (!(std::abs(count) < 1e9)) {
    std::snprintf(buf, sizeof buf, "%.1e", count);
    return buf;
  }
  std::snprintf(buf, sizeof buf, "%.0f", std::round(std::abs(count)));
  std::string digits = buf, out = count < 0.0 ? "-" : "";
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace afemp::core
