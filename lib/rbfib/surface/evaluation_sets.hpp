#pragma once
// Evaluation sites on the reference unit sphere for the forces of Chapter 3 (the JCP 2018 paper,
// Sec. 4.1): the sites with their area weights dA0 and their convex-hull triangulation (LDSM), and
// where the material point (lambda, theta) = (0, 0), the rightmost point of the stretched ellipsoid
// of eq. (88), lies among them (d_max of Fig. 5). Two families: Bauer spirals (dissertation eq.
// 5.1) with the RBF weights of eq. (2.22), and stored maximal-determinant-like sites with the
// nonnegative weights of eq. (45).
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace rbfib::surface {

/// Evaluation sites on the reference unit sphere with their area weights and their convex-hull
/// triangulation (LDSM), and where the material point (lambda, theta) = (0, 0) lies among them.
struct EvaluationSet {
  std::string family;  ///< "spiral" or "MD"
  SphereSites sites;
  std::vector<double> w;  ///< area weights dA0 on S^2 (sum 4 pi)
  double rcond = 0;       ///< of the eq. (2.22) system
  std::vector<Triangle> tris;
  std::vector<double> Z;       ///< unit-sphere points, n x 3 column-major (X[d n + i])
  double eq45_residual = NAN;  ///< MD: residual of the eq. (45) system
  index_t axis_site = -1;      ///< the site at (1, 0, 0), or -1
  /// Without such a site: the triangle whose flat reference contains the point where the ray of
  /// (1, 0, 0) meets it, and that point's barycentric weights (LDSM's piecewise-linear surface
  /// carries the material point (0, 0) there).
  Triangle axis_triangle{0, 0, 0};
  double axis_weights[3] = {0, 0, 0};
  double seconds = 0;  ///< time to build (weights and triangulation)
  index_t size() const { return sites.size(); }
};
/// A Bauer spiral (dissertation eq. 5.1) of n sites with the weights of dissertation eq. (2.22),
/// phi = r^3. An odd n puts site (n + 1)/2 exactly at (lambda, theta) = (0, 0), its axis_site; an
/// even n has no site on the x axis, and axis_site is its rightmost site (rightmost_site), where
/// the runs measure d_max. Throws InputError for n < 4.
EvaluationSet make_evaluation_set(index_t n);

/// The site with the largest x on the unit sphere. The ellipsoid of eq. (88) stretches the
/// sphere's x by a > 0, so this is the rightmost evaluation site at t = 0: the paper's d_max point
/// ("the point with largest x coordinate", Sec. 4.2).
index_t rightmost_site(const SphereSites& sites);

/// The stored maximal-determinant-like sites of degree N (reference/point_sets, n = (N+1)^2) with
/// the nonnegative weights of eq. (45) (the paper's choice); `file` is the path of the set.
/// Throws NumericalError if eq. (45) has no exact nonnegative solution on them.
EvaluationSet make_md_evaluation_set(const std::string& file, int N);


}  // namespace rbfib::surface
