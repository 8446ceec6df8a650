#include "problem.hpp"

#include "common/study.hpp"

#include <random>
#include <vector>

namespace rbfib::unstructured {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

host_vector<double> random_points(index_t n, double L, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, L);
  host_vector<double> X(3 * n);
  for (auto& x : X) x = U(rng);
  return X;
}

Flow shear_flow(const std::array<Box, 3>& boxes, const Params& p) {
  Flow flow;
  const Box& bz = boxes[2];
  const int ny = bz.n(1);
  const double h = bz.axes[1].h();
  std::vector<double> uz(ny), fz(ny);
  for (int j = 0; j < ny; ++j) uz[j] = p.shear_rate * (bz.x(1, j) - 0.5 * p.box);
  for (int j = 0; j < ny; ++j) {
    fz[j] = -p.viscosity * ((uz[(j + 1) % ny] - 2 * uz[j] + uz[(j + ny - 1) % ny]) / (h * h));
    flow.max_background = std::max(flow.max_background, std::abs(fz[j]));
  }
  host_vector<double> u(bz.size()), f(bz.size());
  for (index_t m = 0; m < bz.size(); ++m) u[m] = uz[m / bz.n(0) % ny], f[m] = fz[m / bz.n(0) % ny];  // x fastest, then y
  for (int c = 0; c < 2; ++c) flow.u[c] = flow.f_bg[c] = dvec(boxes[c].size(), 0.0);
  flow.u[2] = u, flow.f_bg[2] = f;
  return flow;
}

Timing run_steps(Interaction& ib, const Flow& flow, const host_vector<double>& X0h, const Params& p, int steps,
                 Interpolation interp, Spreading spread) {
  const index_t n = X0h.size() / 3;
  const dvec X0 = X0h;
  dvec X = X0, Xs(3 * n), F(3 * n), U;
  std::array<dvec, 3> f;
  std::vector<double> ti, ts;
  for (int step = 0; step < steps; ++step) {
    auto t0 = std::chrono::steady_clock::now();
    ib.interpolate(X, flow.u, U, interp);  // (1)
    ti.push_back(seconds_since(t0));
    const double dt = p.dt, k = p.spring;
    thrust::transform(X.begin(), X.end(), U.begin(), Xs.begin(), [dt] RBFIB_HD(double x, double v) { return x + dt * v; });  // (2)
    thrust::transform(Xs.begin(), Xs.end(), X0.begin(), F.begin(), [k] RBFIB_HD(double x, double x0) { return -k * (x - x0); });
    t0 = std::chrono::steady_clock::now();
    ib.spread(Xs, F, f, spread);  // (3)
    ts.push_back(seconds_since(t0));
    for (int c = 0; c < 3; ++c)
      thrust::transform(f[c].begin(), f[c].end(), flow.f_bg[c].begin(), f[c].begin(), thrust::plus<double>());
    t0 = std::chrono::steady_clock::now();
    ib.interpolate(Xs, flow.u, U, interp);  // (4)
    ti.push_back(seconds_since(t0));
    thrust::transform(X.begin(), X.end(), U.begin(), X.begin(), [dt] RBFIB_HD(double x, double v) { return x + dt * v; });  // (5)
  }
  return {study::median(ti), study::median(ts)};
}

}  // namespace rbfib::unstructured
