#pragma once
// 3-point kernel of Roma, Peskin and Berger (1999), seed Fig. 5.1:
//   phi(r) = (1 + sqrt(1 - 3 r^2)) / 3                     for |r| <= 1/2,
//            (5 - 3|r| - sqrt(1 - 3 (1 - |r|)^2)) / 6      for 1/2 <= |r| <= 3/2,
//            0                                             otherwise.
// Support width s = 3 (eq. 4.3). Properties: sum_j phi(r - j) = 1, sum_j (r - j) phi(r - j) = 0,
// sum_j phi(r - j)^2 = 1/2 for every real r.
#include "rbfib/core/exec.hpp"

#include <cmath>

namespace rbfib::ib {

struct Roma3 {
  static constexpr int support = 3;
  static constexpr const char* name = "roma3";
  RBFIB_HD static double phi(double r) {
    const double a = r < 0 ? -r : r;
    if (a <= 0.5) return (1.0 + sqrt(1.0 - 3.0 * a * a)) / 3.0;
    if (a <= 1.5) {
      const double b = 1.0 - a;
      const double q = 1.0 - 3.0 * b * b;
      return (5.0 - 3.0 * a - sqrt(q > 0.0 ? q : 0.0)) / 6.0;
    }
    return 0.0;
  }
  /// w[t] = phi(t - 1 + delta), t = 0..2, for delta in (-1/2, 1/2]: one square root,
  /// sqrt(1 - 3 delta^2).
  RBFIB_HD static void weights(double d, double w[3]) {
    const double q = sqrt(1.0 - 3.0 * d * d);
    w[0] = (2.0 + 3.0 * d - q) / 6.0;
    w[1] = (1.0 + q) / 3.0;
    w[2] = (2.0 - 3.0 * d - q) / 6.0;
  }
};

}  // namespace rbfib::ib
