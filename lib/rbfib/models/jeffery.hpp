#pragma once
// The rigid-body reference for a spheroid in simple shear (Jeffery 1922): the orbit of its symmetry
// axis, beside which the studies of Secs. 5.1.2 and 5.2 read a cell's tumbling and a platelet's
// wobble.
#include "rbfib/core/rotation.hpp"

#include <vector>

namespace rbfib::models {

/// The symmetry axis p(t) of a rigid spheroid of aspect ratio r (axis along p over the transverse
/// diameter; r < 1 oblate) in the simple shear u = gdot x_g e_f (flow along axis f, gradient
/// along axis g), from p(0) = p0 (Jeffery 1922):
///   dp/dt = W p + B (E p - (p.E p) p),  B = (r^2 - 1) / (r^2 + 1),
/// W and E the antisymmetric and symmetric parts of grad u. Classical RK4 with steps of at most
/// 1e-3 / gdot, renormalized; returns p at each of `times` (ascending, from t = 0).
std::vector<Vec3> jeffery_axis(const Vec3& p0, double r, double gdot, int f, int g, const std::vector<double>& times);

}  // namespace rbfib::models
