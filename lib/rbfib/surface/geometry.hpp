#pragma once
// Field-level geometry on the sites of a set of surface operators: the jets of a surface from
// its values at the data sites, and curvature fields (paper eqs. 75-83).
#include "rbfib/surface/geometry_kernels.hpp"
#include "rbfib/surface/operators.hpp"

#include <vector>

namespace rbfib::surface {

/// Jets at the sample sites of ops from the points X (site-major, 3 per data site).
std::vector<Jet> jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& X_data);

/// Scalar jets at the sample sites from values at the data sites.
std::vector<ScalarJet> scalar_jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& u_data);

/// Jets of the unit sphere chi(lambda, theta) at the sites (exact).
std::vector<Jet> unit_sphere_jets(const SphereSites& sites);

/// Geometry at every jet; throws NumericalError naming `cell` and the site where det G <= 0.
std::vector<PointGeometry> surface_geometry(const std::vector<Jet>& jets, const std::string& cell);

}  // namespace rbfib::surface
