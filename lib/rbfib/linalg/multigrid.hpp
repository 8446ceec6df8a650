#pragma once
// Geometric multigrid on cell-centred boxes (the Poisson solve of Section 2.1): a symmetric V-cycle
// whose smoother and coarsest-level solver are Chebyshev iteration, for use as a PCG preconditioner.
//
// Grid transfer between a box of n_d cells per axis and its coarsening with n_d / 2 cells (every
// coarsened axis must have an even count): prolongation P is the tensor product of the 1D
// cell-centred linear interpolation (weights 3/4 and 1/4 from the two nearest coarse cells; on a
// wall the missing neighbour is replaced by the cell itself, i.e. constant extrapolation, which
// matches homogeneous Neumann data; periodic axes wrap), and restriction is R = P^T / 2^dims, so
// that the V-cycle with the same Chebyshev polynomial before and after the coarse correction is a
// symmetric operator.
//
// Index order x fastest (Box); operators act on plain device vectors.
#include "rbfib/linalg/chebyshev.hpp"

#include <functional>
#include <vector>

namespace rbfib {

/// Shape of one coarsening step.
struct CellCentredTransfer {
  int dims = 3;
  int fine[3] = {1, 1, 1};
  int coarse[3] = {1, 1, 1};
  bool periodic[3] = {true, true, true};

  index_t fine_size() const { return index_t(fine[0]) * fine[1] * fine[2]; }
  index_t coarse_size() const { return index_t(coarse[0]) * coarse[1] * coarse[2]; }
};

/// fine += P coarse
void prolong_add(const CellCentredTransfer& t, const dvec& coarse, dvec& fine);
/// coarse = P^T fine / 2^dims
void restrict_to_coarse(const CellCentredTransfer& t, const dvec& fine, dvec& coarse);

/// One level of the hierarchy: its operator A (SPD, or positive semidefinite with a known null
/// space removed by the caller), its Chebyshev smoother (or coarse solver on the last level), and
/// the transfer to the next coarser level (ignored on the last level).
struct MultigridLevel {
  std::function<void(const dvec&, dvec&)> apply;
  ChebyshevIteration smoother;
  CellCentredTransfer to_coarse;
  index_t size = 0;
};

class Multigrid {
 public:
  Multigrid() = default;
  explicit Multigrid(std::vector<MultigridLevel> levels);

  /// x = V b: one V-cycle from a zero initial guess (a fixed symmetric linear map of b).
  void vcycle(const dvec& b, dvec& x) const;
  int levels() const { return int(levels_.size()); }
  const MultigridLevel& level(int l) const { return levels_[l]; }

 private:
  void cycle(int l, const dvec& b, dvec& x) const;

  std::vector<MultigridLevel> levels_;
  mutable std::vector<dvec> r_, bc_, xc_;
};

}  // namespace rbfib
