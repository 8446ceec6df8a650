#pragma once
// How far a set of tethered points (eq. 2.10) has left its anchors, and how fast the fluid moves
// where they hold it: the measures of a wall made of tethers (the endothelium of Sec. 5.2).
#include "rbfib/sim/ib_step.hpp"

namespace rbfib::sim {

struct TetherMotion {
  double max_displacement = 0;  ///< max_k |X_k - X'_k| (cm)
  double slip_rms = 0;          ///< RMS over the anchors of |u| interpolated there by the step's kernel (cm/s)
};

/// Point set p of the coupled step.
TetherMotion tether_motion(const ImmersedBoundary& ib, index_t p);

}  // namespace rbfib::sim
