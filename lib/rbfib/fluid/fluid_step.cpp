#include "rbfib/fluid/fluid_step.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <cmath>

namespace rbfib {

const VectorField& FluidStep::midpoint_velocity() const {
  throw InputError("ib.coupling", "midpoint", "needs a fluid with a midpoint velocity (Peskin's two-stage scheme), not " + name());
}

// ---- Navier-Stokes --------------------------------------------------------------------------

NavierStokesStep::NavierStokesStep(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options,
                                   BoundaryVelocity boundary, std::shared_ptr<const FluidDecomposition> parts)
    : ns_(grid, fluid, std::move(options), std::move(boundary), std::move(parts)) {
  state_[0] = ns_.zero_state(0.0);
}

std::string NavierStokesStep::name() const { return std::string("Navier-Stokes (") + to_string(ns_.options().integrator) + ")"; }

const VectorField& NavierStokesStep::midpoint_velocity() const {
  if (!has_midpoint_velocity()) return FluidStep::midpoint_velocity();
  return ns_.midpoint_velocity();
}

// ---- periodic Stokes ------------------------------------------------------------------------

PeriodicStokesStep::PeriodicStokesStep(const MacGrid& grid, FluidParameters fluid, double dt, bool steady)
    : grid_(grid), fluid_(fluid), dt_(dt), steady_(steady) {
  require(std::isfinite(fluid.density) && fluid.density > 0, "fluid.density", fluid.density, "must be positive and finite (g/cm^3)");
  set_dt(dt);
  FluidState& s = state();
  s.u = zero_vector_field(grid_);
  s.p = dvec(solver().operators().scalar_box().size(), 0.0);
  s.t = 0;
}

void PeriodicStokesStep::set_dt(double dt) {
  require(std::isfinite(dt) && dt > 0, "fluid.dt", dt, "must be positive and finite (s)");
  dt_ = dt;
  solver();  // built now: bad input is refused here, not at the first step
}

const PeriodicStokesSolver& PeriodicStokesStep::solver() const {
  const double alpha = steady_ ? 0.0 : fluid_.density / dt_;
  auto it = solvers_.find(alpha);
  if (it == solvers_.end()) it = solvers_.emplace(alpha, std::make_unique<PeriodicStokesSolver>(grid_, fluid_.viscosity, alpha)).first;
  return *it->second;
}

StepStats PeriodicStokesStep::step(const VectorField* f) {
  const FluidState& from = state();
  FluidState& to = state_[1 - current_];
  const PeriodicStokesSolver& S = solver();
  StepStats stats;
  stats.stages = 1;
  VectorField zero;
  if (!f) {
    zero = zero_vector_field(grid_);
    f = &zero;
  }
  if (steady_) {
    removed_ = S.solve(*f, to.u, to.p);
  } else {
    // (alpha - mu L) u^{n+1} + G p = f + alpha u^n, alpha = rho / dt (D u^n = 0: the pressure is f's).
    for (int a = 0; a < 3; ++a) {
      rhs_[a] = (*f)[a];
      blas::axpy(S.alpha(), from.u[a], rhs_[a]);
    }
    S.solve(rhs_, to.u, to.p);
  }
  to.t = from.t + dt_;
  for (int a = 0; a < 3; ++a)
    if (!blas::all_finite(to.u[a]))
      throw NumericalError(Cause::non_finite, name() + " at t = " + to_text(from.t) + ": velocity component " + to_text(a) +
                                                  " is not finite (NaN or Inf)");
  return stats;
}

}  // namespace rbfib
