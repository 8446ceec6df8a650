#pragma once
// The radial extent of a surface's points about a centre c: max_i |X_i - c| and min_i |X_i - c|.
// Chapter 3's Fig. 4 plots them minus the reference radius ("the maximum displacement from the
// center of mass minus the radius in the reference configuration"), c the centroid.
#include <vector>

namespace rbfib::surface {

struct RadialExtent {
  double min = 0, max = 0;
};

/// Over the points X (n x 3, column-major: X[d n + i]) about c.
RadialExtent radial_extent(const std::vector<double>& X, const double c[3]);

}  // namespace rbfib::surface
