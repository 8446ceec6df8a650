#include "cases.hpp"

#include "rbfib/core/units.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rbfib::study {

using MB = MacBoundary;

// Seed, Section 2 opening: plasma rho = 1 g/cm^3, mu = 0.1 cP (the value the seed states).
static FluidParameters plasma() { return FluidParameters{1.0 * units::g / (units::cm * units::cm * units::cm), 0.1 * units::cP}; }

Problem taylor_green(int n, int nz) {
  Problem p;
  p.name = "taylor_green";
  const double L = 16 * units::um;
  p.grid = make_mac_grid(3, {n, n, nz}, {L, L, L}, {MB::periodic, MB::periodic, MB::periodic});
  p.fluid = plasma();
  exact::TaylorGreen tg{L, 1.0 * units::cm / units::s, p.fluid.viscosity / p.fluid.density, p.fluid.density};
  p.velocity = [tg](int a, double t, double x, double y, double z) { return tg.velocity(a, t, x, y, z); };
  p.pressure = [tg](double t, double x, double y, double z) { return tg.pressure(t, x, y, z); };
  p.t0 = 0.0;
  p.t1 = 4 * units::us;
  return p;
}

Problem couette(int ny, int nxz) {
  Problem p;
  p.name = "couette";
  const double H = 12 * units::um, U = 12 * units::mm / units::s;
  p.grid = make_mac_grid(3, {nxz, ny, nxz}, {16 * units::um, H, 16 * units::um}, {MB::periodic, MB::dirichlet, MB::periodic});
  p.fluid = plasma();
  exact::Couette c{H, U, p.fluid.viscosity / p.fluid.density};
  p.velocity = [c](int a, double t, double x, double y, double z) { return c.velocity(a, t, x, y, z); };
  p.boundary = [U](int a, int d, int side, double, double, double, double) {
    return (a == 0 && d == 1 && side == 1) ? U : 0.0;  // top wall moves in x
  };
  // Start from the series at t0 = 10 us (the data at t = 0 jump at the moving wall, which limits
  // any scheme's order); compare at t1 = 20 us.
  p.t0 = 10 * units::us;
  p.t1 = 20 * units::us;
  return p;
}

Problem manufactured(int n) {
  Problem p;
  p.name = "manufactured";
  p.grid = make_mac_grid(3, {n, n, n}, {1.0, 1.0, 1.0}, {MB::periodic, MB::dirichlet, MB::dirichlet});
  p.fluid = FluidParameters{1.0, 0.1};
  exact::Manufactured m;
  m.rho = p.fluid.density;
  m.mu = p.fluid.viscosity;
  p.velocity = [m](int a, double t, double x, double y, double z) { return m.velocity(a, t, x, y, z); };
  p.pressure = [m](double t, double x, double y, double z) { return m.pressure(t, x, y, z); };
  p.force = [m](int a, double t, double x, double y, double z) { return m.force(a, t, x, y, z); };
  p.boundary = [m](int a, int, int, double t, double x, double y, double z) { return m.velocity(a, t, x, y, z); };
  p.t0 = 0.0;
  p.t1 = 0.04;
  return p;
}

static VectorField sample_field(const NavierStokesSolver& ns, const Field& f, double t) {
  VectorField u;
  for (int a = 0; a < ns.grid().dims; ++a)
    u[a] = sample(ns.operators().component_box(a), [&](double x, double y, double z) { return f(a, t, x, y, z); });
  return u;
}

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

RunResult run(const Problem& problem, TimeIntegrator integrator, double dt) {
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
  RunResult r;
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

}  // namespace rbfib::study
