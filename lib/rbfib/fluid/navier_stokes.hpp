#pragma once
// The incompressible Navier-Stokes solver of Section 2.1 on a MAC grid:
//   rho (u_t + div(u (x) u)) = mu Lap u - grad p + f,   div u = 0          (eqs. 2.1, 2.2)
// with conservative advection (eq. 2.5), the Appendix A corrected Laplacian, and projection
// method PmII with a lagged boundary condition (eqs. 2.6-2.9). One stage with step k, implicitness
// theta (1: backward Euler, 1/2: Crank-Nicolson), source velocity u^s and advected velocity u^a:
//   (I~ - theta k nu L) u* = (I~ + (1 - theta) k nu L) u^s + k I~ [f / rho - G p / rho - N(u^a)]
//                             + (1 - theta) k nu B_h gamma(t^s) + theta k nu B_h gamma*,     (2.6)
//   gamma* = u_b(t^{new}) + G phi_lag on the tangential components at Dirichlet walls,        (2.7)
//   (phi_lag = k q of the same stage of the previous step)
//   -L q = -D u* / k  (homogeneous Neumann on walls),  u^{new} = u* - k G q,                  (2.9, 2.8)
//   p <- p + rho q - theta k mu L q,  phi_lag = k q,
// nu = mu / rho. Integrators:
//   backward_forward_euler: one stage, k = dt, theta = 1, u^s = u^a = u^n, f at t^{n+1};
//   peskin_two_stage:       stage 1: k = dt/2, theta = 1, u^s = u^a = u^n (gives u^{n+1/2});
//                           stage 2: k = dt, theta = 1/2, u^s = u^n, u^a = u^{n+1/2};
//                           f at t^{n+1/2} in both stages; p is then a midpoint pressure.
// Both stages of Peskin's scheme share the Helmholtz operator I~ - (dt/2) nu L.
//
// The pressure update: eliminating u* from the stage equations gives
// G p^{new} = G (p + rho q - theta k mu L q) up to commutator terms (Brown, Cortez & Minion 2001);
// the seed prints the update as p + (rho I + dt mu Lap) q, whose sign of the viscous part differs
// from this derivation; we use the derived sign (reference/fluid.yaml records the choice).
//
// Units (CGS): u cm/s, p dyn/cm^2, f dyn/cm^3, rho g/cm^3, mu poise, t and dt in s.
#include "rbfib/fluid/decomposition.hpp"
#include "rbfib/fluid/fourier_solver.hpp"
#include "rbfib/fluid/helmholtz.hpp"
#include "rbfib/fluid/mac_operators.hpp"
#include "rbfib/fluid/poisson.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rbfib {

enum class TimeIntegrator { backward_forward_euler, peskin_two_stage };

const char* to_string(TimeIntegrator integrator);

/// How the Helmholtz and Poisson systems of a stage are solved: multigrid-preconditioned CG
/// (any boundary combination), the direct Fourier solver (x and z periodic, y periodic or walls:
/// fourier_solver.hpp), or automatic: Fourier wherever the grid allows it, else multigrid.
enum class FluidSolvers { automatic, multigrid, fourier };

const char* to_string(FluidSolvers solvers);

struct FluidParameters {
  double density = 1.0;     ///< rho (g/cm^3)
  double viscosity = 1e-3;  ///< mu (poise)
};

struct NavierStokesOptions {
  TimeIntegrator integrator = TimeIntegrator::backward_forward_euler;
  double dt = 0.0;  ///< time step (s)
  FluidSolvers solvers = FluidSolvers::automatic;
  HelmholtzOptions helmholtz;  ///< for the multigrid path
  PoissonOptions poisson;      ///< for the multigrid path
};

/// Velocity boundary data gamma(a, d, side, t, x, y, z) for component a on face (d, side), as in
/// MacGrid::velocity_condition: the wall velocity for Dirichlet conditions, the inward normal
/// derivative for Neumann ones. Empty function: zero data.
using BoundaryVelocity = std::function<double(int, int, int, double, double, double, double)>;

struct FluidState {
  VectorField u;  ///< velocity (cm/s)
  dvec p;         ///< pressure (dyn/cm^2), cell centres
  /// k q of the last projection of each stage (cm^2/s): G phi is the lagged boundary correction of
  /// eq. 2.7 for the same stage of the next step, phi / k its initial guess.
  std::array<dvec, 2> phi;
  double t = 0.0;
};

struct StepStats {
  int stages = 0;
  std::array<std::array<int, 3>, 2> helmholtz_iterations{};  ///< 0 for a direct (Fourier) solve
  std::array<int, 2> poisson_iterations{};                    ///< 0 for a direct (Fourier) solve
  double max_divergence = 0.0;  ///< max |D u^{n+1}| after the step (1/s)
  double seconds_advection = 0.0, seconds_helmholtz = 0.0, seconds_poisson = 0.0, seconds_projection = 0.0,
         seconds_other = 0.0;
};

