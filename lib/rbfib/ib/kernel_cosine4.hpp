#pragma once
// 4-point cosine kernel (seed Sec. 5.1.3, Fig. 5.1):
//   phi(r) = (1 + cos(pi r / 2)) / 4   for |r| <= 2,   0 otherwise.
// Support width s = 4. Properties: sum_j phi(r - j) = 1, the even-odd condition
// sum_{j even} phi(r - j) = sum_{j odd} phi(r - j) = 1/2, and sum_j phi(r - j)^2 = 3/8.
// It does not have a vanishing first moment.
#include "rbfib/core/exec.hpp"

#include <cmath>

namespace rbfib::ib {

struct Cosine4 {
  static constexpr int support = 4;
  static constexpr const char* name = "cosine4";
  RBFIB_HD static double phi(double r) {
    const double a = r < 0 ? -r : r;
    if (a <= 2.0) return 0.25 * (1.0 + cos(1.5707963267948966 * a));
    return 0.0;
  }
  /// w[t] = phi(t - 2 + delta), t = 0..3, for delta in (0, 1]: one sine and one cosine.
  RBFIB_HD static void weights(double d, double w[4]) {
    const double c = cos(1.5707963267948966 * d), s = sin(1.5707963267948966 * d);
    w[0] = 0.25 * (1.0 - c);
    w[1] = 0.25 * (1.0 + s);
    w[2] = 0.25 * (1.0 + c);
    w[3] = 0.25 * (1.0 - s);
  }
};

}  // namespace rbfib::ib
