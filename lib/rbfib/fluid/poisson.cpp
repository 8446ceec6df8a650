#include "rbfib/fluid/poisson.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/fluid/helmholtz.hpp"

#include <thrust/reduce.h>

#include <cmath>

namespace rbfib {

void remove_mean(dvec& x) {
  if (x.empty()) return;
  const double mean = thrust::reduce(x.begin(), x.end(), 0.0) / double(x.size());
  double* p = ptr(x);
  for_each_index(index_t(x.size()), [=] RBFIB_HD (index_t i) { p[i] -= mean; });
}

double smallest_nonzero_eigenvalue(const Box& box) {
  double lambda = INFINITY;
  for (int d = 0; d < box.dims; ++d) {
    const Axis& ax = box.axes[d];
    const int n = ax.cells;
    if (n < 2) continue;
    // 1D eigenvalues: periodic (4/h^2) sin^2(pi k / n), Neumann (g = 1/2) (4/h^2) sin^2(pi k / (2n)).
    const double arg = ax.periodic() ? pi / n : pi / (2.0 * n);
    const double s = std::sin(arg);
    lambda = std::min(lambda, 4.0 * s * s / (ax.h() * ax.h()));
  }
  return lambda;
}

static Box coarsen(const Box& box) {
  Box c = box;
  for (int d = 0; d < box.dims; ++d) c.axes[d].cells = box.axes[d].cells / 2;
  return c;
}

int PoissonSolver::max_levels(const Box& box) {
  int levels = 1;
  Box b = box;
  for (;;) {
    bool ok = true;
    for (int d = 0; d < b.dims; ++d) ok = ok && b.axes[d].cells % 2 == 0 && b.axes[d].cells / 2 >= 4;
    if (!ok) return levels;
    b = coarsen(b);
    ++levels;
  }
}

PoissonSolver::PoissonSolver(const Box& box, PoissonOptions options) : options_(std::move(options)) {
  box.validate();
  const std::string& name = options_.solver.name;
  for (int d = 0; d < box.dims; ++d) {
    const Axis& ax = box.axes[d];
    const bool ok = ax.g == 0.5 && (ax.periodic() || (ax.lower.kind == BoundaryKind::neumann &&
                                                       ax.upper.kind == BoundaryKind::neumann));
    require(ok, name + ".box.axis[" + std::to_string(d) + "]", to_string(ax.lower.kind),
            "the Poisson problem 2.9 needs a cell-centred box with periodic or homogeneous Neumann axes");
  }
  const int most = max_levels(box);
  int levels = options_.levels == 0 ? most : options_.levels;
  require(levels >= 1 && levels <= most, name + ".levels", options_.levels,
          "the box admits 1 to " + std::to_string(most) +
              " multigrid levels (halving needs even cell counts and at least 4 cells per axis after halving)");
  require(options_.smoothing_steps >= 1, name + ".smoothing_steps", options_.smoothing_steps, "must be at least 1");
  require(options_.coarse_contraction > 0.0 && options_.coarse_contraction < 1.0, name + ".coarse_contraction",
          options_.coarse_contraction, "must lie in (0, 1)");

  std::vector<Box> boxes{box};
  for (int l = 1; l < levels; ++l) boxes.push_back(coarsen(boxes.back()));
  lap_.reserve(levels);
  for (const Box& b : boxes) lap_.emplace_back(b, Correction::none);

  std::vector<MultigridLevel> mg(levels);
  for (int l = 0; l < levels; ++l) {
    const StaggeredLaplacian* L = &lap_[l];
    mg[l].apply = [L](const dvec& x, dvec& y) { L->apply(x, y, 0.0, -1.0); };
    mg[l].size = L->size();
    ChebyshevBounds g = gershgorin_bounds(*L, 0.0, -1.0);
    ChebyshevBounds bounds;
    bounds.lambda_max = g.lambda_max;
    if (l + 1 < levels) {
      bounds.lambda_min = g.lambda_max / (2.0 * box.dims);
      mg[l].smoother = ChebyshevIteration(bounds, options_.smoothing_steps, name + ".smoother");
      CellCentredTransfer& t = mg[l].to_coarse;
      t.dims = box.dims;
      for (int d = 0; d < 3; ++d) {
        t.fine[d] = d < box.dims ? boxes[l].axes[d].cells : 1;
        t.coarse[d] = d < box.dims ? boxes[l + 1].axes[d].cells : 1;
        t.periodic[d] = d < box.dims ? boxes[l].axes[d].periodic() : true;
      }
    } else {
      bounds.lambda_min = smallest_nonzero_eigenvalue(boxes[l]);
      const int steps = std::min(2000, bounds.steps_for(options_.coarse_contraction));
      mg[l].smoother = ChebyshevIteration(bounds, steps, name + ".coarse");
    }
  }
  mg_ = Multigrid(std::move(mg));
}

SolveStats PoissonSolver::solve(dvec& b, dvec& q) const {
  require(index_t(b.size()) == lap_.front().size(), options_.solver.name + ".rhs.size", b.size(), "does not match the box");
  remove_mean(b);
  if (index_t(q.size()) != index_t(b.size())) q.assign(b.size(), 0.0);
  auto A = [this](const dvec& x, dvec& y) { apply(x, y); };
  auto M = [this](const dvec& r, dvec& z) {
    mg_.vcycle(r, z);
    remove_mean(z);
  };
  SolveStats s = conjugate_gradient(A, b, q, options_.solver, M);
  remove_mean(q);
  return s;
}

}  // namespace rbfib
