// Measures of a deposit's free surface (analysis/deposit_metrics.hpp).
#include "analysis/deposit_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/material_column.hpp"

namespace afemp::analysis {

DepositProfile deposit_profile(std::span<const Vec3> points, const Vec3& origin, const Vec3& along,
                               const Vec3& up, double bin, double skin) {
  std::vector<std::vector<double>> heights;
  DepositProfile p;
  p.bin = bin;
  for (const Vec3& x : points) {
    const double s = dot(x - origin, along);
    if (s < 0.0) continue;
    const auto k = static_cast<std::size_t>(s / bin);
    if (k >= heights.size()) heights.resize(k + 1);
    heights[k].push_back(dot(x - origin, up));
    p.tip = std::max(p.tip, s);
  }
  p.surface.assign(heights.size(), std::nan(""));
  for (std::size_t k = 0; k < heights.size(); ++k)
    if (!heights[k].empty()) p.surface[k] = material_column_top(heights[k], bin) + skin;
  return p;
}

double surface_height(const DepositProfile& profile, double s) {
  const std::vector<double>& h = profile.surface;
  const auto centre = [&](std::size_t k) { return (static_cast<double>(k) + 0.5) * profile.bin; };
  std::size_t below = h.size();  // the last bin with points whose centre is at or before s
  for (std::size_t k = 0; k < h.size() && centre(k) <= s; ++k)
    if (!std::isnan(h[k])) below = k;
  std::size_t above = h.size();  // the first bin with points whose centre is after s
  for (std::size_t k = 0; k < h.size() && above == h.size(); ++k)
    if (centre(k) > s && !std::isnan(h[k])) above = k;
  if (below == h.size()) return above == h.size() ? std::nan("") : h[above];
  if (above == h.size()) return centre(below) + 0.5 * profile.bin >= s ? h[below] : std::nan("");
  const double t = (s - centre(below)) / (centre(above) - centre(below));
  return h[below] + t * (h[above] - h[below]);
}

double runout_to_height(const DepositProfile& profile, double level) {
  const std::vector<double>& h = profile.surface;
  std::size_t k = h.size();
  while (k > 0 && !(h[k - 1] >= level)) --k;
  if (k == 0) return 0.0;
  const std::size_t last = k - 1;  // the last bin at or above level
  const double centre = (static_cast<double>(last) + 0.5) * profile.bin;
  if (last + 1 == h.size()) return centre + 0.5 * profile.bin;
  const double next = std::isnan(h[last + 1]) ? 0.0 : h[last + 1];
  return centre + (h[last] - level) / (h[last] - next) * profile.bin;
}

}  // namespace afemp::analysis
