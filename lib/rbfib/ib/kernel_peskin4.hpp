#pragma once
// 4-point kernel of Peskin (2002):
//   phi(r) = (3 - 2|r| + sqrt(1 + 4|r| - 4 r^2)) / 8        for |r| <= 1,
//            (5 - 2|r| - sqrt(-7 + 12|r| - 4 r^2)) / 8      for 1 <= |r| <= 2,
//            0                                              otherwise.
// Support width s = 4. Properties: sum_j phi(r - j) = 1, even-odd condition (each half sums to
// 1/2), sum_j (r - j) phi(r - j) = 0, sum_j phi(r - j)^2 = 3/8.
#include "rbfib/core/exec.hpp"

#include <cmath>

namespace rbfib::ib {

struct Peskin4 {
  static constexpr int support = 4;
  static constexpr const char* name = "peskin4";
  RBFIB_HD static double phi(double r) {
    const double a = r < 0 ? -r : r;
    if (a <= 1.0) return (3.0 - 2.0 * a + sqrt(1.0 + 4.0 * a - 4.0 * a * a)) / 8.0;
    if (a <= 2.0) {
      const double q = -7.0 + 12.0 * a - 4.0 * a * a;
      return (5.0 - 2.0 * a - sqrt(q > 0.0 ? q : 0.0)) / 8.0;
    }
    return 0.0;
  }
  /// w[t] = phi(t - 2 + delta), t = 0..3, for delta in (0, 1]: all four share one square root,
  /// sqrt(1 + 4 delta - 4 delta^2).
  RBFIB_HD static void weights(double d, double w[4]) {
    const double q = sqrt(1.0 + 4.0 * d - 4.0 * d * d);
    w[0] = (1.0 + 2.0 * d - q) / 8.0;
    w[1] = (1.0 + 2.0 * d + q) / 8.0;
    w[2] = (3.0 - 2.0 * d + q) / 8.0;
    w[3] = (3.0 - 2.0 * d - q) / 8.0;
  }
};

}  // namespace rbfib::ib
