#include "rbfib/cells/shapes.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::cells {

ReferenceShape evans_fung_red_cell(double R0) {
  require(R0 > 0, "red cell radius R0 (cm)", R0, "must be > 0");
  return {"Evans-Fung red cell, R0 = " + to_text(R0 * 1e4) + " um", [R0](double l, double t, double* x) {
            const double ct = std::cos(t), st = std::sin(t), r = ct * ct;
            x[0] = R0 * std::cos(l) * ct;
            x[1] = R0 * std::sin(l) * ct;
            x[2] = R0 * (0.105 + r - 0.56 * r * r) * st;
          }};
}

ReferenceShape chapter3_red_cell_shape(double R) {
  require(R > 0, "red cell radius R (cm)", R, "must be > 0");
  return {"red cell of paper eq. (92), R = " + to_text(R * 1e4) + " um", [R](double l, double t, double* x) {
            const double xs = std::cos(l) * std::cos(t), ys = std::sin(l) * std::cos(t), zs = std::sin(t);
            const double q = ys * ys + zs * zs;
            x[0] = R * 0.5 * xs * (0.21 + 2 * q - 1.12 * q * q);
            x[1] = R * ys;
            x[2] = R * zs;
          }};
}

ReferenceShape ellipsoid_shape(double a, double b, double c) {
  require(a > 0 && b > 0 && c > 0, "ellipsoid semi-axes a, b, c (cm)", to_text(a) + ", " + to_text(b) + ", " + to_text(c),
          "must be > 0");
  const bool sphere = a == b && b == c;
  return {(sphere ? "sphere, R = " + to_text(a * 1e4) + " um"
                  : "ellipsoid " + to_text(a * 1e4) + " x " + to_text(b * 1e4) + " x " + to_text(c * 1e4) + " um"),
          [a, b, c](double l, double t, double* x) {
            x[0] = a * std::cos(l) * std::cos(t);
            x[1] = b * std::sin(l) * std::cos(t);
            x[2] = c * std::sin(t);
          }};
}

}  // namespace rbfib::cells
