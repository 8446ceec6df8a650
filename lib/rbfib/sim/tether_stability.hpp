#pragma once
// The explicit stability of tethered points (eq. 2.10: F = -k (X - X') - eta U per point) in the
// seed's coupling (a)-(g) with backward-forward Euler. The derivation and its numbers:
// docs/derivations/tether_stability/README.md. In short: a flat sheet of tethered points a height
// H above a no-slip wall has a most mobile mode, the uniform sliding mode, and a step maps it by a
// real eigenvalue that crosses -1 (sign flips every step) when
//   (eta + c k dt) G1(dt) > 1,   c = 1/2 with the spring at X^n (the seed's coupling: tethered
//                                 points are not predicted), 3/2 at X* (predicted: the midpoint one);
//   G1(dt) = n_A J (2 rho/dt - mu L_h)^{-1} S~   (cm s^-1 dyn^-1),
// the per-point mobility of that mode for an oscillation flipping sign every step: n_A points per
// area, J the kernel's interpolation across the wall-normal MAC x-velocities u_j at
// y_j = (j + 1/2) h, S~ = w / h its spreading, L_h the 1D second difference with the walls'
// no-slip. Eq. 5.4 does not see this instability until its amplitude has grown by orders of
// magnitude, so the adaptive step needs it as a bound of its own.
// "The seed's rule" (Sec. 2.2: the constants "as large as possible for the chosen spatial and
// temporal step size"): eta = 0.8 s / G1(dt), k = 0.4 s / (dt G1(dt)), a gain s with the seed's
// split k dt/2 : eta = 1 : 4 (tether time eta/k = 2 dt); s = 0.8 gives the seed's k = 2.5 dyn/cm and
// eta = 2.5e-7 dyn s/cm at h = 0.2 um, n_A = 62.5 um^-2, 1 cP, dt = 50 ns.
// Units: CGS.
#include "rbfib/ib/kernels.hpp"

namespace rbfib::sim {

/// A flat sheet of tethered points in a channel between two no-slip walls a height apart (y).
struct TetherSheet {
  double h = 0;                ///< grid spacing (cm)
  double channel = 0;          ///< distance between the walls (cm): a whole number of cells
  double plane = 0;            ///< the sheet's height above the lower wall (cm)
  double points_per_area = 0;  ///< n_A (1/cm^2)
  double rho = 1, mu = 0;      ///< g/cm^3, P
  ib::Kernel kernel = ib::Kernel::bspline3;
};

/// G1(dt) (cm s^-1 dyn^-1); InputError for a sheet that makes no sense.
double sliding_mobility(const TetherSheet& s, double dt);

/// The sliding mode's gain (eta + c k dt) G1(dt) (c = 1/2; 3/2 when the coupling predicts the
/// points): the step is stable below 1.
double tether_gain(const TetherSheet& s, double k, double eta, double dt, bool predicted);

/// The largest dt in [lo, hi] whose gain is at most 1 (the gain grows with dt); lo when even lo
/// exceeds it, hi when hi does not.
double tether_dt_limit(const TetherSheet& s, double k, double eta, bool predicted, double lo = 1e-10, double hi = 1e-4);

struct TetherConstants {
  double k = 0;    ///< dyn/cm per point
  double eta = 0;  ///< dyn s/cm per point
};

/// The seed's rule at gain `safety` (in (0, 1)): eta = 0.8 safety / G1(dt), k = 0.4 safety / (dt G1(dt)).
TetherConstants tether_constants_for_step(const TetherSheet& s, double dt, double safety);

}  // namespace rbfib::sim
