// What the deck importers share (include/afemp/deck_import.hpp, core/decks/scene_text.hpp):
// recognising a deck, the scene's header comments and number syntax, writing the files.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "afemp/deck_import.hpp"
#include "core/decks/scene_text.hpp"
#include "core/source_text.hpp"

namespace afemp::core {

DeckFormat deck_format(const std::string& path) {
  const std::string ext = upper(std::filesystem::path(path).extension().string());
  if (ext == ".K" || ext == ".KEY" || ext == ".DYN") return DeckFormat::lsdyna;
  if (ext == ".MPM") return DeckFormat::mpm3d;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::string first = upper(trim(line));
    if (first.empty() || first.starts_with('$') || first.starts_with('!') || first.starts_with('#'))
      continue;
    if (first.starts_with("*KEYWORD")) return DeckFormat::lsdyna;
    if (first.starts_with("MPM3")) return DeckFormat::mpm3d;
    break;
  }
  return DeckFormat::none;
}

const char* to_string(DeckFormat format) {
  switch (format) {
    case DeckFormat::lsdyna:
      return "LS-DYNA";
    case DeckFormat::mpm3d:
      return "MPM3D";
    case DeckFormat::none:
      break;
  }
  return "scene";
}

std::string describe(const DeckNote& note) {
  return note.at.file + ":" + std::to_string(note.at.line) + ": " + note.keyword + ": " +
         (note.approximated  ? "approximated: "
          : note.changes_run ? "not translated, the run differs: "
                             : "not translated: ") +
         note.what;
}

std::string toml_number(double v) {
  char buf[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;  // a control character has no place here
    out += c;
  }
  return out + "\"";
}

std::string toml_vec3(double x, double y, double z) {
  std::string s = "[";  // appended piece by piece: "[" + std::string trips GCC 12's -Wrestrict
  s += toml_number(x);
  s += ", ";
  s += toml_number(y);
  s += ", ";
  s += toml_number(z);
  return s + "]";
}

std::string imported_scene_header(const std::string& deck_path, DeckFormat format,
                                  const std::string& units, const std::vector<DeckNote>& notes) {
  std::string s = "# Imported by `afemp import` from " + deck_path + " (" + to_string(format) +
                  " deck; docs/import.md).\n# Units: " + units + ".\n";
  if (notes.empty()) return s + "# Everything the deck holds is translated.\n";
  if (std::any_of(notes.begin(), notes.end(), [](const DeckNote& n) { return n.changes_run; }))
    s += "# WARNING: imported with --allow-untranslated: this scene does not run as the deck "
         "means\n# (the lines 'the run differs' below; [run] untranslated repeats them for "
         "`afemp check`).\n";
  s += "# What the deck holds that this scene does not carry as the deck meant it:\n";
  for (const DeckNote& n : notes) s += "#   " + describe(n) + "\n";
  return s;
}

void refuse_untranslated(const std::vector<DeckNote>& notes, const DeckImportOptions& options) {
  if (options.allow_untranslated) return;
  const DeckNote* first = nullptr;
  std::string others;
  for (const DeckNote& n : notes) {
    if (!n.changes_run) continue;
    if (first == nullptr)
      first = &n;
    else
      others +=
          (others.empty() ? "" : ", ") + n.keyword + " (line " + std::to_string(n.at.line) + ")";
  }
  if (first == nullptr) return;
  throw InputError(first->at, first->keyword,
                   "not translated, and the run would differ for it: " + first->what +
                       (others.empty() ? "" : "; so do " + others) +
                       ". Translate it into the scene by hand after importing with "
                       "--allow-untranslated (the scene then warns of it), or remove it "
                       "(docs/import.md)");
}

std::string untranslated_run_key(const std::vector<DeckNote>& notes) {
  std::string s;
  for (const DeckNote& n : notes)
    if (n.changes_run) s += "  " + toml_string(describe(n)) + ",\n";
  return s.empty() ? s : "untranslated = [\n" + s + "]\n";
}

void write_deck_import(const DeckImport& deck, const std::string& scene_path) {
  const std::filesystem::path folder = std::filesystem::path(scene_path).parent_path();
  const auto write = [](const std::filesystem::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    if (!out) throw InputError({p.string(), 0}, "-o", "cannot write the file");
  };
  for (const DeckFile& f : deck.files) write(folder / f.name, f.text);
  write(scene_path, deck.scene);
}

}  // namespace afemp::core
