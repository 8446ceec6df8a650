#pragma once
// Material coordinates on the unit sphere S^2 and the sites the surface operators live on.
//
// Coordinates follow Chapter 3 (eq. 9): longitude lambda in (-pi, pi], latitude theta in
// [-pi/2, pi/2]; Chapter 2 calls the same pair (theta, phi). The unit-sphere map is
//   chi(lambda, theta) = (cos lambda cos theta, sin lambda cos theta, sin theta),
// with metric det G0 = cos^2 theta (zero at the poles, which evaluation sites must avoid).
// Angles in radians; the sphere is dimensionless (cell shapes carry the length unit, cm).
#include "rbfib/core/exec.hpp"

#include <cmath>
#include <vector>

namespace rbfib::surface {

/// A set of sites on S^2: site i is (lambda[i], theta[i]).
struct SphereSites {
  std::vector<double> lambda;
  std::vector<double> theta;
  index_t size() const { return static_cast<index_t>(lambda.size()); }
};

/// chi(lambda, theta) on the unit sphere, written to x[0..2].
inline void unit_sphere_point(double lambda, double theta, double* x) {
  x[0] = std::cos(lambda) * std::cos(theta);
  x[1] = std::sin(lambda) * std::cos(theta);
  x[2] = std::sin(theta);
}

/// The Cartesian points chi(site) of a site set, site-major (3 doubles per site).
std::vector<double> unit_sphere_points(const SphereSites& sites);

/// Throws InputError naming `what` and the pair if two sites coincide on S^2 (distance below
/// `tol`), or if a site is not finite.
void require_distinct(const SphereSites& sites, const char* what, double tol = 1e-12);

}  // namespace rbfib::surface
