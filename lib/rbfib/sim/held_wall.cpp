#include "rbfib/sim/held_wall.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rbfib::sim {

HeldWallSet::HeldWallSet(HeldWall wall) : wall_(std::move(wall)) {
  const std::string field = name();
  require(wall_.X.size() % 3 == 0 && !wall_.X.empty(), field + ": marker positions size", wall_.X.size(), "must be a positive multiple of 3");
  require(blas::all_finite(wall_.X), field + ": marker positions", "NaN or Inf", "must be finite");
}

void HeldWallSet::locate(ib::Interaction& ib) { ib.sort(ptr(wall_.X), index_t(wall_.X.size()) / 3, at_); }

void HeldWallSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool) { interpolate_at(ib, at_, u, U_, name()); }

namespace {

/// A trial force whose response is about 1e3 cm/s (a Stokeslet's mu h u), far above the flow's own
/// velocities: the differences keep their digits.
double trial_force(const FluidStep& fluid) {
  const MacGrid& grid = fluid.grid();
  return fluid.viscosity() * std::min({grid.h(0), grid.h(1), grid.h(2)}) * 1e3;
}

/// The base of the mobility's columns: the velocity at the markers after the step without force,
/// from the current state (the fluid step is affine in its force).
dvec base_velocity(ib::Interaction& ib, FluidStep& fluid, const ib::SortedPoints& at, const std::string& name) {
  fluid.step(nullptr);
  dvec U0;
  interpolate_at(ib, at, fluid.next().u, U0, name);
  return U0;
}

VectorField zeros_like(const VectorField& shape) {
  VectorField g;
  for (int a = 0; a < 3; ++a) g[a].assign(shape[a].size(), 0.0);
  return g;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

dvec HeldWallSet::response(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, index_t column, double trial, const dvec& U0,
                           VectorField& g, VectorField& scratch) {
  dvec F(wall_.X.size(), 0.0), U;
  F[static_cast<std::size_t>(column)] = trial;
  for (int a = 0; a < 3; ++a) thrust::fill(g[a].begin(), g[a].end(), 0.0);
  spread_into(ib, algorithm, wall_.X, F, spread_, g, scratch);
  fluid.step(&g);
  interpolate_at(ib, at_, fluid.next().u, U, name());
  blas::axpy(-1.0, U0, U);
  blas::scale(1 / trial, U);
  return U;
}

linalg::LuFactors HeldWallSet::build(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, const VectorField& shape,
                                     VectorField& scratch) {
  const auto t0 = std::chrono::steady_clock::now();
  const index_t m = index_t(wall_.X.size());  // 3n unknowns
  VectorField g = zeros_like(shape);
  const dvec U0 = base_velocity(ib, fluid, at_, name());
  const double trial = trial_force(fluid);
  std::vector<double> M(static_cast<std::size_t>(m * m));
  for (index_t j = 0; j < m; ++j) {
    const dvec U = response(ib, fluid, algorithm, j, trial, U0, g, scratch);
    thrust::copy(U.begin(), U.end(), M.begin() + j * m);
  }
  linalg::LuFactors lu = linalg::lu_factor(linalg::DeviceMatrix::from_host(m, m, M.data()), (name() + ": mobility J L S").c_str());
  seconds_building_ += seconds_since(t0);
  return lu;
}

CirculantMobility HeldWallSet::build_circulant(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, const VectorField& shape,
                                               VectorField& scratch) {
  const auto t0 = std::chrono::steady_clock::now();
  const index_t n = index_t(wall_.X.size()) / 3;
  VectorField g = zeros_like(shape);
  const dvec U0 = base_velocity(ib, fluid, at_, name());
  const double trial = trial_force(fluid);
  std::array<std::vector<double>, 3> columns;
  const index_t origin = lattice_->marker[0];  // the lattice point (0, 0)
  for (int c = 0; c < 3; ++c) {
    const dvec U = response(ib, fluid, algorithm, c * n + origin, trial, U0, g, scratch);
    columns[std::size_t(c)].assign(U.begin(), U.end());
  }
  CirculantMobility mobility(*lattice_, columns);
  seconds_building_ += seconds_since(t0);
  return mobility;
}

void HeldWallSet::hold(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  if (!lattice_known_) {
    if (!wall_.dense) lattice_ = commensurate_lattice(std::vector<double>(wall_.X.begin(), wall_.X.end()), fluid.grid());
    lattice_known_ = true;
  }
  const double dt = fluid.dt();
  const bool built = lattice_ ? circulant_.count(dt) > 0 : mobility_.count(dt) > 0;
  if (!built) {
    if (lattice_)
      circulant_.emplace(dt, build_circulant(ib, fluid, algorithm, f, scratch));
    else
      mobility_.emplace(dt, build(ib, fluid, algorithm, f, scratch));
    fluid.step(&f);  // u* again, after the trial steps
  }
  // M Lambda = -J u*.
  interpolate_at(ib, at_, fluid.next().u, lambda_, name());
  blas::scale(-1.0, lambda_);
  if (lattice_) {
    std::vector<double> b(lambda_.begin(), lambda_.end());
    circulant_.at(dt).solve(b);
    thrust::copy(b.begin(), b.end(), lambda_.begin());
  } else {
    const index_t m = index_t(lambda_.size());
    linalg::lu_solve(mobility_.at(dt), linalg::Op::none, linalg::MatrixView{ptr(lambda_), m, 1, m});
  }
  if (!blas::all_finite(lambda_)) throw NumericalError(Cause::non_finite, name() + ": non-finite wall force");
  spread_into(ib, algorithm, wall_.X, lambda_, spread_, f, scratch);
}

}  // namespace rbfib::sim
