#pragma once
// What the benchmark drivers share beyond study.hpp: the machine's ceilings measured in the same
// run (a square DGEMM for dense products, a streaming triad for bandwidth), the machine's state
// recorded beside the times (OpenMP wait policy, load average), and the largest differences of
// device vectors against a reference (the error of a fast path against the serial one).
#include "common/study.hpp"
#include "rbfib/core/exec.hpp"

#include <array>
#include <vector>

namespace rbfib::study {

/// This machine's ceilings, measured in the same run as the times they judge.
struct Ceiling {
  double dgemm_flops = 0;       ///< flop/s of a square DGEMM through linalg/dense (median of repeats)
  double triad_bytes_per_s = 0; ///< 3 x 8 n bytes over a triad on n = 2^24 doubles (best of 10)
};

/// Measures both ceilings and records parameters.dgemm_n, values.dgemm_gflops, values.triad_GBps.
Ceiling measure_ceiling(Json& results, index_t dgemm_n, int repeats);

/// parameters.OMP_WAIT_POLICY: the environment's, or the libgomp default.
void record_wait_policy(Json& parameters);

/// The one-minute load average of /proc/loadavg (NaN where unreadable): this machine is shared.
double load_average();

/// max_i |a_i - b_i|.
double max_abs_diff(const dvec& a, const dvec& b);

/// max over the vectors k of max |a_k - b_k|, over max over k of max |b_k| (the difference itself
/// when b is zero): one vector, or the three components of a MAC field.
double max_rel_diff(const std::vector<const dvec*>& a, const std::vector<const dvec*>& b);
double max_rel_diff(const std::array<dvec, 3>& a, const std::array<dvec, 3>& b);

}  // namespace rbfib::study
