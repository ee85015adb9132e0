// Unit systems of decks and their factors into mm, ms, g, N, MPa (core/decks/deck_units.hpp).
#include "core/decks/deck_units.hpp"

#include <array>
#include <cmath>

namespace afemp::core {

namespace {

constexpr std::array<UnitSystem, 5> kSystems{{
    {"mm-ms-g", "mm-ms-g", "mm, ms, g, N, MPa", 1.0, 1.0, 1.0, "g/mm^3", "MPa"},
    {"m-s-kg", "SI", "m, s, kg, N, Pa", 1e3, 1e3, 1e3, "kg/m^3", "Pa"},
    {"mm-s-t", "mm-s-t", "mm, s, tonne, N, MPa", 1.0, 1e3, 1e6, "t/mm^3", "MPa"},
    {"mm-ms-kg", "mm-ms-kg", "mm, ms, kg, kN, GPa", 1.0, 1.0, 1e3, "kg/mm^3", "GPa"},
    {"cm-us-g", "cm-us-g", "cm, us, g, 10^7 N, Mbar", 10.0, 1e-3, 1.0, "g/cm^3", "Mbar"},
}};

}  // namespace

std::span<const UnitSystem> unit_systems() {
  return kSystems;
}

UnitConversion::UnitConversion(const std::string& system, const SourceLocation& at) {
  if (system.empty()) {
    description_ =
        "the deck's own, numbers unchanged (not stated: give --units to convert into mm, ms, g, "
        "N, MPa)";
    return;
  }
  std::string known;
  for (const UnitSystem& s : kSystems) {
    if (system == s.name) {
      length_ = s.length;
      time_ = s.time;
      mass_ = s.mass;
      description_ = std::string("mm, ms, g, N, MPa (the deck's ") + s.units + " converted)";
      scene_units_ = "mm-ms-g";
      return;
    }
    if (!known.empty()) known += ", ";
    known += s.name;
    known += " (";
    known += s.units;
    known += ")";
  }
  throw InputError(at, "--units", "unknown unit system '" + system + "'; known: " + known);
}

double UnitConversion::operator()(double value, Dimension d) const {
  return value * std::pow(length_, d.length) * std::pow(time_, d.time) * std::pow(mass_, d.mass);
}

}  // namespace afemp::core
