#pragma once
// Verification of the Navier-Stokes solver against an exact solution (exact_solutions.hpp): a
// problem is a grid, a fluid, the exact velocity (and pressure, body force, wall velocities) and a
// time interval; a run starts from the exact data at t0, steps to t1 with one integrator and step,
// and reports the relative errors at t1, the divergence after projection and the iteration counts.
#include "rbfib/fluid/navier_stokes.hpp"

#include <functional>
#include <string>

namespace rbfib {

using ExactField = std::function<double(int, double, double, double, double)>;  ///< (a, t, x, y, z)
using ExactScalar = std::function<double(double, double, double, double)>;     ///< (t, x, y, z)

struct ExactProblem {
  std::string name;
  MacGrid grid;
  FluidParameters fluid;
  ExactField velocity;   ///< exact velocity
  ExactScalar pressure;  ///< exact pressure (initial data); empty: zero
  ExactField force;      ///< body force; empty: none
  BoundaryVelocity boundary;
  double t0 = 0.0, t1 = 0.0;
  bool from_rest = false;  ///< start from u = 0 instead of the exact velocity at t0
};

struct ExactRun {
  VectorField u;           ///< final velocity
  int steps = 0;
  double err_inf = 0;      ///< max |u - u_exact| / max |u_exact| at t1
  double err_l2 = 0;       ///< ||u - u_exact||_2 / ||u_exact||_2 at t1
  double seconds = 0;      ///< wall time of all steps (solver only, not the exact data)
  double max_div_rel = 0;  ///< max over steps of max |D u| h_min / max |u|
  double max_div = 0;      ///< max over steps of max |D u| (1/s)
  double helmholtz_iterations = 0;  ///< mean per solve
  double poisson_iterations = 0;    ///< mean per solve
};

/// Advances `problem` from t0 to t1 with `integrator` and step dt (the solver's default solvers).
ExactRun run_exact(const ExactProblem& problem, TimeIntegrator integrator, double dt);

/// max over components of |u - v| / max |v|.
double relative_difference(const VectorField& u, const VectorField& v, int dims);

}  // namespace rbfib
