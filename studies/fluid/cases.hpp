#pragma once
// The verification problems of the `fluid` study and the runner that advances one of them with one
// integrator and reports errors, divergence, iteration counts and wall time.
#include "rbfib/fluid/exact_solutions.hpp"
#include "rbfib/fluid/navier_stokes.hpp"

#include <functional>
#include <string>

namespace rbfib::study {

using Field = std::function<double(int, double, double, double, double)>;  // (a, t, x, y, z)
using Scalar = std::function<double(double, double, double, double)>;      // (t, x, y, z)

struct Problem {
  std::string name;
  MacGrid grid;
  FluidParameters fluid;
  Field velocity;     ///< exact velocity
  Scalar pressure;    ///< exact pressure (initial data), empty: zero
  Field force;        ///< body force, empty: none
  BoundaryVelocity boundary;
  double t0 = 0.0, t1 = 0.0;
  bool from_rest = false;  ///< start from u = 0 instead of the exact velocity at t0
};

struct RunResult {
  VectorField u;       ///< final velocity
  int steps = 0;
  double err_inf = 0;  ///< max |u - u_exact| / max |u_exact| at t1
  double err_l2 = 0;   ///< ||u - u_exact||_2 / ||u_exact||_2 at t1
  double seconds = 0;  ///< wall time of all steps (solver only, not the exact data)
  double max_div_rel = 0;  ///< max over steps of max|D u| h_min / max|u|
  double max_div = 0;      ///< max over steps of max|D u| (1/s)
  double helmholtz_iterations = 0;  ///< mean per solve
  double poisson_iterations = 0;    ///< mean per solve
};

/// Taylor-Green vortex on the periodic box [0, L]^2 x [0, Lz], cells n x n x nz.
Problem taylor_green(int n, int nz);
/// Start-up Couette flow in the whole-blood channel (16 x 12 x 16 um), cells nxz x ny x nxz.
Problem couette(int ny, int nxz);
/// Manufactured flow on [0, 1]^3 cm, periodic x, no-slip (moving) walls in y and z, n^3 cells.
Problem manufactured(int n);

RunResult run(const Problem& problem, TimeIntegrator integrator, double dt);

/// max over components of |u - v| / max |v|
double relative_difference(const VectorField& u, const VectorField& v, int dims);

}  // namespace rbfib::study
