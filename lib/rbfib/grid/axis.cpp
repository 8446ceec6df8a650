#include "rbfib/grid/axis.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib {

const char* to_string(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::periodic: return "periodic";
    case BoundaryKind::dirichlet: return "dirichlet";
    case BoundaryKind::neumann: return "neumann";
    case BoundaryKind::robin: return "robin";
  }
  return "?";
}

AxisEnd axis_end(const BoundaryCondition& bc, double s, double h) {
  // Linear extrapolation with a = 1 - s, b = s, a' = 1/h, b' = -1/h (after eq. A.9):
  //   gamma = alpha (s u_0 + (1 - s) u_1) + beta (u_1 - u_0) / h.
  const double denom = bc.alpha * s - bc.beta / h;  // alpha b + beta b'
  AxisEnd end;
  end.ghost = -(bc.alpha * (1.0 - s) + bc.beta / h) / denom;
  end.data = 1.0 / denom;
  // eq. A.10: eps = (beta (1 - 2s) - alpha h s (1 - s)) / (2 (beta - alpha h s)).
  const double eps = (bc.beta * (1.0 - 2.0 * s) - bc.alpha * h * s * (1.0 - s)) / (2.0 * (bc.beta - bc.alpha * h * s));
  end.one_minus_eps = 1.0 - eps;
  return end;
}

void Axis::validate(const std::string& name) const {
  require(cells >= 1, name + ".cells", cells, "must be a positive number of cells");
  require(std::isfinite(length) && length > 0.0, name + ".length", length, "must be positive and finite");
  require(std::isfinite(origin), name + ".origin", origin, "must be finite");
  require(g > 0.0 && g <= 1.0, name + ".g", g, "staggering must lie in (0, 1]");
  const bool lo_p = lower.kind == BoundaryKind::periodic, hi_p = upper.kind == BoundaryKind::periodic;
  require(lo_p == hi_p, name + ".upper", to_string(upper.kind),
          std::string("must be periodic exactly when the lower end is (lower is ") + to_string(lower.kind) + ")");
  if (lo_p) return;
  require(unknowns() >= 2, name + ".cells", cells, "a non-periodic axis needs at least 2 unknowns");
  for (int side = 0; side < 2; ++side) {
    const BoundaryCondition& bc = side ? upper : lower;
    const std::string f = name + (side ? ".upper" : ".lower");
    require(std::isfinite(bc.alpha) && std::isfinite(bc.beta), f + ".alpha/beta",
            to_text(bc.alpha) + "/" + to_text(bc.beta), "must be finite");
    require(bc.alpha != 0.0 || bc.beta != 0.0, f + ".alpha/beta", "0/0", "alpha and beta cannot both vanish");
    const double s = end_offset(side == 1);
    require(bc.alpha * s - bc.beta / h() != 0.0, f + ".alpha/beta", to_text(bc.alpha) + "/" + to_text(bc.beta),
            "alpha s - beta/h = 0: the ghost value is arbitrary (the extraordinary Robin case after eq. A.7)");
  }
}

AxisStencil make_stencil(const Axis& axis, Correction correction) {
  axis.validate("axis");
  AxisStencil st;
  st.n = axis.unknowns();
  st.periodic = axis.periodic();
  st.inv_h2 = 1.0 / (axis.h() * axis.h());
  if (st.periodic) return st;
  st.lo = axis_end(axis.lower, axis.end_offset(false), axis.h());
  st.hi = axis_end(axis.upper, axis.end_offset(true), axis.h());
  if (correction == Correction::appendix_a) {
    st.w_lo = st.lo.one_minus_eps;
    st.w_hi = st.hi.one_minus_eps;
    require(st.w_lo > 0.0, "axis.lower", to_string(axis.lower.kind),
            "1 - eps = " + to_text(st.w_lo) + " <= 0: the corrected Helmholtz operator would not be positive definite");
    require(st.w_hi > 0.0, "axis.upper", to_string(axis.upper.kind),
            "1 - eps = " + to_text(st.w_hi) + " <= 0: the corrected Helmholtz operator would not be positive definite");
  }
  return st;
}

}  // namespace rbfib
