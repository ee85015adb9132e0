// OFHC-like copper for shock tests: perfectly plastic (Y = 240 MPa) with the Mie-Grueneisen
// EOS of Ma 2005 (c0 3940 m/s, s 1.49, gamma0 1.96), units mm, ms, g, MPa, as a scene's
// [materials.copper] table (header only; not a test file itself).
#pragma once

namespace afemp::test {

inline constexpr const char* copper_shock_material = R"(
[materials.copper]
density = 8.93e-3
E = 124e3
nu = 0.35
strength = { model = "j2", yield = 240 }
eos = { model = "mie-gruneisen", c0 = 3940, s = 1.49, gamma0 = 1.96 }
)";

}  // namespace afemp::test
