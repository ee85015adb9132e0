// Failure models in hexahedra (core/materials/failure.hpp, composed in finish_increment).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "afemp/errors.hpp"
#include "core/scene.hpp"
#include "fem/fe_solver.hpp"

namespace afemp::fem {
namespace {

// A 1 mm cube of 2024-T351 aluminium (2 x 2 x 2 one-point hexahedra; Johnson-Cook strength
// A 265, B 426, n 0.34, C 0.015; no heating) compressed between a fixed, frictionless plane
// (z = 0) and a frictionless rigid wall moving down at 1 m/s, with symmetry planes x = 0 and
// y = 0: homogeneous uniaxial compression, triaxiality sigma* = -p / sigma_vm = -1/3.
// Reference: Johnson & Cook (1985) damage with the 2024-T351 constants of Johnson & Holmquist
// (1989), D1 = 0.13, D2 = 0.13, D3 = -1.5, D4 = 0.011 (epsdot_0 = 1/s): at constant
// triaxiality D = eps_p / eps_f, so the points fail at
// eps_f = [D1 + D2 exp(-1.5 sigma*)] [1 + D4 ln(epsdot_p / epsdot_0)], with the plastic
// strain rate they have then (the wall's 1000/s over the shrinking height).
// Within 5 % (measured: 0.3712 against 0.3719). After failing, a point carries no shear.
TEST(FeFailure, JohnsonCookDamageFailsUniaxialCompressionAtTheStrainOfItsTriaxiality) {
  const std::string text = R"(
[run]
end_time = 1.0
[materials.al2024]
density = 2.77e-3
E = 73100
nu = 0.33
strength = { model = "johnson-cook", A = 265, B = 426, n = 0.34, C = 0.015, reference_strain_rate = 1e-3 }
failure = { model = "johnson-cook", D1 = 0.13, D2 = 0.13, D3 = -1.5, D4 = 0.011, reference_strain_rate = 1e-3 }
[[bodies]]
name = "cube"
discretisation = "hexahedra"
material = "al2024"
shape = { box = { min = [0, 0, 0], max = [1, 1, 1] } }
mesh = { divisions = [2, 2, 2] }
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [1, 0, 0] } }
fixed = ["x"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 1, 0] } }
fixed = ["y"]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
fixed = ["z"]
[[walls]]
point = [0, 0, 1]
normal = [0, 0, -1]
velocity = [0, 0, -1]
)";
  const core::Scene scene = core::parse_scene(text, "compression.toml");
  FeSolver solver(scene);
  const HexElements& h = solver.hexahedra();
  double eps_at_failure = -1.0, triaxiality = 0.0, rate = 0.0, previous_eps = 0.0, previous_t = 0.0;
  while (solver.time() < 0.6 && eps_at_failure < 0.0) {
    const double before = h.plastic_strain[0];
    solver.step(solver.stable_time_step());
    if (h.damage[0] >= 1.0) {
      eps_at_failure = h.plastic_strain[0];
      break;
    }
    // The state of the step before it fails: triaxiality and plastic strain rate (per ms).
    const core::SymTensor& s = h.stress[0];
    const double p = core::pressure(s);
    triaxiality = -p / core::von_mises(s);
    rate = (h.plastic_strain[0] - before) / (solver.time() - previous_t);
    previous_eps = h.plastic_strain[0];
    previous_t = solver.time();
  }
  ASSERT_GT(eps_at_failure, 0.0) << "no failure by t = 0.6 ms";
  const double eps_f = (0.13 + 0.13 * std::exp(-1.5 * triaxiality)) *
                       (1.0 + 0.011 * std::log(std::max(rate / 1e-3, 1.0)));
  std::printf(
      "JC failure in compression: eps_p %.4f at failure (previous step %.4f), "
      "triaxiality %.4f, rate %.0f /s, eps_f %.4f (%+.2f %%)\n",
      eps_at_failure, previous_eps, triaxiality, rate * 1e3, eps_f,
      100.0 * (eps_at_failure / eps_f - 1.0));
  EXPECT_NEAR(triaxiality, -1.0 / 3.0, 0.02);
  EXPECT_NEAR(eps_at_failure, eps_f, 0.05 * eps_f);
  // Every point fails together (homogeneous); a step later none carries shear.
  solver.step(solver.stable_time_step());
  for (std::size_t e = 0; e < h.damage.size(); ++e) {
    EXPECT_GE(h.damage[e], 1.0) << "hexahedron " << e;
    EXPECT_LT(core::von_mises(h.stress[e]), 1e-9) << "hexahedron " << e;
  }
}

// Reference: the scene rules. A failure model on a truss material, both failure keys, and a
// failure model with Holmquist-Johnson-Cook (which has its own damage) are input errors that
// name the key and what is allowed.
TEST(FeFailure, FailureInputsTheModelsCannotCarryAreErrors) {
  auto error_of = [](const std::string& text) -> std::string {
    try {
      const core::Scene scene = core::parse_scene(text, "bad.toml");
      core::check_scene(scene);
    } catch (const core::InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string material =
      "[materials.steel]\ndensity = 7.85e-3\nE = 2e5\nnu = 0.3\n"
      "strength = { model = \"j2\", yield = 500 }\n";
  const std::string truss =
      "[run]\nend_time = 1.0\n" + material +
      "failure = { model = \"spall\", pressure = 1000 }\n"
      "[[bodies]]\nname = \"rod\"\ndiscretisation = \"trusses\"\nmaterial = \"steel\"\n"
      "area = 1.0\nshape = { line = { from = [0, 0, 0], to = [10, 0, 0] } }\nmesh = { size = 2.5 "
      "}\n";
  const std::string e1 = error_of(truss);
  EXPECT_NE(e1.find("bodies.rod.material"), std::string::npos) << e1;
  EXPECT_NE(e1.find("failure_strain"), std::string::npos) << e1;
  const std::string both =
      "[run]\nend_time = 1.0\n" + material +
      "failure_strain = 0.3\nfailure = { model = \"plastic-strain\", strain = 0.3 }\n";
  const std::string e2 = error_of(both);
  EXPECT_NE(e2.find("failure_strain"), std::string::npos) << e2;
  EXPECT_NE(e2.find("not both"), std::string::npos) << e2;
  const std::string unknown =
      "[run]\nend_time = 1.0\n" + material + "failure = { model = \"gurson\" }\n";
  const std::string e3 = error_of(unknown);
  EXPECT_NE(e3.find("materials.steel.failure.model"), std::string::npos) << e3;
  EXPECT_NE(e3.find("johnson-cook"), std::string::npos) << e3;
  const std::string negative =
      "[run]\nend_time = 1.0\n" + material +
      "failure = { model = \"johnson-cook\", D1 = -0.5, D2 = 0.2, D3 = -1 }\n";
  const std::string e4 = error_of(negative);
  EXPECT_NE(e4.find("D1 + D2"), std::string::npos) << e4;
}

}  // namespace
}  // namespace afemp::fem
