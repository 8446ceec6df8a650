#include "rbfib/surface/sphere.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib::surface {

std::vector<double> unit_sphere_points(const SphereSites& sites) {
  std::vector<double> p(static_cast<std::size_t>(3 * sites.size()));
  for (index_t i = 0; i < sites.size(); ++i) unit_sphere_point(sites.lambda[i], sites.theta[i], &p[3 * i]);
  return p;
}

void require_distinct(const SphereSites& sites, const char* what, double tol) {
  require(sites.lambda.size() == sites.theta.size(), std::string(what) + ".lambda.size()",
          sites.lambda.size(), "must equal theta.size() = " + to_text(sites.theta.size()));
  for (index_t i = 0; i < sites.size(); ++i)
    require(std::isfinite(sites.lambda[i]) && std::isfinite(sites.theta[i]),
            std::string(what) + "[" + to_text(i) + "]", to_text(sites.lambda[i]) + ", " + to_text(sites.theta[i]),
            "site angles must be finite");
  const std::vector<double> p = unit_sphere_points(sites);
  for (index_t i = 0; i < sites.size(); ++i)
    for (index_t j = i + 1; j < sites.size(); ++j) {
      const double dx = p[3 * i] - p[3 * j], dy = p[3 * i + 1] - p[3 * j + 1], dz = p[3 * i + 2] - p[3 * j + 2];
      if (dx * dx + dy * dy + dz * dz <= tol * tol)
        throw InputError(std::string(what), "sites " + to_text(i) + " and " + to_text(j),
                         "coincide on the sphere (distance <= " + to_text(tol) + "): the interpolation matrix is singular");
    }
}

}  // namespace rbfib::surface