class NavierStokesSolver {
 public:
  /// Throws InputError naming the field on non-positive dt, density or viscosity, or a bad grid.
  /// parts: the grid split among processes (decomposition.hpp); the solver then steps this
  /// process's part, grid() is the local grid, and the direct solves are the parts' (the Fourier
  /// path only: InputError otherwise, and on walls with a normal velocity).
  NavierStokesSolver(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options,
                     BoundaryVelocity boundary = {}, std::shared_ptr<const FluidDecomposition> parts = nullptr);

  /// A state with zero velocity, pressure and phi at time t.
  FluidState zero_state(double t = 0.0) const;

  /// Advances state by one step dt. f: Eulerian force density (dyn/cm^3) at t^{n+1} (backward-
  /// forward Euler) or t^{n+1/2} (Peskin); nullptr: no force. Throws NumericalError from a solve
  /// that does not converge, naming it (state is then unchanged).
  StepStats step(FluidState& state, const VectorField* f = nullptr);
  /// The same step from `from` into `to` (another state, resized as needed; `from` is not
  /// touched): the double-buffered form, with no copy of the fields.
  StepStats step(const FluidState& from, FluidState& to, const VectorField* f = nullptr);

  /// u^{n+1/2} of the last step of Peskin's two-stage scheme (its first stage); empty before one.
  const VectorField& midpoint_velocity() const { return u_half_; }

  /// Changes the time step (s) of the following steps: the Helmholtz operators of each step size
  /// used are built once and kept, so an adaptive run that moves among a few sizes (dt = 2^k
  /// dt_min) builds each once. Throws InputError naming the field on a non-positive dt.
  void set_dt(double dt);

  /// Time at which step() expects f, for a step from time t.
  double force_time(double t) const;

  /// Boundary data at time t (sampled, then the normal data made compatible: zero net outflow).
  const VelocityBoundaryData& boundary_data(double t) const;

  /// max |D u| with the normal velocity on walls from the boundary data at state.t (1/s).
  double max_divergence(const FluidState& state) const;

  const MacOperators& operators() const { return ops_; }
  const MacGrid& grid() const { return grid_; }
  const FluidParameters& fluid() const { return fluid_; }
  const NavierStokesOptions& options() const { return options_; }
  /// Whether the stages use the direct Fourier solvers (else multigrid-preconditioned CG).
  bool fourier() const { return fourier_; }
  /// The split this solver steps one part of; null on one process.
  const FluidDecomposition* parts() const { return parts_.get(); }
  /// The iterative solvers; only on the multigrid path (InputError otherwise).
  const HelmholtzSolver& helmholtz(int a) const;
  const PoissonSolver& poisson() const;

 private:
  /// One stage: from the pressure p_in and the lagged phi_in into u, p (which may be p_in) and phi.
  void stage(const dvec& p_in, const dvec& phi_in, VectorField& u, dvec& p, dvec& phi, const VectorField& u_src,
             double t_src, const VectorField& u_adv, double t_adv, double k, double theta, const VectorField* f,
             StepStats& stats, int s);

  MacGrid grid_;
  FluidParameters fluid_;
  NavierStokesOptions options_;
  BoundaryVelocity boundary_;
  MacOperators ops_;
  bool fourier_ = false;
  std::shared_ptr<const FluidDecomposition> parts_;
  /// The velocity systems of one step size (multigrid or Fourier, per component).
  struct HelmholtzSet {
    double dt = 0;
    std::array<std::unique_ptr<HelmholtzSolver>, 3> multigrid;
    std::array<DirectSolve, 3> fourier;
  };
  DirectSolve make_fourier(const Box& box, Correction correction, double alpha, double beta, const std::string& name) const;
  HelmholtzSet make_helmholtz(double dt) const;
  std::vector<HelmholtzSet> helmholtz_;  // one per step size used; current_ is in use
  std::size_t current_ = 0;
  std::unique_ptr<PoissonSolver> poisson_;
  DirectSolve fourier_poisson_;
  std::vector<StaggeredLaplacian> fourier_laplacians_;  // Fourier path: per component, then the scalar box
  const StaggeredLaplacian& velocity_laplacian(int a) const;
  const StaggeredLaplacian& pressure_laplacian() const;
  mutable std::vector<std::pair<double, VelocityBoundaryData>> cache_;
  // workspace
  VectorField adv_, gp_, rhs_, ustar_, tmp_, u_half_;
  FluidState spare_;  // the other buffer of the in-place step
  dvec div_, q_, lq_;
};

}  // namespace rbfib
