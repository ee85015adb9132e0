// User strength models (include/afemp/user_material.hpp). Reference: a linear-hardening J2
// law written as a user model, keeping its own hardening variable as a history variable, must
// give the built-in J2 model's histories (Simo & Hughes 1998, box 3.2: the same radial return)
// to round-off, in particles (whose history is reordered with them), one-point and fully
// integrated hexahedra, and trusses (whose uniaxial secant search runs batched); its history
// variable must equal the solver's plastic strain. A model gets the pressure and temperature it
// declares it reads (the closed-form p = -tr(sigma) / 3 of a known state), and nothing else.
// Bad parameters and names get InputErrors naming the key and what is allowed.
#include <gtest/gtest.h>

#include <afemp/afemp.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/materials/uniaxial_update.hpp"
#include "core/scene.hpp"
#include "taylor_bar_scene.hpp"

namespace {

// sigma_y = yield_stress + hardening * alpha, alpha the model's own history variable.
void linear_j2(const afemp::StrengthBatch& b) {
  const double y0 = b.parameters[0], h = b.parameters[1], g = b.shear_modulus;
  for (std::size_t j = 0; j < b.count; ++j) {
    afemp::SymTensor s = b.deviator_at(j);
    const afemp::SymTensor de = b.strain_increment_at(j);
    double& alpha = b.history_at(j, 0);
    const double sigma_y = y0 + h * alpha;
    s += (2.0 * g) * de;
    const double q = afemp::von_mises(s);
    double dp = 0.0, flow = sigma_y;
    if (q > sigma_y) {
      dp = (q - sigma_y) / (3.0 * g + h);
      flow = sigma_y + h * dp;
      s *= flow / q;
    }
    alpha += dp;
    b.set_deviator(j, s);
    b.plastic_strain_increment[j] = dp;
    b.flow_stress[j] = flow;
  }
}

void register_once() {
  static const bool done = [] {
    afemp::UserStrengthDefinition d;
    d.name = "test-linear-j2";
    d.parameters = {"yield_stress", "hardening"};
    d.history_variables = {"alpha"};
    d.check = [](const std::vector<double>& p) {
      if (!(p[0] >= 0.0)) throw std::invalid_argument("yield_stress must be >= 0");
    };
    d.update = linear_j2;
    afemp::register_strength_model(d);
    return true;
  }();
  (void)done;
}

const char* kBuiltIn = R"(strength = { model = "j2", yield = 157, hardening = 425 })";
const char* kUser =
    R"(strength = { model = "test-linear-j2", yield_stress = 157, hardening = 425 })";

// The coarse Taylor bar of tests/taylor_bar_scene.hpp with either strength model.
std::string particles(const char* strength) {
  return afemp::test::taylor_bar_scene(false, strength);
}
std::string hexahedra(const char* strength, const char* element) {
  return afemp::test::taylor_bar_scene(true, strength, element);
}

// A steel bar of 40 trusses clamped at z = 0 and moving at 20 m/s along +z: the tension wave
// from the clamp (rho c v ~ 790 MPa) exceeds the yield stress.
std::string truss_bar(const std::string& strength) {
  return R"(
[run]
end_time = 0.02
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
)" + strength +
         R"(
[[bodies]]
name = "bar"
material = "steel"
discretisation = "trusses"
shape = { line = { from = [0, 0, 0], to = [0, 0, 100] } }
area = 4.0
mesh = { segments = 40 }
velocity = [0, 0, 20]
[[constraints]]
nodes = { plane = { point = [0, 0, 0], normal = [0, 0, 1] } }
fixed = ["x", "y", "z"]
)";
}

struct Trace {
  std::vector<double> kinetic, internal, plastic;
  std::vector<double> plastic_strain, history;  // per point at the end
};

Trace trace(const std::string& text) {
  afemp::Simulation sim(afemp::core::parse_scene(text, "user_material.toml"));
  Trace t;
  sim.on_step([&](afemp::Simulation& s) {
    const afemp::Energies e = s.energies();
    t.kinetic.push_back(e.kinetic);
    t.internal.push_back(e.internal);
    t.plastic.push_back(e.plastic);
  });
  sim.run();
  const afemp::ParticleFields p = sim.particles();
  const afemp::ElementFields h = sim.hexahedra(), tr = sim.trusses();
  const auto& eps = !p.position.empty() ? p.plastic_strain
                    : h.size() > 0      ? h.plastic_strain
                                        : tr.plastic_strain;
  const auto& his = !p.position.empty() ? p.history : h.size() > 0 ? h.history : tr.history;
  t.plastic_strain.assign(eps.begin(), eps.end());
  t.history.assign(his.begin(), his.end());
  return t;
}

