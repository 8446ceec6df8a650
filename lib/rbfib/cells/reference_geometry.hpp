#pragma once
// Measures of a reference shape (shapes.hpp) before it is placed: the surface area of the
// Evans-Fung red cell (diss. Sec. 2.2) by quadrature of its profile, and the support function of a
// rotated shape (how far its convex hull reaches along a direction), by which cells are placed at
// a given gap between their hulls (Sec. 5.1.3).
#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/rotation.hpp"

namespace rbfib::cells {

/// The area of the Evans-Fung surface X(l, t) = R0 (cos l cos t, sin l cos t, zeta(cos^2 t) sin t),
/// zeta(s) = 0.105 + s - 0.56 s^2: 2 pi int r sqrt(r'^2 + z'^2) dt over [-pi/2, pi/2] with
/// r = R0 cos t and z = R0 zeta sin t, derivatives exact, composite Simpson over `intervals`
/// (even) intervals (cm^2; 134.19 um^2 for R0 = 3.91 um).
double evans_fung_area(double R0, int intervals = 20000);

/// The support function max_X (R X).u of the reference shape rotated by R: its convex hull's
/// extent along u (unit) from the origin, by a search over the (n_lambda + 1) x (n_theta + 1)
/// grid of lambda in [0, 2 pi] and theta in [-pi/2, pi/2] (cm). For the Evans-Fung cell with
/// R0 = 3.91 um the default grid is within 1e-4 um.
double support(const ReferenceShape& shape, const Mat3& R, const Vec3& u, int n_lambda = 1440, int n_theta = 720);

}  // namespace rbfib::cells
