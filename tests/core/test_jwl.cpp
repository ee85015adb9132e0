// The JWL equation of state and programmed burn (core/materials/jwl.cpp,
// core/programmed_burn.cpp). References: closed forms. The published parameter sets pass
// through their own Chapman-Jouguet state: on the Rayleigh line V_CJ = 1 - p_CJ / (rho0 D^2),
// with the Hugoniot energy E_CJ = E0 + p_CJ (1 - V_CJ) / 2, the JWL pressure is p_CJ (TNT of
// LS-DYNA's examples and of Dobratz & Crawford 1985, Composition B and PBX 9501 of Dobratz &
// Crawford 1985: within 0.05 %, the four digits the parameters are given to), and the isentrope
// through it is tangent to the Rayleigh line there (slope -rho0 D^2 within 0.1 %: each set's
// worst is -0.04 %, TNT of LS-DYNA's examples); the tangent bulk modulus is
// -V dp/dV (central difference, 1e-6); lighting times are distances over D; bad parameters are
// refused naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "afemp/errors.hpp"
#include "core/programmed_burn.hpp"
#include "core/scene.hpp"

namespace afemp::core {
namespace {

struct Explosive {
  const char* name;
  double rho0, D, pcj;
  Jwl eos;
};

// mm, ms, g: pressures in MPa, D in mm/ms (= m/s), E0 in MPa (MJ/m^3).
const Explosive kExplosives[] = {
    {"TNT (LS-DYNA examples)",
     1.63e-3,
     6930,
     2.1e4,
     {1.63e-3, 3.712e5, 3.231e3, 4.15, 0.95, 0.30, 7.0e3}},
    {"TNT (Dobratz & Crawford 1985)",
     1.63e-3,
     6930,
     2.1e4,
     {1.63e-3, 3.738e5, 3.747e3, 4.15, 0.90, 0.35, 6.0e3}},
    {"Composition B (Dobratz & Crawford 1985)",
     1.717e-3,
     7980,
     2.95e4,
     {1.717e-3, 5.242e5, 7.678e3, 4.2, 1.1, 0.34, 8.5e3}},
    {"PBX 9501 (Dobratz & Crawford 1985)",
     1.84e-3,
     8800,
     3.7e4,
     {1.84e-3, 8.524e5, 1.802e4, 4.6, 1.3, 0.38, 1.02e4}},
};

TEST(Jwl, PublishedSetsPassThroughTheirChapmanJouguetState) {
  for (const Explosive& x : kExplosives) {
    const double v_cj = 1.0 - x.pcj / (x.rho0 * x.D * x.D);
    const double e_cj = x.eos.E0 + 0.5 * x.pcj * (1.0 - v_cj);
    const double p = x.eos.pressure(v_cj, e_cj);
    EXPECT_NEAR(p, x.pcj, 5e-4 * x.pcj) << x.name;
    // form() is the same pressure, linear in the specific energy e = E / rho0.
    const EosLinearForm f = x.eos.form(1.0 / v_cj - 1.0);
    EXPECT_NEAR(f.a + f.b * e_cj / x.rho0, p, 1e-9 * p) << x.name;
    // The CJ point is where the Rayleigh line touches the products' isentrope: there
    // dp/dV along the isentrope (dE = -p dV) is the Rayleigh line's slope -rho0 D^2.
    const double h = 1e-6;
    const double dpdv =
        (x.eos.pressure(v_cj + h, e_cj) - x.eos.pressure(v_cj - h, e_cj)) / (2 * h) -
        x.eos.omega / v_cj * p;
    EXPECT_NEAR(dpdv, -x.rho0 * x.D * x.D, 1e-3 * x.rho0 * x.D * x.D) << x.name;
  }
}

TEST(Jwl, TangentBulkModulusIsMinusVdpdV) {
  const Jwl& eos = kExplosives[0].eos;
  for (const double V : {0.6, 0.73, 1.0, 2.0, 7.0}) {
    const double e = 4.0e6;  // per unit mass
    const double E = eos.rho0 * e;
    const double h = 1e-6 * V;
    const double dpdv = (eos.pressure(V + h, E) - eos.pressure(V - h, E)) / (2 * h);
    const double k = eos.tangent_bulk_modulus(1.0 / V - 1.0, e);
    EXPECT_NEAR(k, std::max(-V * dpdv, 0.0), 1e-6 * std::abs(V * dpdv)) << "V = " << V;
  }
}

TEST(ProgrammedBurn, PointsLightAtTheirDistanceOverD) {
  std::vector<DetonationSpec> d(3);
  d[0].point = {0, 0, 0};
  d[1].kind = DetonationSpec::Kind::plane;
  d[1].point = {0, 0, 10};
  d[1].normal = {0, 0, 1};
  d[1].time = 0.001;
  d[2].kind = DetonationSpec::Kind::line;
  d[2].point = {20, 0, 0};
  d[2].end = {20, 10, 0};
  const double D = 5000.0;
  EXPECT_DOUBLE_EQ(lighting_time({3, 4, 0}, std::span(d).first(1), D), 5.0 / D);
  EXPECT_DOUBLE_EQ(lighting_time({0, 0, 4}, std::span(d).subspan(1, 1), D), 0.001 + 6.0 / D);
  EXPECT_DOUBLE_EQ(lighting_time({23, 14, 0}, std::span(d).subspan(2, 1), D), 5.0 / D);
  EXPECT_DOUBLE_EQ(lighting_time({17, 5, 0}, std::span(d).subspan(2, 1), D), 3.0 / D);
  EXPECT_DOUBLE_EQ(lighting_time({19, 5, 0}, d, D), 1.0 / D);
  ProgrammedBurn b{5000.0, 2.0e4};
  const double rho0 = 1.6e-3, v_cj = b.cj_volume(rho0);
  // Unlit and uncompressed: nothing; 0.75 of the 1.5 lengths after lighting: half; compressed
  // half way to V_CJ: half; never more than 1, never less than before.
  EXPECT_EQ(burn_fraction(b, rho0, 0.0, 0.0, 1e-3, 1.0, 1.0), 0.0);
  EXPECT_NEAR(burn_fraction(b, rho0, 0.0, 1e-3 + 0.75 / b.detonation_velocity, 1e-3, 1.0, 1.0), 0.5,
              1e-12);
  EXPECT_NEAR(burn_fraction(b, rho0, 0.0, 0.0, 1e-3, 1.0, 0.5 * (1.0 + v_cj)), 0.5, 1e-12);
  EXPECT_EQ(burn_fraction(b, rho0, 0.0, 1.0, 1e-3, 1.0, 1.0), 1.0);
  EXPECT_EQ(burn_fraction(b, rho0, 0.7, 0.0, 1e-3, 1.0, 1.0), 0.7);
}

std::string charge(const std::string& eos, const std::string& more) {
  return R"([run]
end_time = 0.001
[grid]
cell = 1.0
min = [0, 0, 0]
max = [4, 4, 4]
[materials.tnt]
density = 1.63e-3
strength = { model = "fluid" }
eos = )" +
         eos + "\n" + more + R"(
[[bodies]]
name = "charge"
material = "tnt"
shape = { box = { min = [1, 1, 1], max = [3, 3, 3] } }
)";
}

