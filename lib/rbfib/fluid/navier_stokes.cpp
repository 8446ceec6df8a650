#include "rbfib/fluid/navier_stokes.hpp"

#include "rbfib/fluid/mac_kernels.hpp"

#include <chrono>
#include <cmath>

namespace rbfib {

const char* to_string(TimeIntegrator integrator) {
  switch (integrator) {
    case TimeIntegrator::backward_forward_euler: return "backward-forward Euler";
    case TimeIntegrator::peskin_two_stage: return "Peskin 2-stage";
  }
  return "?";
}

namespace {
using clock_type = std::chrono::steady_clock;
double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

/// out = k (f / rho - G p / rho - N)
struct StageSource {
  const double *f, *gp, *adv;
  double k, inv_rho;
  double* out;
  RBFIB_HD void operator()(index_t i) const { out[i] = k * ((f ? f[i] : 0.0) * inv_rho - gp[i] * inv_rho - adv[i]); }
};

/// y = s x
struct Scaled {
  const double* x;
  double s;
  double* y;
  RBFIB_HD void operator()(index_t i) const { y[i] = s * x[i]; }
};
}  // namespace

NavierStokesSolver::NavierStokesSolver(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options,
                                       BoundaryVelocity boundary, std::shared_ptr<const FluidDecomposition> parts)
    : grid_(parts ? parts->local_grid() : grid),
      fluid_(fluid),
      options_(std::move(options)),
      boundary_(std::move(boundary)),
      ops_(grid_),
      parts_(std::move(parts)) {
  require(std::isfinite(fluid_.density) && fluid_.density > 0.0, "fluid.density", fluid_.density,
          "must be positive and finite (g/cm^3)");
  require(std::isfinite(fluid_.viscosity) && fluid_.viscosity > 0.0, "fluid.viscosity", fluid_.viscosity,
          "must be positive and finite (poise)");
  require(std::isfinite(options_.dt) && options_.dt > 0.0, "fluid.dt", options_.dt, "must be positive and finite (s)");
  bool fourier_possible = FourierSolver::applies(ops_.scalar_box());
  for (int a = 0; a < grid_.dims; ++a) fourier_possible = fourier_possible && FourierSolver::applies(ops_.component_box(a));
  if (options_.solvers == FluidSolvers::fourier)
    require(fourier_possible, "fluid.solvers", to_string(options_.solvers),
            "needs x and z periodic (y periodic or walls); this grid has walls across x or z");
  fourier_ = options_.solvers == FluidSolvers::fourier || (options_.solvers == FluidSolvers::automatic && fourier_possible);
  if (parts_)
    require(fourier_, "fluid.solvers", to_string(options_.solvers),
            "a fluid split among processes needs the Fourier solvers (x and z periodic); the multigrid path runs on "
            "one process only");
  if (fourier_) {
    for (int a = 0; a < grid_.dims; ++a) fourier_laplacians_.emplace_back(ops_.component_box(a), Correction::appendix_a);
    fourier_laplacians_.emplace_back(ops_.scalar_box(), Correction::none);
  }
  helmholtz_.push_back(make_helmholtz(options_.dt));
  if (fourier_)
    fourier_poisson_ = make_fourier(ops_.scalar_box(), Correction::none, 0.0, -1.0, options_.poisson.solver.name);
  else
    poisson_ = std::make_unique<PoissonSolver>(ops_.scalar_box(), options_.poisson);
}

DirectSolve NavierStokesSolver::make_fourier(const Box& box, Correction correction, double alpha, double beta,
                                             const std::string& name) const {
  if (parts_) return parts_->fourier(box, correction, alpha, beta, name);
  auto solver = std::make_shared<const FourierSolver>(box, correction, alpha, beta, name);
  return [solver](const dvec& b, dvec& x) { solver->solve(b, x); };
}

const char* to_string(FluidSolvers solvers) {
  switch (solvers) {
    case FluidSolvers::automatic: return "automatic";
    case FluidSolvers::multigrid: return "multigrid";
    case FluidSolvers::fourier: return "fourier";
  }
  return "?";
}

NavierStokesSolver::HelmholtzSet NavierStokesSolver::make_helmholtz(double dt) const {
  const double nu = fluid_.viscosity / fluid_.density;
  // Backward Euler: c = dt nu; Peskin: both stages have c = (dt/2) nu.
  const double c = (options_.integrator == TimeIntegrator::backward_forward_euler ? 1.0 : 0.5) * dt * nu;
  HelmholtzSet set;
  set.dt = dt;
  for (int a = 0; a < grid_.dims; ++a) {
    const std::string name = options_.helmholtz.solver.name + " u" + std::to_string(a);
    if (fourier_) {
      set.fourier[a] = make_fourier(ops_.component_box(a), Correction::appendix_a, 1.0, -c, name);
    } else {
      HelmholtzOptions h = options_.helmholtz;
      h.solver.name = name;
      set.multigrid[a] = std::make_unique<HelmholtzSolver>(ops_.component_box(a), c, h);
    }
  }
  return set;
}

void NavierStokesSolver::set_dt(double dt) {
  require(std::isfinite(dt) && dt > 0.0, "fluid.dt", dt, "must be positive and finite (s)");
  options_.dt = dt;
  for (std::size_t k = 0; k < helmholtz_.size(); ++k)
    if (helmholtz_[k].dt == dt) {
      current_ = k;
      return;
    }
  helmholtz_.push_back(make_helmholtz(dt));
  current_ = helmholtz_.size() - 1;
}

const HelmholtzSolver& NavierStokesSolver::helmholtz(int a) const {
  require(!fourier_, "NavierStokesSolver::helmholtz", a, "the iterative solvers exist on the multigrid path only");
  return *helmholtz_[current_].multigrid[a];
}

const PoissonSolver& NavierStokesSolver::poisson() const {
  require(!fourier_, "NavierStokesSolver::poisson", "fourier", "the iterative solvers exist on the multigrid path only");
  return *poisson_;
}

const StaggeredLaplacian& NavierStokesSolver::velocity_laplacian(int a) const {
  return fourier_ ? fourier_laplacians_[a] : helmholtz_[current_].multigrid[a]->laplacian();
}

const StaggeredLaplacian& NavierStokesSolver::pressure_laplacian() const {
  return fourier_ ? fourier_laplacians_.back() : poisson_->laplacian();
}

FluidState NavierStokesSolver::zero_state(double t) const {
  FluidState s;
  s.u = zero_vector_field(grid_);
  s.p = dvec(ops_.scalar_box().size(), 0.0);
  s.phi[0] = s.phi[1] = dvec(ops_.scalar_box().size(), 0.0);
  s.t = t;
  return s;
}

double NavierStokesSolver::force_time(double t) const {
  return options_.integrator == TimeIntegrator::backward_forward_euler ? t + options_.dt : t + 0.5 * options_.dt;
}

const VelocityBoundaryData& NavierStokesSolver::boundary_data(double t) const {
  for (auto& entry : cache_)
    if (entry.first == t) return entry.second;
  VelocityBoundaryData data;
  if (boundary_) {
    const BoundaryVelocity& b = boundary_;
    data = sample_velocity_boundary(grid_, [&](int a, int d, int side, double x, double y, double z) {
      return b(a, d, side, t, x, y, z);
    });
  } else {
    data = zero_velocity_boundary(grid_);
  }
  const double shift = ops_.make_compatible(data);
  // On a process's part the walls' outflow is a partial sum: only data without one is exact. Agreed
  // by all processes (one that refused alone would leave the others in the next exchange).
  require(!parts_ || parts_->all(shift == 0.0), "fluid.boundary (normal wall velocity)", shift,
          "must be zero on a fluid split among processes");
  if (cache_.size() >= 4) cache_.erase(cache_.begin());
  cache_.emplace_back(t, std::move(data));
  return cache_.back().second;
}

double NavierStokesSolver::max_divergence(const FluidState& state) const {
  dvec div;
  ops_.divergence(state.u, &boundary_data(state.t), div);
  return parts_ ? parts_->max_abs(div) : blas::norm_inf(div);
}

void NavierStokesSolver::stage(const dvec& p_in, const dvec& phi_in, VectorField& u, dvec& p, dvec& phi,
                               const VectorField& u_src, double t_src, const VectorField& u_adv, double t_adv, double k,
                               double theta, const VectorField* f, StepStats& stats, int s) {
  const int dims = grid_.dims;
  const double rho = fluid_.density, mu = fluid_.viscosity, nu = mu / rho;
  const double t_new = t_src + k;

  auto t0 = clock_type::now();
  ops_.advection(u_adv, boundary_data(t_adv), adv_);
  stats.seconds_advection += seconds_since(t0);

  t0 = clock_type::now();
  ops_.gradient(p_in, gp_);
  // gamma*: the data at t_new, plus the lagged slip G phi on tangential components at no-slip walls.
  VelocityBoundaryData gstar = boundary_data(t_new);
  require(index_t(phi_in.size()) == ops_.scalar_box().size(), "fluid.state.phi.size", phi_in.size(), "does not match the MAC grid");
  for (int a = 0; a < dims; ++a)
    for (int d = 0; d < dims; ++d) {
      if (d == a || grid_.periodic(d)) continue;
      for (int side = 0; side < 2; ++side) {
        if ((side ? grid_.upper[d] : grid_.lower[d]) != MacBoundary::dirichlet) continue;
        dvec& g = gstar[a].face[d][side];
        for_each_index(index_t(g.size()), kernels::AddFaceGradient{shape_of(ops_.component_box(a)), shape_of(ops_.scalar_box()), a, d,
                                                                   side, 1.0 / grid_.h(a), ptr(phi_in), ptr(g)});
      }
    }
  const VelocityBoundaryData& gsrc = boundary_data(t_src);
  for (int a = 0; a < dims; ++a) {
    const StaggeredLaplacian& L = velocity_laplacian(a);
    const index_t n = L.size();
    // tmp = k (f / rho - G p / rho - N)
    dvec& src = tmp_[a];
    src.resize(n);
    if (f)
      require(index_t((*f)[a].size()) == n, "fluid.force[" + std::to_string(a) + "].size", (*f)[a].size(),
              "does not match velocity component " + std::to_string(a));
    for_each_index(n, StageSource{f ? ptr((*f)[a]) : nullptr, ptr(gp_[a]), ptr(adv_[a]), k, 1.0 / rho, ptr(src)});
    L.apply_identity(src, rhs_[a]);  // I~ k (...)
    L.apply(u_src[a], ustar_[a], 1.0, (1.0 - theta) * k * nu);
    blas::axpy(1.0, ustar_[a], rhs_[a]);
    if (theta < 1.0) L.add_boundary(gsrc[a], rhs_[a], (1.0 - theta) * k * nu);
    L.add_boundary(gstar[a], rhs_[a], theta * k * nu);
  }
  stats.seconds_other += seconds_since(t0);

  t0 = clock_type::now();
  for (int a = 0; a < dims; ++a) {
    if (fourier_) {
      helmholtz_[current_].fourier[a](rhs_[a], ustar_[a]);
      continue;
    }
    ustar_[a] = u_src[a];  // initial guess
    stats.helmholtz_iterations[s][a] = helmholtz_[current_].multigrid[a]->solve(rhs_[a], ustar_[a]).iterations;
  }
  stats.seconds_helmholtz += seconds_since(t0);

  // Projection (PmII): -L q = -D u* / k, u = u* - k G q, p += rho q - theta k mu L q.
  t0 = clock_type::now();
  ops_.divergence(ustar_, &gstar, div_);
  for_each_index(index_t(div_.size()), Scaled{ptr(div_), -1.0 / k, ptr(div_)});  // -D u* / k
  stats.seconds_projection += seconds_since(t0);

  t0 = clock_type::now();
  if (fourier_) {
    fourier_poisson_(div_, q_);
  } else {
    if (q_.size() != div_.size()) q_.assign(div_.size(), 0.0);
    // initial guess: the last pseudo-pressure, phi / k
    for_each_index(index_t(q_.size()), Scaled{ptr(phi_in), 1.0 / k, ptr(q_)});
    stats.poisson_iterations[s] = poisson_->solve(div_, q_).iterations;
  }
  stats.seconds_poisson += seconds_since(t0);

  t0 = clock_type::now();
  ops_.gradient(q_, gp_);
  for (int a = 0; a < dims; ++a) {
    u[a] = ustar_[a];
    blas::axpy(-k, gp_[a], u[a]);
  }
  pressure_laplacian().apply(q_, lq_);
  if (&p != &p_in) p = p_in;
  blas::axpy(rho, q_, p);
  blas::axpy(-theta * k * mu, lq_, p);
  phi.resize(q_.size());
  for_each_index(index_t(q_.size()), Scaled{ptr(q_), k, ptr(phi)});  // phi = k q (q came back filled)
  if (parts_) {  // u and p on the ghost planes: from their owners (the stencils' last plane wrapped)
    for (int a = 0; a < dims; ++a) parts_->fill(u[a]);
    parts_->fill(p);
  }
  stats.seconds_projection += seconds_since(t0);
  ++stats.stages;
}

StepStats NavierStokesSolver::step(FluidState& state, const VectorField* f) {
  StepStats stats = step(state, spare_, f);
  std::swap(state, spare_);
  return stats;
}

StepStats NavierStokesSolver::step(const FluidState& from, FluidState& to, const VectorField* f) {
  require(&from != &to, "fluid.step", "the same state", "must write the new state into another one than it reads");
  for (int a = 0; a < grid_.dims; ++a)
    require(index_t(from.u[a].size()) == ops_.component_box(a).size(), "fluid.state.u[" + std::to_string(a) + "].size",
            from.u[a].size(), "does not match the MAC grid");
  require(index_t(from.p.size()) == ops_.scalar_box().size(), "fluid.state.p.size", from.p.size(),
          "does not match the MAC grid");
  // phi of a fresh state is empty: zero (no lagged correction yet).
  const dvec zero_phi = from.phi[0].size() == from.p.size() && from.phi[1].size() == from.p.size()
                            ? dvec() : dvec(from.p.size(), 0.0);
  auto phi_of = [&](int s) -> const dvec& { return index_t(from.phi[s].size()) == ops_.scalar_box().size() ? from.phi[s] : zero_phi; };
  StepStats stats;
  const double t = from.t, dt = options_.dt;
  if (options_.integrator == TimeIntegrator::backward_forward_euler) {
    stage(from.p, phi_of(0), to.u, to.p, to.phi[0], from.u, t, from.u, t, dt, 1.0, f, stats, 0);
    to.phi[1] = phi_of(1);  // carried unchanged (one stage)
  } else {
    stage(from.p, phi_of(0), u_half_, to.p, to.phi[0], from.u, t, from.u, t, 0.5 * dt, 1.0, f, stats, 0);  // u^{n+1/2}
    stage(to.p, phi_of(1), to.u, to.p, to.phi[1], from.u, t, u_half_, t + 0.5 * dt, dt, 0.5, f, stats, 1);
  }
  to.t = t + dt;
  int bad = -1;
  for (int a = grid_.dims - 1; a >= 0; --a)
    if (!blas::all_finite(to.u[a])) bad = a;
  if (parts_ && !parts_->all(bad < 0) && bad < 0) bad = 3;  // finite here, not on another process
  if (bad >= 0)
    throw NumericalError(Cause::non_finite, "fluid step at t = " + to_text(t) + ": velocity " +
                         (bad < 3 ? "component " + std::to_string(bad) : std::string("on another process")) +
                         " is not finite (NaN or Inf); limit: finite values");
  auto t0 = clock_type::now();
  stats.max_divergence = max_divergence(to);
  stats.seconds_other += seconds_since(t0);
  return stats;
}

}  // namespace rbfib