void expect_same(const Trace& user, const Trace& built_in, const char* what) {
  ASSERT_EQ(user.kinetic.size(), built_in.kinetic.size());
  ASSERT_GT(user.kinetic.size(), 10u);
  double worst = 0.0;
  auto compare = [&](double a, double b, double scale) {
    const double d = std::abs(a - b) / scale;
    worst = std::max(worst, d);
    return d;
  };
  const double e0 = built_in.kinetic.front();
  for (std::size_t k = 0; k < user.kinetic.size(); ++k) {
    ASSERT_LE(compare(user.kinetic[k], built_in.kinetic[k], e0), 1e-12) << "step " << k + 1;
    ASSERT_LE(compare(user.internal[k], built_in.internal[k], e0), 1e-12) << "step " << k + 1;
    ASSERT_LE(compare(user.plastic[k], built_in.plastic[k], e0), 1e-12) << "step " << k + 1;
  }
  // The bar yields: plastic work is done (a model that never yields would not match anyway).
  EXPECT_GT(built_in.plastic.back(), 0.01 * e0);
  ASSERT_EQ(user.history.size(), user.plastic_strain.size()) << "one history variable per point";
  double max_eps = 0.0;
  for (std::size_t i = 0; i < user.plastic_strain.size(); ++i) {
    EXPECT_NEAR(user.history[i], user.plastic_strain[i], 1e-12) << "point " << i;
    EXPECT_LE(compare(user.plastic_strain[i], built_in.plastic_strain[i], 1.0), 1e-12);
    max_eps = std::max(max_eps, user.plastic_strain[i]);
  }
  EXPECT_GT(max_eps, 0.01);
  std::printf(
      "[%s] %zu steps, largest plastic strain %.4f, largest difference from built-in J2 "
      "%.3g (energies relative to the initial kinetic energy; tolerance 1e-12)\n",
      what, user.kinetic.size(), max_eps, worst);
}

}  // namespace

TEST(UserMaterial, LinearJ2GivesBuiltInJ2TaylorHistoriesInParticles) {
  register_once();
  expect_same(trace(particles(kUser)), trace(particles(kBuiltIn)), "particles");
}

TEST(UserMaterial, LinearJ2GivesBuiltInJ2TaylorHistoriesInOnePointHexahedra) {
  register_once();
  expect_same(trace(hexahedra(kUser, "one-point")), trace(hexahedra(kBuiltIn, "one-point")),
              "one-point hexahedra");
}

TEST(UserMaterial, LinearJ2GivesBuiltInJ2TaylorHistoriesInFullyIntegratedHexahedra) {
  register_once();
  expect_same(trace(hexahedra(kUser, "full")), trace(hexahedra(kBuiltIn, "full")),
              "fully integrated hexahedra");
}

TEST(UserMaterial, LinearJ2GivesBuiltInJ2HistoriesInTrusses) {
  register_once();
  expect_same(trace(truss_bar(kUser)), trace(truss_bar(kBuiltIn)), "trusses");
}

