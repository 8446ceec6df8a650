// Unit tests of the staggered Laplacian with ghost extrapolation and the Appendix A correction:
// symmetry, positive definiteness of the Helmholtz operator, and exactness on quadratics for
// every staggering g and boundary type.
#include "rbfib/fluid/diffusion.hpp"
#include "rbfib/fluid/laplacian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rbfib {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

Axis make_axis(int cells, double g, BoundaryCondition bc, double length = 1.0) { return Axis{cells, length, g, bc, bc, 0.0}; }

// Dense matrix of u -> alpha I~ u + beta L u by columns.
std::vector<std::vector<double>> dense(const StaggeredLaplacian& L, double alpha, double beta) {
  const index_t n = L.size();
  std::vector<std::vector<double>> A(n, std::vector<double>(n));
  dvec e(n, 0.0), y(n);
  for (index_t j = 0; j < n; ++j) {
    e[j] = 1.0;
    L.apply(e, y, alpha, beta);
    host_vector<double> h = y;
    for (index_t i = 0; i < n; ++i) A[i][j] = h[i];
    e[j] = 0.0;
  }
  return A;
}

struct Case {
  double g;
  BoundaryCondition bc;
  const char* name;
};

const Case kCases[] = {
    {0.5, BoundaryCondition::dirichlet(), "dirichlet g=1/2"}, {1.0, BoundaryCondition::dirichlet(), "dirichlet g=1"},
    {0.3, BoundaryCondition::dirichlet(), "dirichlet g=0.3"}, {0.5, BoundaryCondition::neumann(), "neumann g=1/2"},
    {1.0, BoundaryCondition::neumann(), "neumann g=1"},       {0.3, BoundaryCondition::neumann(), "neumann g=0.3"},
    {0.5, BoundaryCondition::robin(1.0, -0.2), "robin g=1/2"}, {1.0, BoundaryCondition::robin(2.0, -0.1), "robin g=1"},
};

TEST(Laplacian, EpsilonOfTheSeed) {
  // eq. A.10: Dirichlet eps = (1-g)/2, Neumann eps = (1-2g)/2.
  const double h = 0.1;
  EXPECT_DOUBLE_EQ(1.0 - axis_end(BoundaryCondition::dirichlet(), 0.5, h).one_minus_eps, 0.25);
  EXPECT_DOUBLE_EQ(1.0 - axis_end(BoundaryCondition::dirichlet(), 1.0, h).one_minus_eps, 0.0);
  EXPECT_DOUBLE_EQ(1.0 - axis_end(BoundaryCondition::neumann(), 0.5, h).one_minus_eps, 0.0);
  EXPECT_DOUBLE_EQ(1.0 - axis_end(BoundaryCondition::neumann(), 1.0, h).one_minus_eps, -0.5);
  // Ghost values: Dirichlet at g = 1/2 mirrors, u_0 = 2 gamma - u_1; Neumann u_0 = u_1 - h gamma.
  const AxisEnd d = axis_end(BoundaryCondition::dirichlet(), 0.5, h), n = axis_end(BoundaryCondition::neumann(), 1.0, h);
  EXPECT_DOUBLE_EQ(d.ghost, -1.0);
  EXPECT_DOUBLE_EQ(d.data, 2.0);
  EXPECT_DOUBLE_EQ(n.ghost, 1.0);
  EXPECT_DOUBLE_EQ(n.data, -h);
}

TEST(Laplacian, SymmetricAndHelmholtzPositiveDefinite2D) {
  for (const Case& c : kCases)
    for (Correction corr : {Correction::none, Correction::appendix_a}) {
      Box box;
      box.dims = 2;
      box.axes[0] = make_axis(5, c.g, c.bc);
      box.axes[1] = make_axis(4, 0.5, BoundaryCondition::dirichlet(), 0.8);
      StaggeredLaplacian L(box, corr);
      const auto A = dense(L, 1.0, -0.37);  // Helmholtz I~ - 0.37 L
      const index_t n = L.size();
      double scale = 0;
      for (auto& row : A)
        for (double v : row) scale = std::max(scale, std::abs(v));
      for (index_t i = 0; i < n; ++i)
        for (index_t j = 0; j < n; ++j) ASSERT_NEAR(A[i][j], A[j][i], 4 * eps * scale) << c.name << " at " << i << "," << j;
      // Cholesky succeeds iff symmetric positive definite.
      std::vector<std::vector<double>> C = A;
      for (index_t k = 0; k < n; ++k) {
        double d = C[k][k];
        for (index_t m = 0; m < k; ++m) d -= C[k][m] * C[k][m];
        ASSERT_GT(d, 0.0) << c.name << (corr == Correction::none ? " uncorrected" : " corrected") << ": pivot " << k;
        C[k][k] = std::sqrt(d);
        for (index_t i = k + 1; i < n; ++i) {
          double s = C[i][k];
          for (index_t m = 0; m < k; ++m) s -= C[i][m] * C[k][m];
          C[i][k] = s / C[k][k];
        }
      }
    }
}

