#pragma once
// Timing the cell force call (cells/batch.hpp), shared by the studies that do: the machine's
// ceiling for its dense products (a square DGEMM through the same dense seam, measured in the
// same run), the flops and operator bytes of one call's products, and the median phase times.
#include "rbfib/cells/batch.hpp"

namespace rbfib::study {

/// Flop rate (flop/s) of a square n x n x n DGEMM through linalg/dense, median of repeats.
double dgemm_rate(index_t n, int repeats);

/// Flops of the dense products of one force call for N cells of a type, as performed: the jets
/// of positions (and, with dissipation, velocities) at the sample and, with bending, the data
/// sites (one product, 2 x 6 (n_s + n_d) n_d x 3 or 6 N), and the derivatives of H - H' at the
/// sample sites (2 x 5 n_s n_d x N); and the operator bytes they stream (each product reads its
/// operator once).
struct ProductFlops {
  double jets = 0, bending = 0;
  double bytes = 0;
  double total() const { return jets + bending; }
};
ProductFlops product_flops(const cells::CellType& type, index_t N);

/// Median over repeated force calls of each phase; total: the median of the whole call. One
/// warm-up call first (it allocates the workspace).
cells::ForceTimings median_force_timings(const cells::Batch& batch, int repeats, double& total);

}  // namespace rbfib::study
