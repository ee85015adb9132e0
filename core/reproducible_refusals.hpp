// What the reproducible mode ([run] reproducible = true; docs/parallel.md, "The reproducible
// mode") covers: the stages whose sums it makes independent of their order. A scene that asks for
// it with a stage whose sums it does not cover is refused, naming that stage, by the parser (at the
// key's line) and by the check of a scene built in code alike.
#pragma once

#include <optional>
#include <string>

#include "afemp/scene.hpp"

namespace afemp::core {

inline std::optional<std::string> reproducible_refusal(const Scene& scene) {
  if (!scene.run.reproducible) return std::nullopt;
  std::string what;
  // Particles: a body of them, or hexahedra that convert into them. The couplings' mesh nodes
  // add their terms into the grid's fixed-point sums as particles do (mpm/grid_points.hpp).
  bool particles = false;
  for (const BodySpec& b : scene.bodies)
    particles = particles || b.discretisation == Discretisation::particles || b.conversion;
  const MpmSettings& m = scene.mpm;
  if (particles && (m.shape == ShapeFunction::cpdi1 || m.shape == ShapeFunction::cpdi2))
    what =
        "the CPDI shape functions (mpm.shape_function): their gradients have no bound the "
        "nodal sums' fixed point can be scaled by";
  // [[phases]] need nothing: a relaxation is explicit steps, and a static or implicit phase's
  // solve is serial but for the BLAS, which the mode runs on one thread (fem/static_phase.cpp),
  // and on ranks it is rank 0's one-process solve.
  if (what.empty()) return std::nullopt;
  return "the reproducible mode (results bit-identical on any rank and thread count) covers "
         "scenes of meshes, of particles with the linear hat, uGIMP or the B-splines, walls and "
         "grid contact, and of both coupled, their [[phases]] too; this scene has " +
         what + "; allowed: reproducible = false, or a scene without it (docs/parallel.md)";
}

}  // namespace afemp::core
