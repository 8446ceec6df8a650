// Unit tests of the Helmholtz and Poisson solvers: Gershgorin bounds enclose the spectrum, the
// V-cycle is symmetric, PCG reaches the tolerance, and failures and bad input are reported by name.
#include "../common/random_field.hpp"
#include "rbfib/fluid/helmholtz.hpp"
#include "rbfib/fluid/poisson.hpp"
#include "rbfib/grid/mac.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <random>

namespace rbfib {
namespace {

using MB = MacBoundary;

using rbfib::testing::random_vector;

template <class Op>
Eigen::MatrixXd dense(index_t n, const Op& A) {
  Eigen::MatrixXd M(n, n);
  dvec e(n, 0.0), y;
  for (index_t j = 0; j < n; ++j) {
    e[j] = 1.0;
    A(e, y);
    host_vector<double> h = y;
    for (index_t i = 0; i < n; ++i) M(i, j) = h[i];
    e[j] = 0.0;
  }
  return M;
}

TEST(Helmholtz, GershgorinBoundsEncloseTheSpectrum) {
  MacGrid g = make_mac_grid(3, {4, 5, 4}, {1.0, 1.2, 0.9}, {MB::periodic, MB::dirichlet, MB::neumann});
  for (int a = 0; a < 3; ++a) {
    HelmholtzSolver H(g.component(a), 0.02, HelmholtzOptions{});
    const Eigen::MatrixXd M = dense(H.laplacian().size(), [&](const dvec& x, dvec& y) { H.apply(x, y); });
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (M + M.transpose()));
    EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-12);  // symmetric (Appendix A)
    EXPECT_GT(H.bounds().lambda_min, 0.0);
    EXPECT_LE(H.bounds().lambda_min, es.eigenvalues().minCoeff() * (1 + 1e-12));
    EXPECT_GE(H.bounds().lambda_max, es.eigenvalues().maxCoeff() * (1 - 1e-12));
  }
}

TEST(Helmholtz, ReachesToleranceAndReportsNonConvergence) {
  MacGrid g = make_mac_grid(3, {16, 12, 16}, {1.6, 1.2, 1.6}, {MB::periodic, MB::dirichlet, MB::periodic});
  const Box box = g.component(0);
  HelmholtzSolver H(box, 0.05, HelmholtzOptions{});  // c / h^2 = 5: a stiff step
  const dvec b = random_vector(box.size(), 4);
  dvec x(box.size(), 0.0), r;
  const SolveStats s = H.solve(b, x);
  H.apply(x, r);
  blas::axpy(-1.0, b, r);
  EXPECT_LE(blas::norm2(r), 1e-11 * blas::norm2(b) * 1.01);
  EXPECT_LE(s.iterations, 30);
  HelmholtzOptions one;
  one.solver = SolverOptions{"helmholtz u0", 1e-11, 1};
  HelmholtzSolver H1(box, 0.05, one);
  dvec x1(box.size(), 0.0);
  try {
    H1.solve(b, x1);
    FAIL() << "a 1-iteration limit was not reported";
  } catch (const NumericalError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("helmholtz u0"), std::string::npos) << m;
    EXPECT_NE(m.find("did not converge in 1 iterations"), std::string::npos) << m;
    EXPECT_NE(m.find("relative residual"), std::string::npos) << m;
  }
  EXPECT_THROW(HelmholtzSolver(box, -1.0, HelmholtzOptions{}), InputError);
}

TEST(Poisson, VCycleIsSymmetricAndPcgConverges) {
  for (auto bc : {std::array<MB, 3>{MB::periodic, MB::dirichlet, MB::periodic},
                  std::array<MB, 3>{MB::dirichlet, MB::dirichlet, MB::neumann}}) {
    MacGrid g = make_mac_grid(3, {16, 16, 8}, {1.0, 1.0, 0.5}, bc);
    PoissonSolver P(g.scalar(), PoissonOptions{});
    EXPECT_EQ(P.levels(), 2);  // 16x16x8 -> 8x8x4; 4 cannot be halved to >= 4
    const index_t n = g.scalar().size();
    dvec a = random_vector(n, 5), b = random_vector(n, 6), Va, Vb;
    P.multigrid().vcycle(a, Va);
    P.multigrid().vcycle(b, Vb);
    EXPECT_NEAR(blas::dot(Va, b), blas::dot(a, Vb), 1e-12 * blas::norm2(Va) * blas::norm2(b));
    dvec rhs = random_vector(n, 7), q(n, 0.0), r;
    const SolveStats s = P.solve(rhs, q);  // rhs made mean-free inside
    P.apply(q, r);
    blas::axpy(-1.0, rhs, r);
    EXPECT_LE(blas::norm2(r), 1.01e-11 * blas::norm2(rhs));
    EXPECT_LE(s.iterations, 15);
  }
}

TEST(Poisson, RefusesATooDeepHierarchyAndReportsNonConvergence) {
  MacGrid g = make_mac_grid(3, {16, 12, 16}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::periodic});
  PoissonOptions deep;
  deep.levels = 4;  // 16x12x16 -> 8x6x8 only
  try {
    PoissonSolver P(g.scalar(), deep);
    FAIL() << "accepted 4 levels";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "poisson.levels");
  }
  PoissonOptions one;
  one.solver.max_iterations = 1;
  PoissonSolver P(g.scalar(), one);
  dvec rhs = random_vector(g.scalar().size(), 8), q;
  try {
    P.solve(rhs, q);
    FAIL() << "a 1-iteration limit was not reported";
  } catch (const NumericalError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("poisson: did not converge in 1 iterations"), std::string::npos) << m;
  }
}

TEST(Poisson, SmallestNonzeroEigenvalueIsExact) {
  MacGrid g = make_mac_grid(2, {4, 6, 1}, {1.0, 1.5, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  const Box s = g.scalar();
  StaggeredLaplacian L(s, Correction::none);
  const Eigen::MatrixXd M = dense(s.size(), [&](const dvec& x, dvec& y) { L.apply(x, y, 0.0, -1.0); });
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(M);
  EXPECT_NEAR(es.eigenvalues()(0), 0.0, 1e-12);
  EXPECT_NEAR(es.eigenvalues()(1), smallest_nonzero_eigenvalue(s), 1e-12 * es.eigenvalues().maxCoeff());
}

}  // namespace
}  // namespace rbfib
