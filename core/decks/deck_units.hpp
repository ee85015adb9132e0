// The unit systems decks are written in, and the factors that bring their numbers into mm, ms,
// g, N, MPa (afemp's examples; docs/scene-format.md "Units"). A quantity is named by the
// powers of length, time and mass in it.
#pragma once

#include <span>
#include <string>

#include "afemp/errors.hpp"

namespace afemp::core {

// A unit system: its units of length, time and mass in mm, ms and g, and how it writes a
// density and a stress.
struct UnitSystem {
  const char* name;   // as --units takes it
  const char* label;  // as messages name it ("SI" for m-s-kg)
  const char* units;  // "m, s, kg, N, Pa"
  double length, time, mass;
  const char* density_unit;
  const char* stress_unit;
};
// The systems decks are written in (mm-ms-g first), which the plausibility warnings also try
// a scene without [run] units against (core/plausibility.cpp).
std::span<const UnitSystem> unit_systems();

struct Dimension {
  int length = 0, time = 0, mass = 0;
};

namespace dimension {
inline constexpr Dimension none{0, 0, 0};
inline constexpr Dimension length{1, 0, 0};
inline constexpr Dimension time{0, 1, 0};
inline constexpr Dimension rate{0, -1, 0};
inline constexpr Dimension mass{0, 0, 1};
inline constexpr Dimension velocity{1, -1, 0};
inline constexpr Dimension acceleration{1, -2, 0};
inline constexpr Dimension density{-3, 0, 1};
inline constexpr Dimension stress{-1, -2, 1};          // also energy per volume
inline constexpr Dimension specific_energy{2, -2, 0};  // per mass; c_p per kelvin
inline constexpr Dimension volume{3, 0, 0};
}  // namespace dimension

class UnitConversion {
 public:
  // `system` as DeckImportOptions::units; empty keeps the numbers. An unknown name is an
  // InputError at `at` listing the known ones.
  UnitConversion(const std::string& system, const SourceLocation& at);
  double operator()(double value, Dimension d) const;
  // "mm, ms, g, N, MPa (converted from m, s, kg, N, Pa)" or "the deck's own (...)".
  const std::string& description() const { return description_; }
  // The [run] units of the scene the numbers go into: "mm-ms-g" when converting, else empty
  // (the deck's own units, which the scene cannot name).
  const std::string& scene_units() const { return scene_units_; }

 private:
  double length_ = 1.0, time_ = 1.0, mass_ = 1.0;  // one deck unit in mm, ms, g
  std::string description_;
  std::string scene_units_;
};

}  // namespace afemp::core
