// Measures of a granular deposit's final free surface (a collapsed column, a slope's run-out),
// read from the positions of its points (Model::body_points), as the column-collapse experiment
// of Bui et al. 2008 reports it (examples/column_collapse). The deposit lies on a base through
// `origin` whose unit normal is `up` and spreads from there along the unit `along` (in the
// example: origin the foot of the back wall). For a point x, s = (x - origin).along is its
// distance along the base and h = (x - origin).up its height.
#pragma once

#include <span>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::analysis {

struct DepositProfile {
  double bin = 0.0;             // bin k holds the points with k bin <= s < (k + 1) bin
  std::vector<double> surface;  // each bin's free-surface height; NaN for a bin without points
  double tip = 0.0;             // the farthest point's s
};

// The surface of bin k is the top of its material column (analysis/material_column.hpp, gap
// `bin`: grains lying loose above it are not the surface) plus `skin`, how far the material
// reaches above its top point (half a particle spacing: particles sit inside the material).
// Points with s < 0 are left out.
DepositProfile deposit_profile(std::span<const Vec3> points, const Vec3& origin, const Vec3& along,
                               const Vec3& up, double bin, double skin);

// The surface height at s: linear between the centres of bins with points, the first bin's
// height before its centre; NaN beyond the last bin with points.
double surface_height(const DepositProfile& profile, double s);

// The run-out to a height: the s beyond which the surface stays below `level`, between the
// centres of the last bin at or above it and the next, linearly interpolated (a bin without
// points counts as height 0; past the last bin, its outer edge). 0 when no bin reaches `level`.
double runout_to_height(const DepositProfile& profile, double level);

}  // namespace afemp::analysis
