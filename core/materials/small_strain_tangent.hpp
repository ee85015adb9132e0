// Small-strain stress update and consistent (algorithmic) tangent of a material for the
// static implicit solve: the isotropic bulk law K tr(eps) for the pressure, the strength model
// for the deviator, and d sigma / d eps of that discrete update (Simo & Taylor, CMAME 48 (1985)
// 101-118; Simo & Hughes 1998, box 3.2 and eq. 3.3.11 for the radial returns of J2 and
// Johnson-Cook, the latter with its rate and temperature frozen: see small_strain_update).
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

}  // namespace afemp::core
