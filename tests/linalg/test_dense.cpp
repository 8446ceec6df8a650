// The dense seam: products and LU solves agree with plain loops on random matrices, in every
// transpose combination, on blocks with a leading dimension larger than the row count, and in
// batches; a singular matrix is named in the error.
#include "rbfib/core/error.hpp"
#include "rbfib/linalg/dense.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

namespace rbfib::linalg {
namespace {

std::vector<double> random_values(std::size_t n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> v(n);
  for (auto& x : v) x = u(g);
  return v;
}

// (op(A) op(B))(i, j) by a plain triple loop on host column-major arrays.
double reference_entry(Op oa, Op ob, const std::vector<double>& A, index_t lda, const std::vector<double>& B, index_t ldb,
                       index_t k, index_t i, index_t j) {
  double s = 0;
  for (index_t l = 0; l < k; ++l) {
    const double a = oa == Op::none ? A[i + l * lda] : A[l + i * lda];
    const double b = ob == Op::none ? B[l + j * ldb] : B[j + l * ldb];
    s += a * b;
  }
  return s;
}

TEST(Dense, GemmMatchesLoopsInEveryTransposeCombination) {
  const index_t m = 37, n = 11, k = 23;
  for (Op oa : {Op::none, Op::transpose})
    for (Op ob : {Op::none, Op::transpose}) {
      const index_t ar = oa == Op::none ? m : k, ac = oa == Op::none ? k : m;
      const index_t br = ob == Op::none ? k : n, bc = ob == Op::none ? n : k;
      const auto a = random_values(ar * ac, 1), b = random_values(br * bc, 2), c0 = random_values(m * n, 3);
      DeviceMatrix A = DeviceMatrix::from_host(ar, ac, a.data()), B = DeviceMatrix::from_host(br, bc, b.data());
      DeviceMatrix C = DeviceMatrix::from_host(m, n, c0.data());
      gemm(oa, ob, 2.0, A.view(), B.view(), -0.5, C.view());
      const auto c = C.to_host();
      double err = 0;
      for (index_t j = 0; j < n; ++j)
        for (index_t i = 0; i < m; ++i)
          err = std::max(err, std::abs(c[i + j * m] - (2 * reference_entry(oa, ob, a, ar, b, br, k, i, j) - 0.5 * c0[i + j * m])));
      // k products of entries in [-1, 1]: rounding of a sum of k terms, a few ulps each.
      EXPECT_LT(err, 4 * k * 1e-16) << int(oa) << int(ob);
    }
}

TEST(Dense, GemmOnBlocksHonoursTheLeadingDimension) {
  // C's block rows [2, 7) x columns [1, 4) of a 10 x 6 matrix; the rest must stay untouched.
  const auto a = random_values(5 * 8, 4), b = random_values(8 * 3, 5);
  DeviceMatrix A = DeviceMatrix::from_host(5, 8, a.data()), B = DeviceMatrix::from_host(8, 3, b.data());
  DeviceMatrix C(10, 6);
  thrust::fill(C.storage().begin(), C.storage().end(), 7.0);
  gemm(Op::none, Op::none, 1.0, A.view(), B.view(), 0.0, C.view().block(2, 1, 5, 3));
  const auto c = C.to_host();
  for (index_t j = 0; j < 6; ++j)
    for (index_t i = 0; i < 10; ++i) {
      const bool inside = i >= 2 && i < 7 && j >= 1 && j < 4;
      const double want = inside ? reference_entry(Op::none, Op::none, a, 5, b, 8, 8, i - 2, j - 1) : 7.0;
      EXPECT_NEAR(c[i + j * 10], want, 1e-14) << i << "," << j;
    }
}

TEST(Dense, StridedBatchedEqualsOneProductPerBatch) {
  const index_t m = 6, n = 4, k = 5, count = 3;
  const auto a = random_values(m * k * count, 6), b = random_values(k * n * count, 7);
  DeviceMatrix A = DeviceMatrix::from_host(m, k * count, a.data()), B = DeviceMatrix::from_host(k, n * count, b.data());
  DeviceMatrix C(m, n * count);
  gemm_strided_batched(Op::none, Op::none, 1.0, A.view().block(0, 0, m, k), m * k, B.view().block(0, 0, k, n), k * n, 0.0,
                       C.view().block(0, 0, m, n), m * n, count);
  const auto c = C.to_host();
  for (index_t q = 0; q < count; ++q) {
    const std::vector<double> aq(a.begin() + q * m * k, a.begin() + (q + 1) * m * k);
    const std::vector<double> bq(b.begin() + q * k * n, b.begin() + (q + 1) * k * n);
    for (index_t j = 0; j < n; ++j)
      for (index_t i = 0; i < m; ++i)
        EXPECT_NEAR(c[q * m * n + i + j * m], reference_entry(Op::none, Op::none, aq, m, bq, k, k, i, j), 1e-14);
  }
}

TEST(Dense, GemmRejectsMismatchedShapes) {
  DeviceMatrix A(3, 4), B(5, 2), C(3, 2);
  EXPECT_THROW(gemm(Op::none, Op::none, 1.0, A.view(), B.view(), 0.0, C.view()), InputError);
}

TEST(Dense, LuSolvesAndTransposedSolves) {
  const index_t n = 40, nrhs = 3;
  const auto a = random_values(n * n, 8), x = random_values(n * nrhs, 9);
  const Eigen::Map<const Eigen::MatrixXd> Ae(a.data(), n, n);
  const Eigen::Map<const Eigen::MatrixXd> Xe(x.data(), n, nrhs);
  for (Op op : {Op::none, Op::transpose}) {
    const Eigen::MatrixXd Be = op == Op::none ? Eigen::MatrixXd(Ae * Xe) : Eigen::MatrixXd(Ae.transpose() * Xe);
    const LuFactors f = lu_factor(DeviceMatrix::from_host(n, n, a.data()), "test matrix");
    DeviceMatrix B = DeviceMatrix::from_host(n, nrhs, Be.data());
    lu_solve(f, op, B.view());
    const auto got = B.to_host();
    double err = 0;
    for (index_t i = 0; i < n * nrhs; ++i) err = std::max(err, std::abs(got[i] - x[i]));
    EXPECT_LT(err, 1e-12) << int(op);
  }
}

TEST(Dense, ConditionEstimateBracketsTheTrueOne) {
  // The estimate of ||A^{-1}||_1 is a lower bound attained by some unit vector, and in practice
  // within a factor 3 (Higham 1988): so rcond_est >= rcond_true >= rcond_est / 3 is asserted on
  // a random matrix, an ill-conditioned graded one (columns scaled over 10 decades) and a
  // Hilbert matrix; the identity gives 1.
  const index_t n = 60;
  auto check = [&](const Eigen::MatrixXd& A, const char* name) {
    const double norm1 = A.cwiseAbs().colwise().sum().maxCoeff();
    const double inv1 = A.inverse().cwiseAbs().colwise().sum().maxCoeff();
    const double truth = 1.0 / (norm1 * inv1);
    const double est = lu_rcond(lu_factor(DeviceMatrix::from_host(A.rows(), A.cols(), A.data()), name), norm1);
    EXPECT_GE(est, truth * (1 - 1e-8)) << name;
    EXPECT_LE(est, 3 * truth) << name;
    return est;
  };
  const auto a = random_values(n * n, 3);
  Eigen::MatrixXd R = Eigen::Map<const Eigen::MatrixXd>(a.data(), n, n);
  check(R, "random");
  Eigen::MatrixXd G = R;
  for (index_t j = 0; j < n; ++j) G.col(j) *= std::pow(10.0, -10.0 * double(j) / double(n - 1));
  EXPECT_LT(check(G, "graded"), 1e-9);
  Eigen::MatrixXd H(8, 8);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) H(i, j) = 1.0 / (i + j + 1);
  EXPECT_LT(check(H, "Hilbert 8"), 1e-9);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  EXPECT_NEAR(lu_rcond(lu_factor(DeviceMatrix::from_host(n, n, I.data()), "identity"), 1.0), 1.0, 1e-13);  // sums of n terms 1/n
}

TEST(Dense, FactorsFromTheHostGiveTheSameSolves) {
  // Eigen's factorization (with its row permutation) turned into LAPACK's interchange sequence.
  const index_t n = 25;
  const auto a = random_values(n * n, 10), b = random_values(n, 11);
  const Eigen::Map<const Eigen::MatrixXd> Ae(a.data(), n, n);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(Ae);
  std::vector<index_t> perm(n);
  const auto& idx = lu.permutationP().indices();
  for (index_t i = 0; i < n; ++i) perm[idx[i]] = i;
  const Eigen::MatrixXd packed = lu.matrixLU();
  const LuFactors f = lu_from_host(n, packed.data(), perm);
  DeviceMatrix B = DeviceMatrix::from_host(n, 1, b.data());
  lu_solve(f, Op::none, B.view());
  const Eigen::VectorXd want = lu.solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
  const auto got = B.to_host();
  for (index_t i = 0; i < n; ++i) EXPECT_NEAR(got[i], want[i], 1e-12 * (1 + std::abs(want[i])));
}

TEST(Dense, SingularMatrixIsNamed) {
  std::vector<double> a(9, 1.0);  // rank one
  try {
    lu_factor(DeviceMatrix::from_host(3, 3, a.data()), "my matrix");
    FAIL() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("my matrix"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rbfib::linalg
