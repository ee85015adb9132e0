// Small-strain stress update and consistent (algorithmic) tangent of a material for the
// static implicit solve: the isotropic bulk law K tr(eps) for the pressure, the strength model
// for the deviator, and d sigma / d eps of that discrete update (Simo & Taylor, CMAME 48 (1985)
// 101-118; Simo & Hughes 1998, box 3.2 and eq. 3.3.11 for the radial returns of J2 and
// Johnson-Cook, the latter with its rate and temperature frozen: see small_strain_update); and
// the same for a bar under uniaxial stress (trusses): the 1-D return map and its tangent
// E H / (E + H) (Simo & Hughes 1998, sec. 1.4).
#pragma once

#include <array>

#include "afemp/material.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

// A 6x6 matrix in Voigt order (xx, yy, zz, yz, xz, xy), acting on engineering strains
// (gamma_yz = 2 eps_yz, ...) and giving stresses.
using VoigtMatrix = std::array<std::array<double, 6>, 6>;

// The converged state of a point at the end of the last load step.
struct SmallStrainPoint {
  SymTensor strain{};    // total strain (tensor components)
  SymTensor deviator{};  // stress deviator
  double plastic_strain = 0.0;
};

struct SmallStrainResult {
  SymTensor stress{};
  double plastic_strain = 0.0;  // at the end of the increment
  VoigtMatrix tangent{};        // d stress / d strain of this update
};

// Throws std::invalid_argument naming the material and its strength model or EOS when the
// static solve has no tangent for it: only the elastic, J2 and Johnson-Cook strength models
// without an EOS (the bulk law K tr(eps)) have one here, and a secant is never put in its place.
void check_small_strain_tangent(const Material& material);

// The stress, plastic strain and consistent tangent at total strain `strain` from the converged
// state `from` (a pure function: Newton iterations and line searches call it freely). The
// deviator comes from the strength model's own update (J2Plasticity::update,
// JohnsonCook::update, Elastic::update) with the deviatoric strain increment, so the explicit
// and the static solve share one return map. The update sees no time step and the material's
// initial temperature: Johnson-Cook's rate factor is 1 (its quasi-static curve) and its thermal
// factor stays that of the initial temperature in every load step. The material must pass
// check_small_strain_tangent.
SmallStrainResult small_strain_update(const Material& material, const SmallStrainPoint& from,
                                      const SymTensor& strain);

// The converged state of a bar (a truss) under uniaxial stress: its axial strain and stress
// and its equivalent plastic strain (the accumulated |d eps_p|, which sets the yield stress).
struct SmallStrainBarPoint {
  double strain = 0.0;
  double stress = 0.0;
  double plastic_strain = 0.0;
};

struct SmallStrainBarResult {
  double stress = 0.0;
  double plastic_strain = 0.0;  // at the end of the increment
  double tangent = 0.0;         // d stress / d strain of this update: E, or E H / (E + H)
};

// The axial stress, plastic strain and consistent tangent of a bar at axial strain `strain`
// from the converged state `from`, by the 1-D return map of isotropic hardening (Simo & Hughes
// 1998, box 1.4): sigma_trial = sigma_n + E (eps - eps_n), and when |sigma_trial| exceeds
// sigma_y(eps_p) the plastic increment dp solves |sigma_trial| - E dp = sigma_y(eps_p + dp),
// tangent E H / (E + H) with H = d sigma_y / d eps_p at the increment's end (E_t = E H / (E + H)
// of the bilinear curve for J2). The strength model's own radial return does it: the uniaxial
// stress sigma is the deviator sigma diag(2/3, -1/3, -1/3), whose von Mises stress is |sigma|,
// and with shear modulus E / 3 its consistency condition q_trial - 3G dp = sigma_y is the 1-D
// one. The same frozen rate and temperature as small_strain_update; the same materials.
SmallStrainBarResult small_strain_bar_update(const Material& material,
                                             const SmallStrainBarPoint& from, double strain);

}  // namespace afemp::core
