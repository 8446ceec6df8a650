#pragma once
// The Eulerian side of the coupled step (Sec. 2.4 (e)): a fluid on a MAC grid advanced by one step
// with a force density. The coupled step (sim/ib_step.hpp) sees only this interface, so one
// coupling serves every fluid:
//   NavierStokesStep     the Navier-Stokes solver of Sec. 2.1 (navier_stokes.hpp), either integrator;
//   PeriodicStokesStep   Chapter 3's periodic Stokes solver (periodic_stokes.hpp): steady
//                        (alpha = 0, the flow of the force alone, Sec. 3.3 step 4) or unsteady
//                        (backward Euler: (rho / dt) (u^{n+1} - u^n) = mu L u^{n+1} - G p + f).
//
// The state is double-buffered: step(f) writes the next state into the buffer not in use and
// leaves state() as it was; accept() swaps the two. A refused or failed step is simply not
// accepted: nothing is copied per step, and the last good state survives by construction.
// Units (CGS): u cm/s, p dyn/cm^2, f dyn/cm^3, rho g/cm^3, mu poise, t and dt s.
#include "rbfib/fluid/navier_stokes.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"

#include <array>
#include <map>
#include <memory>
#include <string>

namespace rbfib {

class FluidStep {
 public:
  virtual ~FluidStep() = default;
  /// "Navier-Stokes (Peskin's two-stage scheme)", "steady periodic Stokes", ...
  virtual std::string name() const = 0;
  virtual const MacGrid& grid() const = 0;
  virtual const MacOperators& operators() const = 0;
  virtual double density() const = 0;    ///< rho (g/cm^3): eq. 5.4 and the kinetic energy
  virtual double viscosity() const = 0;  ///< mu (poise)
  virtual double dt() const = 0;         ///< s
  /// Throws InputError naming the field on a non-positive or non-finite dt.
  virtual void set_dt(double dt) = 0;
  /// Computes the state at t + dt from state() and f into next(); state() is not touched. f may
  /// be null (no force). Throws NumericalError from a failed solve or a non-finite velocity.
  virtual StepStats step(const VectorField* f) = 0;
  /// The velocity the midpoint coupling interpolates at the end of a step, u^{n+1/2} of the last
  /// step(); InputError for a fluid without one (only Peskin's two-stage scheme has it).
  virtual const VectorField& midpoint_velocity() const;
  virtual bool has_midpoint_velocity() const { return false; }
  /// The split among processes this fluid steps one part of (decomposition.hpp); null for a
  /// fluid on one process.
  virtual const FluidDecomposition* parts() const { return nullptr; }

  /// The state at t^n (velocity, pressure, lagged corrections, time).
  const FluidState& state() const { return state_[current_]; }
  FluidState& state() { return state_[current_]; }
  /// The state the last step() computed (t^{n+1}), until accept().
  const FluidState& next() const { return state_[1 - current_]; }
  /// Makes next() the state: the two buffers swap.
  void accept() { current_ = 1 - current_; }

 protected:
  std::array<FluidState, 2> state_;
  int current_ = 0;
};

class NavierStokesStep final : public FluidStep {
 public:
  /// parts: the grid split among processes (the solver then steps this process's part).
  NavierStokesStep(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options, BoundaryVelocity boundary,
                   std::shared_ptr<const FluidDecomposition> parts = nullptr);
  std::string name() const override;
  const MacGrid& grid() const override { return ns_.grid(); }
  const MacOperators& operators() const override { return ns_.operators(); }
  double density() const override { return ns_.fluid().density; }
  double viscosity() const override { return ns_.fluid().viscosity; }
  double dt() const override { return ns_.options().dt; }
  void set_dt(double dt) override { ns_.set_dt(dt); }
  StepStats step(const VectorField* f) override { return ns_.step(state(), state_[1 - current_], f); }
  const VectorField& midpoint_velocity() const override;
  bool has_midpoint_velocity() const override { return ns_.options().integrator == TimeIntegrator::peskin_two_stage; }
  const FluidDecomposition* parts() const override { return ns_.parts(); }
  const NavierStokesSolver& solver() const { return ns_; }

 private:
  NavierStokesSolver ns_;
};

class PeriodicStokesStep final : public FluidStep {
 public:
  /// steady: alpha = 0 (the density enters only eq. 5.4); else backward Euler in time with
  /// alpha = rho / dt. Throws InputError naming the field for a grid with walls, or a non-positive
  /// density, viscosity or dt.
  PeriodicStokesStep(const MacGrid& grid, FluidParameters fluid, double dt, bool steady);
  std::string name() const override { return steady_ ? "steady periodic Stokes" : "unsteady periodic Stokes (backward Euler)"; }
  const MacGrid& grid() const override { return grid_; }
  const MacOperators& operators() const override { return solver().operators(); }
  double density() const override { return fluid_.density; }
  double viscosity() const override { return fluid_.viscosity; }
  double dt() const override { return dt_; }
  void set_dt(double dt) override;
  StepStats step(const VectorField* f) override;
  /// The mean force density the last steady step removed (dyn/cm^3; a periodic flow cannot
  /// balance a net force).
  const std::array<double, 3>& removed_mean() const { return removed_; }

 private:
  const PeriodicStokesSolver& solver() const;
  MacGrid grid_;
  FluidParameters fluid_;
  double dt_;
  bool steady_;
  mutable std::map<double, std::unique_ptr<PeriodicStokesSolver>> solvers_;  // one per alpha used
  VectorField rhs_;
  std::array<double, 3> removed_{0, 0, 0};
};

}  // namespace rbfib
