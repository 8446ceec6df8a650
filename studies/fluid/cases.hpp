#pragma once
// The verification problems of the `fluid` study (exact solutions: fluid/exact_solutions.hpp).
#include "rbfib/fluid/verification.hpp"

namespace rbfib::study {

/// Taylor-Green vortex on the periodic box [0, L]^2 x [0, Lz], cells n x n x nz.
ExactProblem taylor_green(int n, int nz);
/// Start-up Couette flow in the whole-blood channel (16 x 12 x 16 um), cells nxz x ny x nxz.
ExactProblem couette(int ny, int nxz);
/// Manufactured flow on [0, 1]^3 cm, periodic x, no-slip (moving) walls in y and z, n^3 cells.
ExactProblem manufactured(int n);

}  // namespace rbfib::study
