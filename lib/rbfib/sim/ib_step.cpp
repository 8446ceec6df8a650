#include "rbfib/sim/ib_step.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <thrust/copy.h>
#include <thrust/find.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace rbfib::sim {

namespace {
using clock_type = std::chrono::steady_clock;
double seconds_since(clock_type::time_point& t0) {
  synchronize();
  const auto t1 = clock_type::now();
  const double s = std::chrono::duration<double>(t1 - t0).count();
  t0 = t1;
  return s;
}
/// Index of the first entry that is NaN or Inf, or -1.
index_t first_non_finite(const dvec& x) {
  const auto bad = thrust::find_if(x.begin(), x.end(), [] RBFIB_HD (double v) { return !((v - v) == 0.0); });
  return bad == x.end() ? -1 : index_t(bad - x.begin());
}

std::array<Box, 3> component_boxes(const MacOperators& ops) {
  return {ops.component_box(0), ops.component_box(1), ops.component_box(2)};
}
}  // namespace

const char* to_string(Coupling c) { return c == Coupling::seed ? "seed (a)-(g), first order" : "midpoint, second order"; }

ImmersedBoundary::ImmersedBoundary(const MacGrid& grid, FluidParameters fluid, NavierStokesOptions options,
                                   BoundaryVelocity boundary, IbOptions ib)
    : ns_(grid, fluid, std::move(options), std::move(boundary)),
      ib_(component_boxes(ns_.operators()), ib.kernel),
      options_(std::move(ib)) {
  require(grid.dims == 3, "grid.dims", grid.dims, "the immersed-boundary step needs a 3D grid");
  require(options_.coupling == Coupling::seed || ns_.options().integrator == TimeIntegrator::peskin_two_stage,
          "ib.coupling", to_string(options_.coupling), "needs Peskin's two-stage fluid scheme (its midpoint velocity)");
  state_ = ns_.zero_state(0.0);
}

index_t ImmersedBoundary::add(cells::Batch batch) {
  batches_.push_back(Entry{std::move(batch), {}, {}, {}, {}});
  return index_t(batches_.size()) - 1;
}

index_t ImmersedBoundary::add(TetheredPoints p) {
  const std::string field = "tethered points '" + p.name + "'";
  require(p.X.size() % 3 == 0 && !p.X.empty(), field + ": positions size", p.X.size(), "must be a positive multiple of 3");
  require(p.anchors.size() == p.X.size(), field + ": anchors size", p.anchors.size(), "must equal the positions' size");
  require(std::isfinite(p.k) && p.k >= 0, field + ": spring constant k (dyn/cm)", p.k, "must be finite and >= 0");
  require(std::isfinite(p.eta) && p.eta >= 0, field + ": damping eta (dyn s/cm)", p.eta, "must be finite and >= 0");
  require(first_non_finite(p.X) < 0 && first_non_finite(p.anchors) < 0, field + ": positions and anchors", "NaN or Inf",
          "must be finite");
  points_.push_back(PointEntry{std::move(p), {}, {}, {}});
  return index_t(points_.size()) - 1;
}

void ImmersedBoundary::positions_of(Entry& e, dvec& X) const {
  const index_t nd = e.batch.type().n_data(), N = e.batch.size(), n = 3 * N * nd;
  X.resize(static_cast<std::size_t>(n));
  thrust::copy(e.batch.state().storage().begin(), e.batch.state().storage().begin() + n, X.begin());
  const index_t k = first_non_finite(X);
  if (k >= 0) {
    const index_t c = (k % (N * nd)) / nd;
    throw NumericalError("cell type '" + e.batch.type().name() + "', cell " + to_text(c) + ": non-finite position at data site " +
                         to_text(k % nd) + " (coordinate " + "xyz"[k / (N * nd)] + ")");
  }
}

void ImmersedBoundary::interpolate_at(const dvec& X, Entry& e) {
  ib_.interpolate(X, state_.u, e.U, options_.interpolation);
  const index_t n = 3 * e.batch.size() * e.batch.type().n_data();
  if (!blas::all_finite(e.U))
    throw NumericalError("cell type '" + e.batch.type().name() + "': non-finite interpolated velocity");
  thrust::copy(e.U.begin(), e.U.end(), e.batch.state().storage().begin() + n);  // the velocity block
}

