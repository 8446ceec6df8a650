#pragma once
// Triangulation of sites on the unit sphere for the LDSM comparison (paper Sec. 2.5): the convex
// hull of chi(site), which for points on a sphere is their spherical Delaunay triangulation.
// Triangles are vertex-index triples ordered counter-clockwise seen from outside (outward
// normal (X2 - X1) x (X3 - X1)). A closed triangulation of n points has 2n - 4 triangles.
#include "rbfib/surface/sphere.hpp"

#include <array>
#include <vector>

namespace rbfib::surface {

using Triangle = std::array<index_t, 3>;

/// The convex hull of points p (x y z per point, p[3 i + d]), incremental, O(n^2): its outward
/// triangles; points inside it (or on it within rounding: 1e-13 length^3 in the orientation test,
/// length the largest |coordinate| unless given) are no vertex of any. Throws InputError for fewer
/// than 4 points, NumericalError when they are coplanar.
std::vector<Triangle> convex_hull(const std::vector<double>& p, double length = 0);

/// The convex hull of the sites on the unit sphere. Throws InputError for coincident sites or fewer
/// than 4, NumericalError if the hull is not a closed triangulation of every site.
std::vector<Triangle> sphere_triangulation(const SphereSites& sites);

/// Mean curvature of a closed triangulated surface X (n x 3) at its vertices from its edges (the
/// discrete curvature the paper's Sec. 5.2.2 uses for LDSM, after its refs. [12, 54]): |H_i| =
/// sum over the edges at i of theta_e |e| / (4 A_i), theta_e the angle between the normals of the
/// two triangles at e and A_i a third of the area of the triangles at i (so sum_i |H_i| A_i is the
/// surface's integrated mean curvature (1/2) sum_e theta_e |e|; 1/r on a sphere). Unsigned, as the
/// paper says ("curvatures that are always positive").
std::vector<double> edge_mean_curvature(const std::vector<Triangle>& tris, const std::vector<double>& X);

/// The enclosed volume, the area and the volume centroid of the closed triangulated surface X
/// (n x 3 column-major, outward triangles): sums over the tetrahedra (0, a, b, c) and the flat
/// triangles (LDSM's piecewise-linear surface).
struct PolyhedronMeasures {
  double volume = 0, area = 0;
  std::array<double, 3> centroid{0, 0, 0};
};
PolyhedronMeasures polyhedron_measures(const std::vector<Triangle>& tris, const std::vector<double>& X);

}  // namespace rbfib::surface
