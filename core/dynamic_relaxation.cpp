// Dynamic relaxation (core/dynamic_relaxation.hpp): damped steps and the kinetic-energy check.
#include "core/dynamic_relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "afemp/errors.hpp"

namespace afemp::core {

namespace {

void check_settings(const RelaxationSettings& s) {
  auto refuse = [](const char* name, const char* lsdyna, const char* allowed) {
    throw std::invalid_argument(std::string("dynamic relaxation: ") + name + " (" + lsdyna +
                                ") must be " + allowed);
  };
  if (!(s.tolerance > 0.0 && s.tolerance < 1.0)) refuse("tolerance", "DRTOL", "in (0, 1)");
  if (!(s.factor > 0.0 && s.factor <= 1.0)) refuse("factor", "DRFCTR", "in (0, 1]");
  if (s.check_every < 1) refuse("check_every", "NRCYCK", "at least 1");
  if (!(s.time_step_factor > 0.0 && std::isfinite(s.time_step_factor)))
    refuse("time_step_factor", "TSSFDR", "positive");
  if (!(s.end > 0.0)) refuse("end", "DRTERM", "positive");
}

}  // namespace

RelaxationResult relax(Model& model, const RelaxationSettings& s,
                       const std::function<void(const RelaxationCheck&)>& observer,
                       const std::function<void()>& after_step) {
  check_settings(s);
  RelaxationCheck check;
  while (true) {
    double dt = s.time_step_factor * model.stable_time_step();
    const bool last = dt >= s.end - check.time;
    if (last) dt = s.end - check.time;
    model.step(dt);
    const Energies before = model.energies();
    const double moving = before.kinetic;
    model.scale_velocities(s.factor);
    if (after_step) after_step();
    ++check.steps;
    check.time = last ? s.end : check.time + dt;
    check.kinetic = model.energies().kinetic;
    check.damped += moving - check.kinetic;
    check.recent = std::max(check.recent, check.kinetic);
    check.peak = std::max(check.peak, check.kinetic);
    if (check.steps % s.check_every != 0 && !last) continue;
    check.ratio = check.peak > 0.0 ? check.recent / check.peak : 0.0;
    if (observer) observer(check);
    if (check.ratio < s.tolerance) {
      model.scale_velocities(0.0);
      check.damped += check.kinetic - model.energies().kinetic;
      RelaxationResult r{check.steps, check.time, check.peak, check.ratio, check.damped, true, {}};
      for (const BodySums& b : before.bodies)
        r.damping_force.push_back((-(1.0 - s.factor) / dt) * b.momentum);
      return r;
    }
    if (last) {
      std::ostringstream why;
      why << "not converged by its end time " << s.end << " (DRTERM), after " << check.steps
          << " steps: the kinetic energy is " << check.ratio << " of its peak " << check.peak
          << " against the tolerance " << s.tolerance << " (DRTOL)";
      throw SimulationError(model.step_count(), model.time(), "dynamic relaxation",
                            "kinetic energy ratio", why.str());
    }
    check.recent = 0.0;
  }
}

}  // namespace afemp::core
