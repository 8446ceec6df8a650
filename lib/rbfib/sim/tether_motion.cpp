#include "rbfib/sim/tether_motion.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::sim {

TetherMotion tether_motion(const ImmersedBoundary& ib, index_t p) {
  const TetheredPoints& e = ib.points(p);
  const host_vector<double> X(e.X.begin(), e.X.end()), A(e.anchors.begin(), e.anchors.end());
  const std::size_t m = X.size() / 3;
  TetherMotion out;
  for (std::size_t i = 0; i < m; ++i) {
    double d2 = 0;
    for (std::size_t d = 0; d < 3; ++d) d2 += (X[d * m + i] - A[d * m + i]) * (X[d * m + i] - A[d * m + i]);
    out.max_displacement = std::max(out.max_displacement, std::sqrt(d2));
  }
  const MacOperators& ops = ib.fluid().operators();
  ib::Interaction probe({ops.component_box(0), ops.component_box(1), ops.component_box(2)}, ib.options().kernel);
  dvec U;
  probe.interpolate(e.anchors, ib.fluid_state().u, U);
  const host_vector<double> Uh(U.begin(), U.end());
  double sum = 0;
  for (double u : Uh) sum += u * u;
  out.slip_rms = m > 0 ? std::sqrt(sum / double(m)) : 0;
  return out;
}

}  // namespace rbfib::sim
