#pragma once
// The pressure Poisson solve of a channel (eq. 2.9: cell centres, x and z periodic, homogeneous
// Neumann walls in y) by the solvers a user could reach for, on the same right-hand side and to the
// same tolerance: our direct Fourier solver, our multigrid-preconditioned CG, and, where the build
// found it, hypre's structured multigrid PFMG as the preconditioner of hypre's CG (a benchmark peer
// only: the library never needs hypre).
#include "rbfib/grid/box.hpp"

#include <string>
#include <vector>

namespace rbfib::study {

struct PoissonPeer {
  std::string solver;
  double seconds = 0;     ///< median wall time of one solve
  double iterations = 0;  ///< 0 for the direct solve
  double relative_residual = 0;  ///< ||b + L q|| / ||b||
  double max_rel_diff_vs_fourier = 0;
};

/// Solves -L q = b for a mean-free random b on `box` with each solver (median of `repeats`).
std::vector<PoissonPeer> compare_poisson_solvers(const Box& box, int repeats, double rtol);

/// Whether hypre was found when this driver was built.
bool have_hypre();

}  // namespace rbfib::study