std::string input_error(const std::string& text) {
  try {
    parse_scene(text, "charge.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(taken)";
}

constexpr const char* kTnt =
    R"({ model = "jwl", A = 3.712e5, B = 3.231e3, R1 = 4.15, R2 = 0.95, omega = 0.30, E0 = 7.0e3 })";

TEST(ProgrammedBurn, BadInputIsRefusedNamingTheKey) {
  const std::string burn = "burn = { D = 6930, pcj = 2.1e4 }";
  // A burn and no detonation to light it.
  EXPECT_NE(
      input_error(charge(kTnt, burn))
          .find("key 'detonations': body \"charge\" is a high explosive (its material has a burn) "
                "and the scene has no [[detonations]]"),
      std::string::npos)
      << input_error(charge(kTnt, burn));
  // A detonation and no explosive.
  EXPECT_NE(input_error(charge(kTnt, "") + "[[detonations]]\npoint = [0, 0, 0]\n")
                .find("no body is of a high explosive"),
            std::string::npos);
  // JWL parameters whose products pull at the reference volume (omega > R2 with a large B).
  const std::string pulling =
      R"({ model = "jwl", A = 1e3, B = 500, R1 = 4, R2 = 0.2, omega = 0.5, E0 = 0 })";
  EXPECT_NE(input_error(charge(pulling, "")).find("eos pressure at V = 1 and E = E0"),
            std::string::npos)
      << input_error(charge(pulling, ""));
  // A burn needs the JWL products; a fluid needs an EOS.
  EXPECT_NE(input_error(charge(R"({ model = "linear", bulk_modulus = 1e4 })", burn))
                .find("a burn (high explosive) needs eos = { model = \"jwl\""),
            std::string::npos);
  // A Chapman-Jouguet pressure above rho0 D^2 has no CJ volume.
  EXPECT_NE(input_error(charge(kTnt, "burn = { D = 6930, pcj = 9e4 }"))
                .find("burn V_CJ = 1 - pcj / (density D^2)"),
            std::string::npos);
}

}  // namespace
}  // namespace afemp::core
