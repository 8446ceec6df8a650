#pragma once
// The velocity profile across a channel with walls in y, periodic in x and z (Fig. 5.4): the
// average over each x-z plane of cell centres of the velocity's component along a direction
// (d_x, 0, d_z) of those planes.
#include "rbfib/sim/ib_step.hpp"

#include <array>
#include <vector>

namespace rbfib::sim {

/// At each level y_j = (j + 1/2) h of the cell centres: the x-z mean of d_x u_x + d_z u_z (cm/s).
std::vector<double> velocity_profile(const ImmersedBoundary& ib, const std::array<double, 3>& direction);

}  // namespace rbfib::sim
