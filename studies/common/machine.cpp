#include "common/machine.hpp"

#include "rbfib/linalg/blas.hpp"

#include "common/force_call.hpp"
#include "common/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace rbfib::study {

Ceiling measure_ceiling(Json& results, index_t dgemm_n, int repeats) {
  Ceiling c;
  c.dgemm_flops = dgemm_rate(dgemm_n, repeats);
  c.triad_bytes_per_s = 3.0 * 8.0 * double(1 << 24) / triad_seconds(1 << 24);
  results["parameters"]["dgemm_n"] = double(dgemm_n);
  results["values"]["dgemm_gflops"] = c.dgemm_flops / 1e9;
  results["values"]["triad_GBps"] = c.triad_bytes_per_s / 1e9;
  return c;
}

void record_wait_policy(Json& parameters) {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  parameters["OMP_WAIT_POLICY"] = policy ? policy : "unset (libgomp default: spin, then sleep)";
}

double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = NAN;
  in >> l;
  return l;
}

double max_abs_diff(const dvec& a, const dvec& b) {
  const host_vector<double> x(a), y(b);
  double d = 0;
  for (std::size_t k = 0; k < x.size(); ++k) d = std::max(d, std::abs(x[k] - y[k]));
  return d;
}

double max_rel_diff(const std::vector<const dvec*>& a, const std::vector<const dvec*>& b) {
  double d = 0, m = 0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    d = std::max(d, max_abs_diff(*a[c], *b[c]));
    m = std::max(m, blas::norm_inf(*b[c]));
  }
  return m > 0 ? d / m : d;
}

double max_rel_diff(const std::array<dvec, 3>& a, const std::array<dvec, 3>& b) {
  return max_rel_diff({&a[0], &a[1], &a[2]}, {&b[0], &b[1], &b[2]});
}

}  // namespace rbfib::study
