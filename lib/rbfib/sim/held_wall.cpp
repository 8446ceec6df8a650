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

linalg::LuFactors HeldWallSet::build(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, const VectorField& shape,
                                     VectorField& scratch) {
  const auto t0 = std::chrono::steady_clock::now();
  const index_t m = index_t(wall_.X.size());  // 3n unknowns
  VectorField g;
  for (int a = 0; a < 3; ++a) g[a].assign(shape[a].size(), 0.0);
  // The base: the step without force, from the same state (the fluid step is affine in its force).
  fluid.step(nullptr);
  dvec U0;
  interpolate_at(ib, at_, fluid.next().u, U0, name());
  // A trial force whose response is about 1e3 cm/s (a Stokeslet's mu h u), far above the flow's own
  // velocities: the differences keep their digits.
  const MacGrid& grid = fluid.grid();
  const double h = std::min({grid.h(0), grid.h(1), grid.h(2)});
  const double trial = fluid.viscosity() * h * 1e3;
  std::vector<double> M(static_cast<std::size_t>(m * m));
  dvec F(static_cast<std::size_t>(m), 0.0), U;
  for (index_t j = 0; j < m; ++j) {
    thrust::fill(F.begin(), F.end(), 0.0);
    F[static_cast<std::size_t>(j)] = trial;
    for (int a = 0; a < 3; ++a) thrust::fill(g[a].begin(), g[a].end(), 0.0);
    spread_into(ib, algorithm, wall_.X, F, spread_, g, scratch);
    fluid.step(&g);
    interpolate_at(ib, at_, fluid.next().u, U, name());
    blas::axpy(-1.0, U0, U);
    const std::vector<double> col(U.begin(), U.end());
    for (index_t i = 0; i < m; ++i) M[static_cast<std::size_t>(i + j * m)] = col[static_cast<std::size_t>(i)] / trial;
  }
  linalg::LuFactors lu = linalg::lu_factor(linalg::DeviceMatrix::from_host(m, m, M.data()), (name() + ": mobility J L S").c_str());
  seconds_building_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return lu;
}

void HeldWallSet::hold(ib::Interaction& ib, FluidStep& fluid, ib::Spreading algorithm, VectorField& f, VectorField& scratch) {
  auto it = mobility_.find(fluid.dt());
  if (it == mobility_.end()) {
    it = mobility_.emplace(fluid.dt(), build(ib, fluid, algorithm, f, scratch)).first;
    fluid.step(&f);  // u* again, after the trial steps
  }
  // M Lambda = -J u*.
  interpolate_at(ib, at_, fluid.next().u, lambda_, name());
  blas::scale(-1.0, lambda_);
  const index_t m = index_t(lambda_.size());
  linalg::lu_solve(it->second, linalg::Op::none, linalg::MatrixView{ptr(lambda_), m, 1, m});
  if (!blas::all_finite(lambda_)) throw NumericalError(Cause::non_finite, name() + ": non-finite wall force");
  spread_into(ib, algorithm, wall_.X, lambda_, spread_, f, scratch);
}

}  // namespace rbfib::sim
