#pragma once
// Timing the cell force call (cells/batch.hpp), shared by the studies that do: the machine's
// ceiling for its dense products (a square DGEMM through the same dense seam, measured in the
// same run) and the median phase times; the flops of a call's products are cells::product_flops.
#include "rbfib/cells/batch.hpp"

namespace rbfib::study {

/// Flop rate (flop/s) of a square n x n x n DGEMM through linalg/dense, median of repeats.
double dgemm_rate(index_t n, int repeats);

/// Median over repeated force calls of each phase; total: the median of the whole call. One
/// warm-up call first (it allocates the workspace).
cells::ForceTimings median_force_timings(const cells::Batch& batch, int repeats, double& total);

}  // namespace rbfib::study
