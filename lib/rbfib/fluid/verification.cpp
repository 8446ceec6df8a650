#include "rbfib/fluid/verification.hpp"

#include "rbfib/linalg/blas.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rbfib {

namespace {
VectorField sample_field(const NavierStokesSolver& ns, const ExactField& f, double t) {
  VectorField u;
  for (int a = 0; a < ns.grid().dims; ++a)
    u[a] = sample(ns.operators().component_box(a), [&](double x, double y, double z) { return f(a, t, x, y, z); });
  return u;
}
}  // namespace

double relative_difference(const VectorField& u, const VectorField& v, int dims) {
  double num = 0, den = 0;
  for (int a = 0; a < dims; ++a) {
    dvec d = u[a];
    blas::axpy(-1.0, v[a], d);
    num = std::max(num, blas::norm_inf(d));
    den = std::max(den, blas::norm_inf(v[a]));
  }
  return num / den;
}

ExactRun run_exact(const ExactProblem& problem, TimeIntegrator integrator, double dt) {
  NavierStokesOptions opt;
  opt.integrator = integrator;
  opt.dt = dt;
  NavierStokesSolver ns(problem.grid, problem.fluid, opt, problem.boundary);
  const int dims = problem.grid.dims;
  FluidState s = ns.zero_state(problem.t0);
  if (!problem.from_rest) s.u = sample_field(ns, problem.velocity, problem.t0);
  if (problem.pressure)
    s.p = sample(ns.operators().scalar_box(), [&](double x, double y, double z) { return problem.pressure(problem.t0, x, y, z); });
  double hmin = problem.grid.h(0);
  for (int d = 1; d < dims; ++d) hmin = std::min(hmin, problem.grid.h(d));
  ExactRun r;
  r.steps = int(std::llround((problem.t1 - problem.t0) / dt));
  long helm = 0, helm_n = 0, pois = 0, pois_n = 0;
  VectorField f;
  for (int n = 0; n < r.steps; ++n) {
    if (problem.force) f = sample_field(ns, problem.force, ns.force_time(s.t));
    const auto t0 = std::chrono::steady_clock::now();
    StepStats st = ns.step(s, problem.force ? &f : nullptr);
    r.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (int k = 0; k < st.stages; ++k) {
      for (int a = 0; a < dims; ++a) helm += st.helmholtz_iterations[k][a], ++helm_n;
      pois += st.poisson_iterations[k], ++pois_n;
    }
    double umax = 0;
    for (int a = 0; a < dims; ++a) umax = std::max(umax, blas::norm_inf(s.u[a]));
    r.max_div = std::max(r.max_div, st.max_divergence);
    r.max_div_rel = std::max(r.max_div_rel, st.max_divergence * hmin / umax);
  }
  r.helmholtz_iterations = helm_n ? double(helm) / helm_n : 0.0;
  r.poisson_iterations = pois_n ? double(pois) / pois_n : 0.0;
  const VectorField exact = sample_field(ns, problem.velocity, s.t);
  r.err_inf = relative_difference(s.u, exact, dims);
  double num = 0, den = 0;
  for (int a = 0; a < dims; ++a) {
    dvec d = s.u[a];
    blas::axpy(-1.0, exact[a], d);
    num += blas::dot(d, d);
    den += blas::dot(exact[a], exact[a]);
  }
  r.err_l2 = std::sqrt(num / den);
  r.u = std::move(s.u);
  return r;
}

}  // namespace rbfib
