#pragma once
// Checkpoints of a scene's run in HDF5: the scene's YAML text and everything the coupled step
// carries over (sim::ImmersedBoundary::Carried). Restoring one into the step built from the
// same scene continues the run bit for bit.
//
// Layout (one file; every array a 1D dataset of doubles, in the library's layouts):
//   /scene                the YAML text (bytes)
//   /fluid/u0, u1, u2     the MAC velocity components (cm/s), /fluid/p (dyn/cm^2),
//   /fluid/phi0, phi1     the lagged projection data (cm^2/s); attribute t (s)
//   /batches/0, 1, ...    each cell batch's data-site state, n_d x 6N column-major: X then U
//   /points/0, 1, ...     each tethered point set's positions, 3n
//   attributes of /: format ("rbfib checkpoint 1"), steps, dt (s), level, allowing
// Written atomically: to PATH.tmp, flushed and fsynced, then renamed over PATH (and the
// directory fsynced), so a kill at any moment leaves the previous checkpoint whole.
#include "rbfib/sim/ib_step.hpp"

#include <string>

namespace rbfib::io {

void write_checkpoint(const std::string& path, const std::string& scene_yaml, const sim::ImmersedBoundary& ib);

struct Checkpoint {
  std::string scene_yaml;
  sim::ImmersedBoundary::Carried state;
};

/// Reads a checkpoint; throws InputError naming the file and what is missing or malformed.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace rbfib::io
