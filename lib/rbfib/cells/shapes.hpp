#pragma once
// Reference shapes of cells as maps from material coordinates (lambda, theta) on S^2 (see
// surface/sphere.hpp) to positions in cm. A cell type needs only positions at its data sites:
// its reference jets come from its own surface operators (cell_type.hpp).
//
//   evans_fung_red_cell (diss. Sec. 2.2): X = R0 (cos l cos t, sin l cos t, z(cos^2 t) sin t),
//       z(r) = 0.105 + r - 0.56 r^2; axis of symmetry z, R0 = 3.91 um.
//   chapter3_red_cell_shape (paper eq. 92): with (x, y, z) = chi(l, t) and q = y^2 + z^2,
//       X = R (x/2 (0.21 + 2 q - 1.12 q^2), y, z); axis of symmetry x, R = 3.91 um.
//   ellipsoid: X = (a cos l cos t, b sin l cos t, c sin t); the platelet (diss. Sec. 2.2) has
//       a = b = 1.55 um, c = 0.5 um (short axis z); a sphere has a = b = c.
#include <functional>
#include <string>

namespace rbfib::cells {

struct ReferenceShape {
  std::string name;
  std::function<void(double lambda, double theta, double* x)> position;  ///< x[0..2] in cm
};

ReferenceShape evans_fung_red_cell(double R0);
ReferenceShape chapter3_red_cell_shape(double R);
ReferenceShape ellipsoid_shape(double a, double b, double c);

}  // namespace rbfib::cells
