#pragma once
// Closed-form test surfaces of the paper's Sec. 4.1 with exact jets (X and its first and second
// derivatives in (lambda, theta)), coordinates as in sphere.hpp.
//
//   ellipsoid (eq. 88):            X = (a cos l cos t, b sin l cos t, c sin t)
//   perturbed ellipsoid (eq. 89):  X = Vf (a (1 + B/5 e) cos l cos t, b (1 + B e) sin l cos t,
//                                          c (1 + B e) sin t),   e = exp(-sin t)
// Vf is chosen so that the enclosed volume equals that of the unit sphere (4 pi / 3).
#include "rbfib/surface/geometry_kernels.hpp"
#include "rbfib/surface/sphere.hpp"

#include <vector>

namespace rbfib::surface {

struct PerturbedEllipsoid {
  double a = 0.1, b = 0.2, c = 0.2, B = 0.25, Vf = 1.0;  ///< B = 0 gives the ellipsoid (eq. 88)
  Jet jet(double lambda, double theta) const;
  std::vector<Jet> jets(const SphereSites& s) const;
  std::vector<double> points(const SphereSites& s) const;  ///< X only, n x 3 column-major (X[d n + i])
  /// Enclosed volume (1/3) int X . (X_l x X_t) dl dt by Gauss-Legendre x trapezoid quadrature.
  double volume() const;
};

inline PerturbedEllipsoid ellipsoid(double a, double b, double c) { return PerturbedEllipsoid{a, b, c, 0.0, 1.0}; }

/// The paper's perturbed ellipsoid (a = 0.1, b = c = 0.2, B = 0.25) with Vf set to give the unit
/// sphere's volume (the paper quotes Vf ~ 5.14).
PerturbedEllipsoid paper_perturbed_ellipsoid();

/// Mean curvature of the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 at (x, y, z), sign as
/// point_geometry (negative with the outward normal):
///   H = -(a^2 + b^2 + c^2 - |x|^2) / (2 a^2 b^2 c^2 h^3),  K = 1/(a^2 b^2 c^2 h^4),
///   h^2 = x^2/a^4 + y^2/b^4 + z^2/c^4.
void ellipsoid_curvatures(double a, double b, double c, const double* x, double& H, double& K);

}  // namespace rbfib::surface
