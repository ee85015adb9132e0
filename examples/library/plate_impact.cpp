// A steel sphere of particles (MPM) strikes an aluminium plate of hexahedra (FE) that this
// program meshes itself, built with the afemp library and no scene file. The plate's strength
// model is the program's own: a user material (Ludwik power-law hardening), registered with
// afemp and run by the solvers on batches of points, in the plate's elements and in the
// particles they become. The plate meets the
// sphere through grid contact (contact-coupled FE-MPM); nothing holds either body, so the
// total momentum must stay what it was (elements that distort become particles and keep theirs),
// and the sphere must come out slower than the plug-sharing bound of Recht & Ipson.
// Units: mm, ms, g, N, MPa (velocity in m/s). docs/library.md walks through it.
#include <afemp/afemp.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <vector>

namespace {

// Ludwik hardening sigma_y = A + B alpha^n with radial return: the consistency condition
// f(dp) = q_trial - 3 G dp - A - B (alpha + dp)^n = 0 has its root between 0 (f > 0) and the
// perfectly plastic step (q_trial - sigma_y) / 3G (f <= 0); Newton steps that leave that
// bracket are replaced by bisection. alpha, the accumulated plastic strain, is the model's
// history variable.
void ludwik(const afemp::StrengthBatch& b) {
  const double A = b.parameters[0], B = b.parameters[1], n = b.parameters[2];
  const double g = b.shear_modulus;
  for (std::size_t j = 0; j < b.count; ++j) {
    afemp::SymTensor s = b.deviator_at(j);
    const afemp::SymTensor de = b.strain_increment_at(j);
    double& alpha = b.history_at(j, 0);
    const double sigma_y = A + B * std::pow(alpha, n);
    s += (2.0 * g) * de;
    const double q = afemp::von_mises(s);
    double dp = 0.0, flow = sigma_y;
    if (q > sigma_y) {
      double lo = 0.0, hi = (q - sigma_y) / (3.0 * g);
      dp = hi;
      for (int it = 0; it < 100; ++it) {
        const double f = q - 3.0 * g * dp - A - B * std::pow(alpha + dp, n);
        if (std::abs(f) <= 1e-12 * q) break;
        (f > 0.0 ? lo : hi) = dp;
        double next = dp - f / (-3.0 * g - n * B * std::pow(alpha + dp, n - 1.0));
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        dp = next;
      }
      flow = q - 3.0 * g * dp;
      s *= flow / q;
    }
    alpha += dp;
    b.set_deviator(j, s);
    b.plastic_strain_increment[j] = dp;
    b.flow_stress[j] = flow;
  }
}

// The program's own mesh: an n x n x m block of unit-aspect hexahedra, corner `min`, edge h.
afemp::MeshArrays plate_mesh(afemp::Vec3 min, int n, int m, double h) {
  afemp::MeshArrays mesh;
  auto node = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= m; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        mesh.nodes.push_back({min.x + i * h, min.y + j * h, min.z + k * h});
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        mesh.hexahedra.push_back({node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                                  node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                                  node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)});
  return mesh;
}

}  // namespace

