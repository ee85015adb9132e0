// The run summary's warnings (core/run_warnings.hpp).
#include "core/run_warnings.hpp"

#include <cmath>
#include <cstdio>

#include "core/state_archive.hpp"

namespace afemp::core {

namespace {

constexpr double kHourglassShare = 0.1;  // of the internal energy
constexpr double kEnergyError = 0.05;    // of the energy the run handled (energy_balance_error)
// Past this error a model that books some mechanism in no column of total() names them.
constexpr double kUnbooked = 0.01;
constexpr double kStepFall = 10.0;  // the first stable step over the smallest
constexpr double kLostMass = 1e-6;  // of the initial mass: past round-off

double total_mass(const Energies& e) {
  double m = 0.0;
  for (const BodySums& b : e.bodies) m += b.mass;
  return m;
}

}  // namespace

void RunWarnings::row(double time, const Energies& e, double error) {
  // As fe_model.cpp's warning: only once the hourglass energy matters at all, not the
  // round-off of the first steps.
  if (e.internal > 0.0 && e.hourglass > 1e-3 * (e.kinetic + e.internal + e.hourglass) &&
      e.hourglass / e.internal > hourglass_peak_) {
    hourglass_peak_ = e.hourglass / e.internal;
    hourglass_peak_energy_ = e.hourglass;
    hourglass_peak_internal_ = e.internal;
    hourglass_time_ = time;
  }
  if (std::abs(error) > std::abs(error_peak_)) {
    error_peak_ = error;
    error_time_ = time;
  }
}

void RunWarnings::new_low(double step, double time, const Model& model) {
  low_ = step;
  low_time_ = time;
  if (step * kStepFall < first_step_ && step < 0.99 * setter_step_) {
    setter_ = model.time_step_setter();
    setter_step_ = step;
    setter_time_ = time;
  }
}

std::vector<std::string> RunWarnings::summary(const Model& model, const Energies& initial,
                                              const Energies& final, double final_error) const {
  std::vector<std::string> out;
  char buf[600];
  if (hourglass_peak_ > kHourglassShare) {
    std::snprintf(buf, sizeof buf,
                  "the hourglass energy reached %.1f %% of the internal energy (%.4g of %.4g) "
                  "at t = %.6g (largest share over the history rows; %.1f %% at the end): the "
                  "one-point elements deform in modes that carry no strain; refine the mesh, "
                  "use the stiffness or assumed_strain hourglass form, or element = \"full\"",
                  100.0 * hourglass_peak_, hourglass_peak_energy_, hourglass_peak_internal_,
                  hourglass_time_,
                  final.internal > 0.0 ? 100.0 * final.hourglass / final.internal : 0.0);
    out.emplace_back(buf);
  }
  if (std::abs(error_peak_) > kEnergyError) {
    std::snprintf(buf, sizeof buf,
                  "the energy-balance error reached %+.1f %% at t = %.6g (%+.1f %% at the end): "
                  "energy was made or lost beyond any account in history.csv; a smaller time "
                  "step factor, or the energy columns and the contacts, say where",
                  100.0 * error_peak_, error_time_, 100.0 * final_error);
    out.emplace_back(buf);
  }
  if (std::max(std::abs(error_peak_), std::abs(final_error)) > kUnbooked) {
    const std::vector<std::string> unbooked = model.unbooked_energies();
    if (!unbooked.empty()) {
      std::snprintf(buf, sizeof buf,
                    "the energy balance ended at %+.2f %% (largest %+.2f %%), and this scene has "
                    "mechanisms whose energy no column of total books: ",
                    100.0 * final_error, 100.0 * error_peak_);
      std::string w = buf;
      for (std::size_t k = 0; k < unbooked.size(); ++k) w += (k ? "; " : "") + unbooked[k];
      if (final.contact > 0.0 && initial.total() > 0.0) {
        std::snprintf(buf, sizeof buf, " (the contact column's estimate: %.4g, %.2f %% of E0)",
                      final.contact, 100.0 * final.contact / initial.total());
        w += buf;
      }
      out.push_back(std::move(w));
    }
  }
  if (low_ * kStepFall < first_step_) {
    std::snprintf(buf, sizeof buf,
                  "the stable time step fell %.3g-fold, from %.4g at the start to %.4g at t = "
                  "%.6g; the steps to the end, and the wall time, grew with it",
                  first_step_ / low_, first_step_, low_, low_time_);
    std::string w = buf;
    if (!setter_.empty()) {
      // The model was last asked within 1 % of the smallest step (new_low): say when.
      std::snprintf(buf, sizeof buf, "; at t = %.6g, at a stable step of %.4g,", setter_time_,
                    setter_step_);
      w += (setter_step_ == low_ ? std::string(";") : std::string(buf)) + " it was set by " +
           setter_;
    }
    out.push_back(std::move(w));
  }
  for (std::string& w : model.summary_warnings()) out.push_back(std::move(w));
  const double m0 = total_mass(initial);
  const double lost = m0 - total_mass(final);
  if (m0 > 0.0 && lost > kLostMass * m0) {
    std::snprintf(buf, sizeof buf, "%.3g %% of the initial mass left the model (%.6g of %.6g)",
                  100.0 * lost / m0, lost, m0);
    std::string w = buf;
    const double eroded = lost - final.outflow_mass;
    if (final.outflow_mass > kLostMass * m0) {
      std::snprintf(buf, sizeof buf, "; %.6g through the grid's outflow faces", final.outflow_mass);
      w += buf;
    }
    if (eroded > kLostMass * m0) {
      std::snprintf(buf, sizeof buf, "; %.6g with eroded elements", eroded);
      w += buf;
    }
    out.push_back(std::move(w));
  }
  return out;
}

void RunWarnings::state(StateArchive& a) {
  const StateArchive::Group group(a, "warnings");
  a.item("first_step", first_step_);
  a.item("hourglass_peak", hourglass_peak_);
  a.item("hourglass_energy", hourglass_peak_energy_);
  a.item("hourglass_internal", hourglass_peak_internal_);
  a.item("hourglass_time", hourglass_time_);
  a.item("error_peak", error_peak_);
  a.item("error_time", error_time_);
  a.item("low", low_);
  a.item("low_time", low_time_);
  a.item("setter_step", setter_step_);
  a.item("setter_time", setter_time_);
  a.item("setter", setter_);
}

}  // namespace afemp::core
