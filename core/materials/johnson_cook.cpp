// Johnson-Cook strength (Ma 2005, eq 2-20): sigma_y = (A + B eps^n)(1 + C ln(epsdot/epsdot_0))
// (1 - T*^m), returned radially with the consistency condition q_tr - 3G dp = sigma_y(eps_p + dp,
// dp/dt, T) solved by bracketed Newton (rtsafe, Press et al., Numerical Recipes §9.4).
#include <algorithm>
#include <cmath>
#include <limits>

#include "afemp/strength_models.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

namespace {

// Thermal factor 1 - T*^m, T* clamped to [0, 1] so a cold point does not harden and a
// molten one carries no deviatoric stress.
double thermal_factor(const JohnsonCook& jc, double temperature) {
  if (!jc.thermal()) return 1.0;
  const double t_star = std::clamp(
      (temperature - jc.room_temperature) / (jc.melt_temperature - jc.room_temperature), 0.0, 1.0);
  return 1.0 - std::pow(t_star, jc.m);
}

// Rate factor, cut off below the reference rate as LS-DYNA *MAT_015 does, so that the
// logarithm never lowers the quasi-static stress.
double rate_factor(const JohnsonCook& jc, double eps_rate) {
  return eps_rate > jc.reference_strain_rate
             ? 1.0 + jc.C * std::log(eps_rate / jc.reference_strain_rate)
             : 1.0;
}

}  // namespace

double JohnsonCook::flow_stress(double eps_p, double eps_rate, double temperature) const {
  const double hardening = A + B * std::pow(std::max(eps_p, 0.0), n);
  return hardening * rate_factor(*this, eps_rate) * thermal_factor(*this, temperature);
}

DeviatoricResult JohnsonCook::update(SymTensor& s, const SymTensor& de_dev,
                                     const StrengthContext& c) const {
  const double three_g = 3.0 * c.shear_modulus;
  const double eps0 = std::max(c.plastic_strain, 0.0);
  const double theta = thermal_factor(*this, c.temperature);  // T is frozen over the increment

  s += (2.0 * c.shear_modulus) * de_dev;
  const double q_trial = von_mises(s);
  // Elastic check at zero plastic rate: the rate factor is then 1.
  const double sigma_y0 = (A + B * std::pow(eps0, n)) * theta;
  if (q_trial <= sigma_y0) return {0.0, sigma_y0};

  // r(dp) = q_tr - 3G dp - sigma_y(dp) is strictly decreasing (A, B, C >= 0, theta in [0, 1]).
  // r(0) > 0, and at the perfectly plastic estimate r = sigma_y0 - sigma_y(dp) <= 0 because
  // sigma_y only grows with strain and rate, so [0, that estimate] brackets the root.
  double sigma_y = sigma_y0;
  double slope = 0.0;
  auto residual = [&](double dp) {
    const double eps = eps0 + dp;
    const double power = std::pow(eps, n);  // one pow a residual: eps^(n-1) = eps^n / eps
    const double h = A + B * power;
    double dh;
    if (eps > 0.0) {
      dh = B * n * power / eps;
    } else {
      // eps_p = 0 with n < 1: d(eps^n)/d eps is infinite; the Newton step then stays on
      // the bracket end and the loop bisects instead.
      dh = n < 1.0 ? std::numeric_limits<double>::infinity() : (n == 1.0 ? B : 0.0);
    }
    double rf = 1.0, drf = 0.0;
    const double rate = c.dt > 0.0 ? dp / c.dt : 0.0;
    if (rate > reference_strain_rate) {
      rf = 1.0 + C * std::log(rate / reference_strain_rate);
      drf = C / dp;
    }
    sigma_y = h * rf * theta;
    slope = -three_g - (dh * rf + h * drf) * theta;
    return q_trial - three_g * dp - sigma_y;
  };

  const double tolerance = 1e-12 * q_trial;
  double lo = 0.0;
  double hi = (q_trial - sigma_y0) / three_g;
  double dp = hi;
  double r = residual(dp);
  double last_step = hi - lo;
  for (int it = 0; it < 400 && std::abs(r) > tolerance; ++it) {
    if (r > 0.0) {
      lo = dp;
    } else {
      hi = dp;
    }
    // Newton unless it leaves the bracket, is not finite, or is less than half the last step
    // (the last guard keeps the steep start of n < 1 from crawling).
    const double newton = dp - r / slope;
    if (!(newton > lo && newton < hi) || std::abs(2.0 * r) > std::abs(last_step * slope)) {
      // Bisect in log(dp) while the bracket spans decades: with n << 1 the root can lie many
      // orders of magnitude below the perfectly plastic estimate.
      const double next =
          lo < 1e-3 * hi ? (lo > 0.0 ? std::sqrt(lo * hi) : 1e-3 * hi) : 0.5 * (lo + hi);
      last_step = std::abs(next - dp);
      dp = next;
    } else {
      last_step = std::abs(newton - dp);
      dp = newton;
    }
    r = residual(dp);
    if (hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * hi) break;
  }

  // Scale onto the yield surface at the converged dp so that the reported flow stress and
  // the returned von Mises stress agree to rounding; the min only guards a return that
  // ran out of iterations from ever growing the trial stress.
  sigma_y = std::min(sigma_y, q_trial);
  s *= sigma_y / q_trial;
  return {dp, sigma_y};
}

void JohnsonCook::parameters(ParameterVisitor& v) {
  v.required("A", A, Range::non_negative());
  v.required("B", B, Range::non_negative());
  v.required("n", n, Range::positive());
  v.optional("C", C, 0.0, Range::non_negative());
  v.optional("m", m, 0.0, Range::non_negative());
  v.optional("reference_strain_rate", reference_strain_rate, 1.0, Range::positive());
  v.optional("room_temperature", room_temperature, 293.0, Range::non_negative());
  if (m > 0.0) {
    // Thermal softening divides by (T_melt - T_room): it needs a melt temperature above room.
    v.require(v.has("melt_temperature"), "melt_temperature",
              "required when m > 0 (thermal softening); allowed: value > " +
                  format_value(room_temperature) + " (room_temperature)");
    v.required("melt_temperature", melt_temperature, Range::above(room_temperature));
  } else {
    v.optional("melt_temperature", melt_temperature, 0.0, Range::non_negative());
  }
}

}  // namespace afemp::core
