// The compression at which an EOS gives an initial pressure, and the geostatic stress
// (initial_pressure.hpp).
#include "core/materials/initial_pressure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <variant>

#include "core/materials/material.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

std::optional<double> compression_at_pressure(const Material& material, double p, double e) {
  if (material.is_explosive()) return std::nullopt;
  return std::visit(
      [&](const auto& eos) -> std::optional<double> {
        using E = std::decay_t<decltype(eos)>;
        if constexpr (std::is_same_v<E, NoEos>) {
          return 0.0;
        } else if constexpr (IsOwnPressureLaw<E>) {
          return std::nullopt;  // its pressure depends on the point's history
        } else {
          auto excess = [&](double mu) {
            const EosLinearForm f = eos.form(mu);
            return f.a + f.b * e - p;
          };
          double lo = -0.5, hi = 1.0;
          if (excess(hi) < 0.0 || excess(lo) > 0.0) return std::nullopt;
          for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
            const double mid = 0.5 * (lo + hi);
            (excess(mid) < 0.0 ? lo : hi) = mid;
          }
          return 0.5 * (lo + hi);
        }
      },
      material.eos);
}

std::optional<std::string> initial_pressure_refusal(const Material& material, double p, double e) {
  if (compression_at_pressure(material, p, e)) return std::nullopt;
  std::string why;
  if (material.is_explosive()) {
    why = "an explosive's state comes from its burn";
  } else if (has_own_pressure_law(material)) {
    why = "the pressure law " + std::string(model_name(material.eos)) + " depends on its history";
  } else {
    char buf[96];
    std::snprintf(buf, sizeof buf, "its EOS does not reach %.10g below twice the reference density",
                  p);
    why = buf;
  }
  return "material \"" + material.name + "\" cannot start at a pressure: " + why +
         "; allowed: a material with a Mie-Grueneisen, linear, linear-polynomial or no EOS, at "
         "a pressure it reaches";
}

SymTensor geostatic_stress(double surface, double k0, const Vec3& gravity, double density,
                           const Vec3& x) {
  const double g = norm(gravity);
  const Vec3 up = (-1.0 / g) * gravity;
  const double depth = std::max(surface - dot(x, up), 0.0);
  const double vertical = -density * g * depth;
  const double horizontal = k0 * vertical;
  const double d = vertical - horizontal;  // sigma = horizontal I + (vertical - horizontal) up up
  return {horizontal + d * up.x * up.x,
          horizontal + d * up.y * up.y,
          horizontal + d * up.z * up.z,
          d * up.y * up.z,
          d * up.x * up.z,
          d * up.x * up.y};
}

double elastic_energy(const Material& material, const SymTensor& stress) {
  const SymTensor s = stress.deviator();
  const double mean = stress.mean();
  return (double_dot(s, s) / (4.0 * material.shear_modulus()) +
          mean * mean / (2.0 * material.bulk_modulus())) /
         material.density;
}

std::optional<std::string> geostatic_stress_refusal(const Material& material, const Vec3& gravity,
                                                    bool pressure) {
  if (!(norm(gravity) > 0.0))
    return "a geostatic initial stress is the weight of the material above: give [run] gravity";
  if (pressure) return "give pressure or initial_stress, not both";
  if (material.has_eos())
    return "material \"" + material.name +
           "\" has an eos, whose pressure follows the density, not an initial stress; allowed: "
           "a material without an eos (its pressure is linear elastic)";
  return std::nullopt;
}

}  // namespace afemp::core
