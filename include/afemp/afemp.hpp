// The afemp library in one include: scenes (materials, bodies, contacts, constraints, walls,
// run settings) built in code or read from a scene file, and the Simulation that runs them.
// docs/library.md is the tutorial.
#pragma once

#include "afemp/deck_import.hpp"
#include "afemp/energies.hpp"
#include "afemp/errors.hpp"
#include "afemp/interrupt.hpp"
#include "afemp/material.hpp"
#include "afemp/probes.hpp"
#include "afemp/run.hpp"
#include "afemp/run_directory.hpp"
#include "afemp/scene.hpp"
#include "afemp/simulation.hpp"
#include "afemp/tensor.hpp"
#include "afemp/user_material.hpp"

/// The vector functions of afemp/tensor.hpp, in namespace afemp.
namespace afemp {
using core::cross;
using core::dot;
using core::norm;
}  // namespace afemp
