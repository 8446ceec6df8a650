#pragma once
// The tethered capillary of the seed's Chapter 3 (Sec. 5.1): nodes on a cylinder about the x axis,
// each pulled to its place by a spring, F_k = -k_teth (X_k - Z_k) (eq. 93), that together hold the
// frame (the constant velocity u_c of eqs. 94-95, sim/lagrangian.hpp), and the background force
// that drives the flow through it: f_in along +x inside the cylinder, a uniform balancing force
// outside, so that its integral over the grid is zero.
#include "rbfib/fluid/mac_operators.hpp"
#include "rbfib/sim/lagrangian.hpp"
#include "rbfib/surface/cylinder.hpp"

#include <cmath>
#include <string>

namespace rbfib::sim {

/// The nodes as tethered points at their anchors, holding the frame (eqs. 93-95).
TetheredPoints tethered_capillary(const std::string& name, const surface::CylinderPoints& nodes, double k_teth);

/// The background force density on the x-faces of ops' grid: f_in (dyn/cm^3) where y^2 + z^2 < R^2
/// and x0 <= x <= x1 (infinite bounds: the whole cylinder through the periodic box), f_out on the
/// other x-faces with N_in f_in + N_out f_out = 0; zero on the y- and z-faces.
VectorField capillary_driving_force(const MacOperators& ops, double R, double f_in, double x0 = -INFINITY,
                                    double x1 = INFINITY);

}  // namespace rbfib::sim
