#pragma once
// 4-point cubic B-spline kernel B_3 (seed Sec. 5.1.1, Fig. 5.1):
//   phi(r) = 2/3 - r^2 + |r|^3 / 2      for |r| <= 1,
//            (2 - |r|)^3 / 6            for 1 <= |r| <= 2,
//            0                          otherwise.
// Support width s = 4. Properties: sum_j phi(r - j) = 1, sum_j (r - j) phi(r - j) = 0 and
// sum_j (r - j)^2 phi(r - j) = 1/3 for every real r; C^2 smooth.
#include "rbfib/core/exec.hpp"

namespace rbfib::ib {

struct BSpline3 {
  static constexpr int support = 4;
  static constexpr const char* name = "bspline3";
  RBFIB_HD static double phi(double r) {
    const double a = r < 0 ? -r : r;
    if (a <= 1.0) return 2.0 / 3.0 - a * a + 0.5 * a * a * a;
    if (a <= 2.0) {
      const double b = 2.0 - a;
      return b * b * b / 6.0;
    }
    return 0.0;
  }
  /// w[t] = phi(t - 2 + delta), t = 0..3, for delta in (0, 1], without branches.
  RBFIB_HD static void weights(double d, double w[4]) {
    const double e = 1.0 - d;
    w[0] = d * d * d / 6.0;
    w[1] = 2.0 / 3.0 - e * e + 0.5 * e * e * e;
    w[2] = 2.0 / 3.0 - d * d + 0.5 * d * d * d;
    w[3] = e * e * e / 6.0;
  }
};

}  // namespace rbfib::ib