TEST(UserMaterial, SceneFileErrorsNameTheKeyAndWhatIsAllowed) {
  register_once();
  auto message = [](const std::string& strength) {
    try {
      afemp::core::parse_scene(afemp::test::taylor_bar_scene(false, strength), "bad.toml");
    } catch (const afemp::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string unknown = message(
      R"(strength = { model = "test-linear-j2", yield_stress = 157, hardening = 425, n = 1 })");
  EXPECT_NE(unknown.find("bad.toml:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("n"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("yield_stress"), std::string::npos)
      << "lists the allowed keys: " << unknown;
  const std::string missing =
      message(R"(strength = { model = "test-linear-j2", yield_stress = 157 })");
  EXPECT_NE(missing.find("hardening"), std::string::npos) << missing;
  const std::string rejected =
      message(R"(strength = { model = "test-linear-j2", yield_stress = -1, hardening = 425 })");
  EXPECT_NE(rejected.find("yield_stress must be >= 0"), std::string::npos) << rejected;
  const std::string model = message(R"(strength = { model = "test-linear-j3" })");
  EXPECT_NE(model.find("test-linear-j2"), std::string::npos) << "lists the models: " << model;
  EXPECT_NE(model.find("johnson-cook"), std::string::npos) << model;
}

TEST(UserMaterial, RegistrationAndCodeBuiltMaterialsAreChecked) {
  register_once();
  afemp::UserStrengthDefinition clash;
  clash.name = "j2";
  clash.update = linear_j2;
  EXPECT_THROW(afemp::register_strength_model(clash), afemp::InputError);
  afemp::UserStrengthDefinition twice;
  twice.name = "test-linear-j2";
  twice.update = linear_j2;
  EXPECT_THROW(afemp::register_strength_model(twice), afemp::InputError);
  afemp::UserStrengthDefinition no_update;
  no_update.name = "test-no-update";
  EXPECT_THROW(afemp::register_strength_model(no_update), afemp::InputError);
  EXPECT_THROW(afemp::user_strength("test-linear-j2", {{"yield_stress", 1.0}}), afemp::InputError);
  EXPECT_THROW(afemp::user_strength("test-linear-j2",
                                    {{"yield_stress", 1.0}, {"hardening", 2.0}, {"n", 1.0}}),
               afemp::InputError);
  const afemp::UserStrength u =
      afemp::user_strength("test-linear-j2", {{"hardening", 425.0}, {"yield_stress", 157.0}});
  ASSERT_EQ(u.parameters.size(), 2u);
  EXPECT_EQ(u.parameters[0], 157.0) << "values in the model's declared order";
  EXPECT_EQ(u.parameters[1], 425.0);
  // A Material built in code with a rejected value: the same check, naming the material.
  afemp::Scene s = afemp::core::parse_scene(particles(kBuiltIn), "taylor.toml");
  s.materials[0].strength =
      afemp::user_strength("test-linear-j2", {{"yield_stress", -5.0}, {"hardening", 425.0}});
  try {
    afemp::Simulation sim(s);
    ADD_FAILURE() << "a negative yield stress was accepted";
  } catch (const afemp::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("copper"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("yield_stress must be >= 0"), std::string::npos)
        << e.what();
  }
}

// What a model declares it reads is what it gets: on a bar point under uniaxial stress
// sigma_xx = -3 p0 at temperature T0, StrengthBatch::pressure holds p0 (p = -tr(sigma) / 3) and
// temperature T0 when declared, and both are null when not; the density is the end-of-increment
// one, rho0 / (1 + d_axial (1 - 2 nu)) (Ma 2005, eq 2-40), since an elastic bar takes the
// lateral strain -nu d_axial at its first and only trial.
TEST(UserMaterial, BatchCarriesPressureAndTemperatureOnlyWhenDeclared) {
  struct Seen {
    const double* pressure = nullptr;
    const double* temperature = nullptr;
    double p = 0.0, t = 0.0, rho = 0.0;
  };
  static Seen seen;
  auto record = [](const afemp::StrengthBatch& b) {
    seen = {b.pressure, b.temperature, b.pressure ? b.pressure[0] : 0.0,
            b.temperature ? b.temperature[0] : 0.0, b.density[0]};
    for (std::size_t j = 0; j < b.count; ++j) {
      afemp::SymTensor s = b.deviator_at(j);
      s += (2.0 * b.shear_modulus) * b.strain_increment_at(j);
      b.set_deviator(j, s);
    }
  };
  for (const bool declared : {true, false}) {
    afemp::UserStrengthDefinition d;
    d.name = declared ? "test-reads-both" : "test-reads-none";
    d.reads_pressure = declared;
    d.reads_temperature = declared;
    d.update = record;
    afemp::register_strength_model(d);
    afemp::core::Material m;
    m.name = "steel";
    m.density = 7.85e-3;
    m.youngs_modulus = 200e3;
    m.poisson_ratio = 0.3;
    m.strength = afemp::user_strength(d.name, {});
    afemp::core::PointState point;
    const double p0 = 150.0, t0 = 400.0;
    point.stress = {-3.0 * p0, 0.0, 0.0, 0.0, 0.0, 0.0};
    point.temperature = t0;
    point.density = m.density;
    const afemp::core::UniaxialUpdate u = afemp::core::uniaxial_update(m, point, 1e-4, 1e-3);
    EXPECT_EQ(u.trials, 1);
    if (declared) {
      ASSERT_NE(seen.pressure, nullptr);
      ASSERT_NE(seen.temperature, nullptr);
      EXPECT_NEAR(seen.p, p0, 1e-12 * p0);
      EXPECT_EQ(seen.t, t0);
    } else {
      EXPECT_EQ(seen.pressure, nullptr);
      EXPECT_EQ(seen.temperature, nullptr);
    }
    const double d_vol = 1e-4 * (1.0 - 2.0 * m.poisson_ratio);
    EXPECT_NEAR(seen.rho, m.density / (1.0 + d_vol), 1e-12 * m.density);
  }
}