int main() try {
  // The program's strength model, under the name a Material (or a scene file) gives it.
  afemp::UserStrengthDefinition model;
  model.name = "ludwik";
  model.parameters = {"A", "B", "n"};
  model.history_variables = {"alpha"};
  model.check = [](const std::vector<double>& p) {
    if (!(p[0] > 0.0 && p[1] >= 0.0 && p[2] > 0.0 && p[2] <= 1.0))
      throw std::invalid_argument("need A > 0, B >= 0 and 0 < n <= 1");
  };
  model.update = ludwik;
  afemp::register_strength_model(model);

  const double v0 = 800.0;  // striking velocity, m/s
  afemp::Scene scene;
  scene.run.title = "steel sphere through an aluminium plate (library example)";
  scene.run.end_time = 0.03;

  scene.has_grid = true;
  scene.mpm.grid.cell = 0.5;
  scene.mpm.grid.min = {-10, -10, -28};
  scene.mpm.grid.max = {10, 10, 6};

  afemp::Material steel;
  steel.name = "steel";
  steel.density = 7.85e-3;
  steel.youngs_modulus = 200e3;
  steel.poisson_ratio = 0.29;
  steel.strength = afemp::JohnsonCook{.A = 792, .B = 510, .n = 0.26};
  afemp::Material aluminium;
  aluminium.name = "aluminium";
  aluminium.density = 2.70e-3;
  aluminium.youngs_modulus = 69e3;
  aluminium.poisson_ratio = 0.33;
  aluminium.strength = afemp::user_strength("ludwik", {{"A", 324}, {"B", 114}, {"n", 0.42}});
  scene.materials = {steel, aluminium};

  afemp::BodySpec sphere;
  sphere.name = "sphere";
  sphere.material = 0;
  sphere.shape = afemp::SphereShape{.centre = {0, 0, 2.5}, .radius = 2.0};
  sphere.velocity = {0, 0, -v0};
  afemp::BodySpec plate;
  plate.name = "plate";
  plate.material = 1;
  plate.discretisation = afemp::Discretisation::hexahedra;
  plate.shape = afemp::MeshFileShape{.arrays = plate_mesh({-8, -8, -2}, 32, 4, 0.5)};
  plate.hourglass = {afemp::HourglassForm::assumed_strain, 1.0};
  // Elements that strain plastically past 0.5 become particles (AFEMP), which keep their mass
  // and momentum and meet the sphere through the same grid contact.
  plate.conversion = afemp::ConversionSettings{.plastic_strain = 0.5};
  scene.bodies = {sphere, plate};

  afemp::ContactSpec contact;
  contact.bodies = {0, 1};
  scene.contacts = {contact};

  {
    afemp::Simulation sim(scene);
    const afemp::Energies start = sim.energies();
    const afemp::Vec3 p0 = start.bodies[0].momentum + start.bodies[1].momentum;
    const double scale = std::abs(start.bodies[0].momentum.z);
    double worst_momentum = 0.0, next_print = 0.0;
    // After every step: the momentum balance, and the sphere's velocity each 0.01 ms.
    sim.on_step([&](afemp::Simulation& s) {
      const afemp::Energies e = s.energies();
      const afemp::Vec3 p = e.bodies[0].momentum + e.bodies[1].momentum;
      worst_momentum = std::max(worst_momentum, afemp::norm(p - p0) / scale);
      if (s.time() >= next_print * (1.0 - 1e-9)) {
        std::printf("t = %.3f ms  sphere v_z = %8.2f m/s  plate v_z = %8.2f m/s\n", s.time(),
                    e.bodies[0].momentum.z / e.bodies[0].mass,
                    e.bodies[1].momentum.z / e.bodies[1].mass);
        next_print += 0.01;
      }
    });
    const afemp::RunSummary summary = sim.run();
    const afemp::BodySums& ball = summary.final.bodies[0];
    const double residual = -ball.momentum.z / ball.mass;
    std::printf("steps %ld, wall %.2f s, energy-balance error %+.3f %%\n", summary.steps,
                summary.wall_seconds, 100.0 * summary.energy_error);
    std::printf("largest momentum error %.2e (of the sphere's initial momentum)\n", worst_momentum);
    std::printf("residual velocity %.1f m/s (%.3f v0)\n", residual, residual / v0);
    // The band: below the bound of Recht & Ipson (1963) for a ballistic limit of zero, where
    // the sphere shares its momentum with a plug of its own diameter pushed out of the plate
    // (v0 m / (m + m_plug) = 0.795 v0), and above half of v0 (a ballistic limit below 0.87 v0).
    const double plug = aluminium.density * 3.14159265358979 * 2.0 * 2.0 * 2.0;
    const double sphere_mass = ball.mass;
    const double upper = v0 * sphere_mass / (sphere_mass + plug);
    const bool momentum_ok = worst_momentum < 1e-10;
    const bool residual_ok = residual > 0.5 * v0 && residual < upper;
    // The model's history variable alpha accumulates the same increments as the solver's
    // plastic strain, in the plate's elements and in the particles converted from them.
    double alpha_max = 0.0, history_gap = 0.0;
    std::size_t converted = 0;
    const afemp::ElementFields hexes = sim.hexahedra();
    for (std::size_t p = 0; p < hexes.plastic_strain.size(); ++p) {
      alpha_max = std::max(alpha_max, hexes.history[p * hexes.history_count]);
      history_gap = std::max(
          history_gap, std::abs(hexes.history[p * hexes.history_count] - hexes.plastic_strain[p]));
    }
    const afemp::ParticleFields particles = sim.particles();
    for (std::size_t i = 0; i < particles.size(); ++i) {
      if (particles.body[i] != 1) continue;
      ++converted;
      const double alpha = particles.history[i * particles.history_count];
      alpha_max = std::max(alpha_max, alpha);
      history_gap = std::max(history_gap, std::abs(alpha - particles.plastic_strain[i]));
    }
    const bool history_ok = alpha_max > 0.5 && history_gap < 1e-12;
    std::printf(
        "plate: %zu particles from converted elements, largest alpha %.3f, largest "
        "|alpha - plastic strain| %.1e\n",
        converted, alpha_max, history_gap);
    std::printf(
        "momentum conserved to 1e-10: %s; residual velocity in (%.0f, %.0f) m/s: %s; "
        "user history carried: %s\n",
        momentum_ok ? "yes" : "NO", 0.5 * v0, upper, residual_ok ? "yes" : "NO",
        history_ok ? "yes" : "NO");
    return momentum_ok && residual_ok && history_ok ? 0 : 1;
  }
} catch (const afemp::InputError& e) {
  std::fprintf(stderr, "input error: %s\n", e.what());
  return 2;
} catch (const afemp::SimulationError& e) {
  std::fprintf(stderr, "simulation stopped: %s\n", e.what());
  return 2;
}
