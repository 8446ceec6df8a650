#include "rbfib/surface/cylinder.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::surface {

CylinderPoints cylinder_points(double R, double x0, double x1, double spacing) {
  require(R > 0, "cylinder radius", R, "must be > 0");
  require(spacing > 0, "cylinder point spacing", spacing, "must be > 0");
  require(x1 > x0, "cylinder length x1 - x0", x1 - x0, "must be > 0");
  CylinderPoints c;
  c.around = std::max(8, int(std::lround(2 * pi * R / spacing)));
  c.along = std::max(2, int(std::lround((x1 - x0) / spacing)));
  const index_t n = c.size();
  c.X.assign(static_cast<std::size_t>(3 * n), 0.0);
  for (int j = 0; j < c.along; ++j)
    for (int i = 0; i < c.around; ++i) {
      const index_t q = index_t(j) * c.around + i;
      const double phi = 2 * pi * (i + 0.5 * (j % 2)) / c.around;
      c.X[q] = x0 + (x1 - x0) * (j + 0.5) / c.along;
      c.X[n + q] = R * std::cos(phi);
      c.X[2 * n + q] = R * std::sin(phi);
    }
  return c;
}

std::vector<Triangle> cylinder_triangles(const CylinderPoints& c) {
  const index_t na = c.around;
  std::vector<Triangle> T;
  for (index_t j = 0; j + 1 < c.along; ++j)
    for (index_t i = 0; i < na; ++i) {
      const index_t a = j * na + i, b = j * na + (i + 1) % na, d = (j + 1) * na + i, e = (j + 1) * na + (i + 1) % na;
      T.push_back({a, b, d});
      T.push_back({b, e, d});
    }
  return T;
}

}  // namespace rbfib::surface