IbStepReport ImmersedBoundary::step() {
  IbStepReport r;
  const double dt = ns_.options().dt;
  const double t = state_.t;
  // Keep X^n and U at the start: the whole Lagrangian state is restored on failure.
  std::vector<dvec> saved(batches_.size()), saved_points(points_.size());
  for (std::size_t b = 0; b < batches_.size(); ++b) saved[b] = batches_[b].batch.state().storage();
  for (std::size_t q = 0; q < points_.size(); ++q) saved_points[q] = points_[q].points.X;
  bool fluid_stepped = false;
  try {
    auto t0 = clock_type::now();
    // (a) U^n = I u^n at X^n; (b) X* = X^n + dt U^n (midpoint: X^{n+1/2} = X^n + dt/2 U^n).
    const bool midpoint = options_.coupling == Coupling::midpoint;
    for (Entry& e : batches_) {
      positions_of(e, e.X0);
      interpolate_at(e.X0, e);
      e.X = e.X0;
      blas::axpy(midpoint ? 0.5 * dt : dt, e.U, e.X);
      thrust::copy(e.X.begin(), e.X.end(), e.batch.state().storage().begin());
    }
    for (PointEntry& q : points_) {
      TetheredPoints& P = q.points;
      q.X0 = P.X;
      ib_.interpolate(q.X0, state_.u, q.U, options_.interpolation);
      if (!blas::all_finite(q.U)) throw NumericalError("tethered points '" + P.name + "': non-finite interpolated velocity");
      blas::axpy(midpoint ? 0.5 * dt : dt, q.U, P.X);
      // F = -k (X* - X') - eta U^n, per point.
      q.F = P.X;
      blas::axpy(-1.0, P.anchors, q.F);
      blas::xpby(dvec(q.F.size(), 0.0), -P.k, q.F);
      blas::axpy(-P.eta, q.U, q.F);
    }
    r.seconds_interpolation += seconds_since(t0);
    // (c) F^{n+1} at X* (sample sites), with U^n for dissipation.
    for (Entry& e : batches_) {
      cells::compute_forces(e.batch, e.forces);
      r.elastic_energy += e.forces.energy;
    }
    r.seconds_forces = seconds_since(t0);
    // (d) f^{n+1} = S F^{n+1} from the sample sites of X*, summed over batches.
    for (int a = 0; a < 3; ++a)
      f_[a].assign(static_cast<std::size_t>(ns_.operators().component_box(a).size()), options_.body_force[a]);
    for (Entry& e : batches_) {
      ib_.spread(e.forces.positions.storage(), e.forces.force.storage(), f_batch_, options_.spreading);
      for (int a = 0; a < 3; ++a) blas::axpy(1.0, f_batch_[a], f_[a]);
    }
    for (PointEntry& q : points_) {
      ib_.spread(q.points.X, q.F, f_batch_, options_.spreading);
      for (int a = 0; a < 3; ++a) blas::axpy(1.0, f_batch_[a], f_[a]);
    }
    r.seconds_spreading = seconds_since(t0);
    // Eq. 5.4: dt <= (1/4) sqrt(h rho / ||f||_inf).
    for (int a = 0; a < 3; ++a) r.max_force_density = std::max(r.max_force_density, blas::norm_inf(f_[a]));
    const MacGrid& g = ns_.grid();
    const double h = std::min({g.h(0), g.h(1), g.h(2)});
    r.dt_bound = r.max_force_density > 0 ? 0.25 * std::sqrt(h * ns_.fluid().density / r.max_force_density)
                                         : std::numeric_limits<double>::infinity();
    if (!std::isfinite(r.max_force_density))
      throw NumericalError("non-finite spread force density");
    if (options_.stopping_condition && dt > r.dt_bound)
      throw NumericalError("stopping condition (eq. 5.4) violated: ||f||_inf = " + to_text(r.max_force_density) +
                           " dyn/cm^3, dt = " + to_text(dt) + " s > (1/4) sqrt(h rho / ||f||_inf) = " + to_text(r.dt_bound) + " s");
    // (e) the fluid step.
    backup_ = state_;
    fluid_stepped = true;
    r.fluid = ns_.step(state_, &f_);
    for (int a = 0; a < 3; ++a)
      if (!blas::all_finite(state_.u[a])) throw NumericalError("non-finite fluid velocity (component " + to_text(a) + ")");
    r.seconds_fluid = seconds_since(t0);
    const MacGrid& grid = ns_.grid();
    const double cell_volume = grid.h(0) * grid.h(1) * grid.h(2);
    for (int a = 0; a < 3; ++a) {
      r.max_velocity = std::max(r.max_velocity, blas::norm_inf(state_.u[a]));
      r.kinetic_energy += 0.5 * ns_.fluid().density * blas::dot(state_.u[a], state_.u[a]) * cell_volume;
    }
    // (f) U^{n+1} = I u^{n+1} at X^n (midpoint: U^{n+1/2} = I u^{n+1/2} at X^{n+1/2});
    // (g) X^{n+1} = X^n + dt U.
    for (Entry& e : batches_) {
      if (midpoint) {
        ib_.interpolate(e.X, ns_.midpoint_velocity(), e.U, options_.interpolation);
        if (!blas::all_finite(e.U))
          throw NumericalError("cell type '" + e.batch.type().name() + "': non-finite interpolated velocity");
        thrust::copy(e.U.begin(), e.U.end(), e.batch.state().storage().begin() + index_t(e.X.size()));
      } else {
        interpolate_at(e.X0, e);
      }
      e.X = e.X0;
      blas::axpy(dt, e.U, e.X);
      thrust::copy(e.X.begin(), e.X.end(), e.batch.state().storage().begin());
    }
    for (PointEntry& q : points_) {
      TetheredPoints& P = q.points;
      if (midpoint)
        ib_.interpolate(P.X, ns_.midpoint_velocity(), q.U, options_.interpolation);
      else
        ib_.interpolate(q.X0, state_.u, q.U, options_.interpolation);
      if (!blas::all_finite(q.U)) throw NumericalError("tethered points '" + P.name + "': non-finite interpolated velocity");
      P.X = q.X0;
      blas::axpy(dt, q.U, P.X);
    }
    r.seconds_interpolation += seconds_since(t0);
  } catch (const std::exception& ex) {
    for (std::size_t b = 0; b < batches_.size(); ++b) batches_[b].batch.state().storage() = saved[b];
    for (std::size_t q = 0; q < points_.size(); ++q) points_[q].points.X = saved_points[q];
    if (fluid_stepped) state_ = backup_;
    throw NumericalError("immersed-boundary step " + to_text(steps_) + " at t = " + to_text(t) + " s: " + ex.what() +
                         " (the state before this step is kept)");
  }
  ++steps_;
  return r;
}

}  // namespace rbfib::sim
