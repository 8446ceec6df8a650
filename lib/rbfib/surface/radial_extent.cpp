#include "rbfib/surface/radial_extent.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::surface {

RadialExtent radial_extent(const std::vector<double>& X, const double c[3]) {
  const std::size_t n = X.size() / 3;
  RadialExtent e{INFINITY, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = X[i] - c[0], dy = X[n + i] - c[1], dz = X[2 * n + i] - c[2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    e.max = std::max(e.max, r);
    e.min = std::min(e.min, r);
  }
  return e;
}

}  // namespace rbfib::surface
