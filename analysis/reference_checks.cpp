#include "analysis/reference_checks.hpp"

#include <cmath>
#include <string>
#include <variant>

#include "analysis/taylor_metrics.hpp"

namespace afemp::analysis {

using core::BodyPoints;
using core::BodySums;
using core::CylinderShape;
using core::VelocityReference;

void check_references(const core::Model& model, const core::Scene& scene, RunSummary& sum) {
  if (scene.taylor_reference) {
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      const auto* bar = std::get_if<CylinderShape>(&scene.bodies[b].shape);
      if (bar == nullptr || bar->nose.crh > 0.0 || bar->top_radius >= 0.0) continue;
      const BodyPoints points = model.body_points(static_cast<int>(b));
      sum.taylor = measure_taylor(scene, static_cast<int>(b), points.position, points.half_size);
      sum.taylor_error = taylor_mean_error(*sum.taylor, *scene.taylor_reference);
      sum.checks.push_back({"taylor mean error (eq 2-42)", sum.taylor_error, 0.0, sum.taylor_error,
                            scene.taylor_reference->tolerance});
      break;
    }
  }
  for (const VelocityReference& v : scene.velocity_references) {
    const BodySums& body = sum.final.bodies[static_cast<std::size_t>(v.body)];
    const Vec3 mean = body.mass > 0.0 ? (1.0 / body.mass) * body.momentum : Vec3{};
    const double value = v.component < 0 ? norm(mean) : mean[v.component];
    static const char* components[] = {"x", "y", "z"};
    const std::string& name = scene.bodies[static_cast<std::size_t>(v.body)].name;
    sum.checks.push_back({"velocity of " + name + " (" +
                              (v.component < 0 ? "magnitude" : components[v.component]) + ")",
                          value, v.value, std::abs(value - v.value) / std::abs(v.value),
                          v.tolerance});
  }
  if (scene.energy_tolerance > 0.0)
    sum.checks.push_back({"largest |energy-balance error|", sum.max_energy_error, 0.0,
                          sum.max_energy_error, scene.energy_tolerance});
}

RunSummary run(core::Model& model, const core::Scene& scene, const core::RunOptions& options) {
  core::TimeLoop loop(model, scene, options);
  loop.run();
  RunSummary summary = loop.finish();
  check_references(model, scene, summary);
  return summary;
}

}  // namespace afemp::analysis
