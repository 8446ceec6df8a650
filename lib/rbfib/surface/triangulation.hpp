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

}  // namespace rbfib::surface
