#include "rbfib/sim/held_wall.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rbfib::sim {

HeldWallSet::HeldWallSet(HeldWall wall, const FluidDecomposition* parts) : wall_(std::move(wall)), parts_(parts) {
  const std::string field = name();
  require(wall_.X.size() % 3 == 0 && !wall_.X.empty(), field + ": marker positions size", wall_.X.size(), "must be a positive multiple of 3");
  require(blas::all_finite(wall_.X), field + ": marker positions", "NaN or Inf", "must be finite");
  const std::vector<double> X(wall_.X.begin(), wall_.X.end());
  const std::size_t n = X.size() / 3;
  for (std::size_t k = 0; k < n; ++k)
    if (!parts_ || parts_->owner(X[std::size_t(parts_->split_axis()) * n + k]) == parts_->process()) mine_.push_back(index_t(k));
  X_mine_ = points_at(wall_.X, mine_);
}

void HeldWallSet::locate(ib::Interaction& ib) { ib.sort(ptr(X_mine_), index_t(mine_.size()), at_); }

void HeldWallSet::interpolate_end(ib::Interaction& ib, const VectorField& u, bool) { interpolate_at(ib, at_, u, U_, name()); }

namespace {

/// A trial force whose response is about 1e3 cm/s (a Stokeslet's mu h u), far above the flow's own
/// velocities: the differences keep their digits.
double trial_force(const FluidStep& fluid) {
  const MacGrid& grid = fluid.grid();
  return fluid.viscosity() * std::min({grid.h(0), grid.h(1), grid.h(2)}) * 1e3;
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

dvec HeldWallSet::velocity_at_markers(ib::Interaction& ib, const VectorField& u) {
  dvec U;
  if (!parts_) {
    interpolate_at(ib, at_, u, U, name());
    return U;
  }
  for (int a = 0; a < 3; ++a) parts_->widen(u[a], wide_[a]);
  agreed(parts_, [&] { interpolate_at(ib, at_, wide_, U, name()); });
  return whole_points(*parts_, U, mine_, index_t(wall_.X.size()) / 3);
}

void HeldWallSet::spread_forces(ib::Interaction& ib, ib::Spreading algorithm, const dvec& F, VectorField& f, VectorField& scratch) {
  if (!parts_) return spread_into(ib, algorithm, wall_.X, F, spread_, f, scratch);
  const dvec mine = points_at(F, mine_);
  const MacGrid& g = parts_->lagrangian_grid();
  for (int a = 0; a < 3; ++a) wide_[a].assign(static_cast<std::size_t>(g.component(a).size()), 0.0);
  agreed(parts_, [&] { spread_into(ib, algorithm, X_mine_, mine, spread_, wide_, scratch); });
  for (int a = 0; a < 3; ++a) {
    parts_->narrow_sum(wide_[a], narrow_[a]);
    blas::axpy(1.0, narrow_[a], f[a]);
  }
}

dvec HeldWallSet::base_velocity(ib::Interaction& ib, FluidStep& fluid) {
  fluid.step(nullptr);
  return velocity_at_markers(ib, fluid.next().u);
}

dvec HeldWallSet::response(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, index_t column, double trial, const dvec& U0,
                           VectorField& g, VectorField& scratch) {
  dvec F(wall_.X.size(), 0.0);
  F[static_cast<std::size_t>(column)] = trial;
  for (int a = 0; a < 3; ++a) thrust::fill(g[a].begin(), g[a].end(), 0.0);
  spread_forces(ib, algorithm, F, g, scratch);
  fluid.step(&g);
  dvec U = velocity_at_markers(ib, fluid.next().u);
  blas::axpy(-1.0, U0, U);
  blas::scale(1 / trial, U);
  return U;
}

linalg::LuFactors HeldWallSet::build(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, const VectorField& shape,
                                     VectorField& scratch) {
  const auto t0 = std::chrono::steady_clock::now();
  const index_t m = index_t(wall_.X.size());  // 3n unknowns
  VectorField g = zeros_like(shape);
  const dvec U0 = base_velocity(ib, fluid);
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
  const dvec U0 = base_velocity(ib, fluid);
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
    if (!wall_.dense)
      lattice_ = commensurate_lattice(std::vector<double>(wall_.X.begin(), wall_.X.end()), parts_ ? parts_->whole_grid() : fluid.grid());
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
  // M Lambda = -J u* (on a split fluid every process solves the same system).
  lambda_ = velocity_at_markers(ib, fluid.next().u);
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
  spread_forces(ib, algorithm, lambda_, f, scratch);
}

}  // namespace rbfib::sim
