#include "common/force_call.hpp"

#include "common/study.hpp"
#include "rbfib/linalg/dense.hpp"

#include <cmath>
#include <vector>

namespace rbfib::study {

double dgemm_rate(index_t n, int repeats) {
  std::vector<double> h(static_cast<std::size_t>(n * n));
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = std::sin(0.001 * double(k));
  const linalg::DeviceMatrix A = linalg::DeviceMatrix::from_host(n, n, h.data()), B = A;
  linalg::DeviceMatrix C(n, n);
  auto call = [&] { linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0, A.view(), B.view(), 0.0, C.view()); };
  call();
  const double t = median_seconds(repeats, [&] {
    call();
    synchronize();
  });
  return 2.0 * double(n) * n * n / t;
}

cells::ForceTimings median_force_timings(const cells::Batch& b, int repeats, double& total) {
  cells::CellForces out;
  cells::compute_forces(b, out);
  std::vector<double> ph[5], tot;
  for (int i = 0; i < repeats; ++i) {
    cells::ForceTimings t;
    cells::compute_forces(b, out, &t);
    const double v[5] = {t.jets, t.bending_products, t.bending_kernel, t.kernels, t.reductions};
    for (int q = 0; q < 5; ++q) ph[q].push_back(v[q]);
    tot.push_back(t.total());
  }
  total = median(tot);
  return {median(ph[0]), median(ph[1]), median(ph[2]), median(ph[3]), median(ph[4])};
}

}  // namespace rbfib::study
