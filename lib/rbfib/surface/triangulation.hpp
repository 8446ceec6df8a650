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

/// Incremental convex hull, O(n^2). Throws InputError for coincident sites or fewer than 4,
/// NumericalError if the hull is not a closed triangulation of every site.
std::vector<Triangle> sphere_triangulation(const SphereSites& sites);

/// The enclosed volume, the area and the volume centroid of the closed triangulated surface X
/// (n x 3 column-major, outward triangles): sums over the tetrahedra (0, a, b, c) and the flat
/// triangles (LDSM's piecewise-linear surface).
struct PolyhedronMeasures {
  double volume = 0, area = 0;
  std::array<double, 3> centroid{0, 0, 0};
};
PolyhedronMeasures polyhedron_measures(const std::vector<Triangle>& tris, const std::vector<double>& X);

}  // namespace rbfib::surface
