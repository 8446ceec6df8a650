#pragma once
// Field-level geometry on the sites of a set of surface operators, for one cell on the host: the
// jets of a surface from its values at the data sites, and curvature fields (paper eqs. 75-83).
// Points are n x 3 column-major (X[d n + i], docs/math.md). The batched device path over all
// cells of a type is in cells/.
#include "rbfib/surface/geometry_kernels.hpp"
#include "rbfib/surface/operators.hpp"

#include <string>
#include <vector>

namespace rbfib::surface {

/// Downloads the jets of one cell (the value block n x 3 and derivative block 5n x 3 that
/// apply_operators writes) into host jets.
std::vector<Jet> jets_on_host(const linalg::DeviceMatrix& value, const linalg::DeviceMatrix& derivatives);

/// Jets at the sample sites of ops from the points X (n_d x 3, column-major).
std::vector<Jet> jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& X_data);

/// Scalar jets at the sample sites from values at the data sites.
std::vector<ScalarJet> scalar_jets_from_operators(const SurfaceOperators& ops, const std::vector<double>& u_data);

/// Jets of the unit sphere chi(lambda, theta) at the sites (exact).
std::vector<Jet> unit_sphere_jets(const SphereSites& sites);

/// Geometry at every jet; throws NumericalError naming `cell` and the site where det G <= 0.
std::vector<PointGeometry> surface_geometry(const std::vector<Jet>& jets, const std::string& cell);

}  // namespace rbfib::surface
