// The top of a column of material from the heights of its points (analysis/crater_metrics.cpp,
// analysis/deposit_metrics.cpp): points thrown clear of the material (ejecta, grains flying
// above a deposit) are not its surface.
#pragma once

#include <algorithm>
#include <vector>

namespace afemp::analysis {

// The heights sorted, walked up from the lowest while successive heights are at most `gap`
// apart: the last one reached. `heights` must not be empty; it is left sorted.
inline double material_column_top(std::vector<double>& heights, double gap) {
  std::sort(heights.begin(), heights.end());
  double top = heights[0];
  for (std::size_t i = 1; i < heights.size() && heights[i] - heights[i - 1] <= gap; ++i)
    top = heights[i];
  return top;
}

}  // namespace afemp::analysis