// u = quadratic in x, y, z; gamma from its values and inward normal derivatives.
struct Quadratic {
  double operator()(double x, double y, double z) const {
    return 0.3 + x - 2 * y + 0.5 * z + 1.2 * x * x - 0.7 * y * y + 0.9 * z * z + 0.4 * x * y - 0.6 * y * z + 0.25 * x * z;
  }
  double grad(int d, double x, double y, double z) const {
    if (d == 0) return 1 + 2.4 * x + 0.4 * y + 0.25 * z;
    if (d == 1) return -2 - 1.4 * y + 0.4 * x - 0.6 * z;
    return 0.5 + 1.8 * z - 0.6 * y + 0.25 * x;
  }
  double second(int d) const { return d == 0 ? 2.4 : d == 1 ? -1.4 : 1.8; }
};

double quadratic_residual(const Box& box, Correction corr) {
  const Quadratic q;
  StaggeredLaplacian L(box, corr);
  dvec u = sample(box, q), Lu;
  BoundaryData gamma = sample_boundary(box, [&](int d, int side, double x, double y, double z) {
    const BoundaryCondition& bc = side ? box.axes[d].upper : box.axes[d].lower;
    const double dnu = (side ? -1.0 : 1.0) * q.grad(d, x, y, z);
    return bc.alpha * q(x, y, z) + bc.beta * dnu;
  });
  L.apply(u, Lu);
  L.add_boundary(gamma, Lu, 1.0);
  double lap = 0;
  for (int d = 0; d < box.dims; ++d) lap += q.second(d);
  dvec ones(u.size(), lap), target;
  L.apply_identity(ones, target);  // I~ (Laplacian of q)
  host_vector<double> a = Lu, b = target;
  double err = 0;
  for (size_t i = 0; i < a.size(); ++i) err = std::max(err, std::abs(a[i] - b[i]));
  return err;
}

TEST(Laplacian, CorrectedReproducesQuadraticsExactly3D) {
  for (const Case& cx : kCases)
    for (const Case& cy : kCases) {
      Box box;
      box.dims = 3;
      box.axes[0] = make_axis(6, cx.g, cx.bc);
      box.axes[1] = make_axis(7, cy.g, cy.bc, 1.3);
      box.axes[2] = make_axis(5, 0.5, BoundaryCondition::neumann(), 0.7);
      // Rounding: entries of L u are O(|u| / h^2); allow 64 eps of that scale.
      const double tol = 64 * eps * 4.0 / std::pow(0.7 / 5, 2);
      EXPECT_LT(quadratic_residual(box, Correction::appendix_a), tol) << cx.name << " x " << cy.name;
    }
}

TEST(Laplacian, UncorrectedMissesQuadraticsWhereEpsilonIsNonzero) {
  Box box;
  box.dims = 1;
  box.axes[0] = make_axis(10, 0.5, BoundaryCondition::dirichlet());
  // eps = 1/4 at both ends: error 1/4 |u_xx| = 0.6 in the boundary rows.
  EXPECT_NEAR(quadratic_residual(box, Correction::none), 0.25 * 2.4, 1e-9);
  box.axes[0] = make_axis(10, 0.5, BoundaryCondition::neumann());  // eps = 0: exact without correction
  EXPECT_LT(quadratic_residual(box, Correction::none), 1e-10);
}

TEST(Laplacian, BadInputNamesTheField) {
  Box box;
  box.dims = 1;
  box.axes[0] = make_axis(10, 1.5, BoundaryCondition::dirichlet());
  try {
    StaggeredLaplacian L(box, Correction::none);
    FAIL() << "accepted g = 1.5";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "box.x.g");
  }
  box.axes[0] = Axis{10, 1.0, 0.5, BoundaryCondition::periodic(), BoundaryCondition::dirichlet(), 0.0};
  EXPECT_THROW(StaggeredLaplacian(box, Correction::none), InputError);
  box.axes[0] = make_axis(10, 0.5, BoundaryCondition::robin(1.0, 0.05));  // alpha s - beta / h = 0
  EXPECT_THROW(StaggeredLaplacian(box, Correction::none), InputError);
}

TEST(Diffusion, CorrectedCrankNicolsonKeepsSteadyQuadratic) {
  // u_t = u_xx + 1, u(x, 0) = x(1 - x)/2 is steady (Tables A.1, A.2); corrected, it stays so.
  for (const Case& c : kCases) {
    if (c.bc.kind == BoundaryKind::robin) continue;
    Box box;
    box.dims = 1;
    box.axes[0] = make_axis(20, c.g, c.bc);
    auto exact = [](double x, double, double) { return 0.5 * x * (1 - x); };
    dvec u = sample(box, exact), u0 = u, f(u.size(), 1.0);
    BoundaryData gamma = sample_boundary(box, [&](int, int, double, double, double) {
      return c.bc.kind == BoundaryKind::dirichlet ? 0.0 : 0.5;  // u_x(0) = -u_x(1) = 1/2
    });
    CrankNicolsonDiffusion cn(box, 1.0, 0.005, Correction::appendix_a, SolverOptions{"helmholtz", 1e-15, 200});
    for (int s = 0; s < 20; ++s) cn.step(u, f, gamma);
    blas::axpy(-1.0, u0, u);
    EXPECT_LT(blas::norm_inf(u), 1e-13) << c.name;
  }
}

}  // namespace
}  // namespace rbfib
