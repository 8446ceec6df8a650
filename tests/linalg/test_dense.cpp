// The dense seam: products and LU solves agree with plain loops on random matrices, in every
// transpose combination, on blocks with a leading dimension larger than the row count, and in
// batches; a singular matrix is named in the error.
#include "rbfib/core/error.hpp"
#include "rbfib/linalg/dense.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
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

// Unit roundoff and gamma_k = k u / (1 - k u), the factor of the standard rounding bounds
// (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., Sec. 3.1).
constexpr double unit_roundoff = std::numeric_limits<double>::epsilon() / 2;
double gamma_n(double k) { return k * unit_roundoff / (1 - k * unit_roundoff); }

// (op(A) op(B))(i, j) by a plain triple loop on host column-major arrays, and the sum of the
// magnitudes of its terms, (|op(A)| |op(B)|)(i, j).
struct Entry {
  double value = 0, magnitude = 0;
};
Entry reference_entry(Op oa, Op ob, const std::vector<double>& A, index_t lda, const std::vector<double>& B, index_t ldb,
                      index_t k, index_t i, index_t j) {
  Entry s;
  for (index_t l = 0; l < k; ++l) {
    const double a = oa == Op::none ? A[i + l * lda] : A[l + i * lda];
    const double b = ob == Op::none ? B[l + j * ldb] : B[j + l * ldb];
    s.value += a * b;
    s.magnitude += std::abs(a * b);
  }
  return s;
}

// Two evaluations of alpha sum_k a b + beta c in any summation order (BLAS kernels differ per CPU)
// are each within gamma_{k+2} |alpha| sum |a b| + gamma_2 |beta c| of the exact value.
double gemm_tolerance(index_t k, double alpha, const Entry& e, double beta, double c) {
  return 2 * (gamma_n(double(k + 2)) * std::abs(alpha) * e.magnitude + gamma_n(2) * std::abs(beta * c));
}

// |L| |U| of P A = L U, in the row order of A (A = P^{-1} L U): the backward error of every solve
// with these factors is bounded by gamma_3n |L| |U| (Higham Thm 9.4).
Eigen::MatrixXd abs_lu(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu) {
  const Eigen::Index n = lu.matrixLU().rows();
  Eigen::MatrixXd L = Eigen::MatrixXd::Identity(n, n);
  L.triangularView<Eigen::StrictlyLower>() = lu.matrixLU();
  const Eigen::MatrixXd U = lu.matrixLU().triangularView<Eigen::Upper>();
  const Eigen::MatrixXd LU = L.cwiseAbs() * U.cwiseAbs();
  return lu.permutationP().inverse() * LU;
}

TEST(Dense, GemmMatchesLoopsInEveryTransposeCombination) {
  const index_t m = 37, k = 23;
  for (index_t n : {11, 1})  // one column: the matrix-vector path
  for (Op oa : {Op::none, Op::transpose})
    for (Op ob : {Op::none, Op::transpose}) {
      const index_t ar = oa == Op::none ? m : k, ac = oa == Op::none ? k : m;
      const index_t br = ob == Op::none ? k : n, bc = ob == Op::none ? n : k;
      const auto a = random_values(ar * ac, 1), b = random_values(br * bc, 2), c0 = random_values(m * n, 3);
      DeviceMatrix A = DeviceMatrix::from_host(ar, ac, a.data()), B = DeviceMatrix::from_host(br, bc, b.data());
      DeviceMatrix C = DeviceMatrix::from_host(m, n, c0.data());
      gemm(oa, ob, 2.0, A.view(), B.view(), -0.5, C.view());
      const auto c = C.to_host();
      // Loop and BLAS each round a sum of k products: bound entry by entry (gemm_tolerance).
      double worst = 0;
      for (index_t j = 0; j < n; ++j)
        for (index_t i = 0; i < m; ++i) {
          const Entry e = reference_entry(oa, ob, a, ar, b, br, k, i, j);
          const double want = 2 * e.value - 0.5 * c0[i + j * m];
          worst = std::max(worst, std::abs(c[i + j * m] - want) / gemm_tolerance(k, 2.0, e, -0.5, c0[i + j * m]));
        }
      EXPECT_LE(worst, 1.0) << int(oa) << int(ob) << " n = " << n;
    }
}

TEST(Dense, OneColumnProductsReadStridedOperands) {
  // op(B) one column: B's column 2 of a 9 x 3 block, or (transposed) B's row 1 of a 3 x 9 matrix
  // (stride 3); C a column of a block whose leading dimension exceeds its rows; batches of two.
  const index_t m = 6, k = 9;
  const auto a = random_values(2 * m * k, 11), bn = random_values(k * 3, 12), bt = random_values(3 * k, 13);
  DeviceMatrix A = DeviceMatrix::from_host(m, 2 * k, a.data());
  DeviceMatrix Bn = DeviceMatrix::from_host(k, 3, bn.data()), Bt = DeviceMatrix::from_host(3, k, bt.data());
  for (Op ob : {Op::none, Op::transpose}) {
    DeviceMatrix C(m + 2, 4);
    thrust::fill(C.storage().begin(), C.storage().end(), 7.0);
    const ConstMatrixView B = ob == Op::none ? Bn.view().block(0, 2, k, 1) : Bt.view().block(1, 0, 1, k);
    gemm_strided_batched(Op::none, ob, 1.0, A.view().block(0, 0, m, k), m * k, B, 0, 0.0, C.view().block(1, 0, m, 1), 2 * (m + 2), 2);
    const auto c = C.to_host();
    std::vector<double> x(static_cast<std::size_t>(k));
    for (index_t l = 0; l < k; ++l) x[std::size_t(l)] = ob == Op::none ? bn[l + 2 * k] : bt[1 + 3 * l];
    for (index_t q = 0; q < 2; ++q)
      for (index_t i = 0; i < m + 2; ++i) {
        const index_t col = 2 * q;
        if (i == 0 || i == m + 1) {
          EXPECT_EQ(c[i + col * (m + 2)], 7.0);
          continue;
        }
        const std::vector<double> aq(a.begin() + q * m * k, a.begin() + (q + 1) * m * k);
        const Entry e = reference_entry(Op::none, Op::none, aq, m, x, k, k, i - 1, 0);
        EXPECT_NEAR(c[i + col * (m + 2)], e.value, gemm_tolerance(k, 1.0, e, 0.0, 0.0)) << int(ob) << " " << q << " " << i;
      }
    for (index_t i = 0; i < m + 2; ++i) EXPECT_EQ(c[i + 1 * (m + 2)], 7.0);  // the column between the batches
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
      if (!inside) {
        EXPECT_EQ(c[i + j * 10], 7.0) << i << "," << j;  // untouched
        continue;
      }
      const Entry e = reference_entry(Op::none, Op::none, a, 5, b, 8, 8, i - 2, j - 1);
      EXPECT_NEAR(c[i + j * 10], e.value, gemm_tolerance(8, 1.0, e, 0.0, 0.0)) << i << "," << j;
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
      for (index_t i = 0; i < m; ++i) {
        const Entry e = reference_entry(Op::none, Op::none, aq, m, bq, k, k, i, j);
        EXPECT_NEAR(c[q * m * n + i + j * m], e.value, gemm_tolerance(k, 1.0, e, 0.0, 0.0));
      }
  }
}

TEST(Dense, SingleGemmIsWithinFloatRoundingInBatchesAndOneColumn) {
  // sgemm on float copies of the operands: within gamma_{k+2} in float's unit roundoff of the exact
  // product of those float operands (computed here in double, exactly enough); one column goes
  // through sgemv, a batch through one product per member.
  const double uf = std::numeric_limits<float>::epsilon() / 2;
  const index_t m = 7, k = 300, count = 2;
  for (index_t n : {index_t(1), index_t(5)}) {
    const auto a = random_values(m * k * count, 11), b = random_values(k * n, 12);
    DeviceMatrix A = DeviceMatrix::from_host(m, k * count, a.data()), B = DeviceMatrix::from_host(k, n, b.data());
    FloatMatrix Af(m, k * count), Bf(k, n), Cf(m, n * count);
    narrow(A.view(), Af.view());
    narrow(B.view(), Bf.view());
    gemm_strided_batched(Op::none, Op::none, 1.0f, Af.view().block(0, 0, m, k), m * k, Bf.view(), 0, 0.0f,
                         Cf.view().block(0, 0, m, n), m * n, count);
    DeviceMatrix C(m, n * count);
    widen(Cf.view(), C.view());
    const auto af = Af.to_host(), bf = Bf.to_host();
    const auto c = C.to_host();
    for (index_t q = 0; q < count; ++q)
      for (index_t j = 0; j < n; ++j)
        for (index_t i = 0; i < m; ++i) {
          double exact = 0, magnitude = 0;
          for (index_t l = 0; l < k; ++l) {
            const double t = double(af[q * m * k + i + l * m]) * double(bf[l + j * k]);
            exact += t;
            magnitude += std::abs(t);
          }
          const double g = double(k + 2) * uf / (1 - double(k + 2) * uf);
          EXPECT_NEAR(c[q * m * n + i + j * m], exact, g * magnitude) << "n = " << n << ", batch " << q;
        }
  }
}

TEST(Dense, NarrowAndWidenRoundToFloatOnBlocks) {
  const index_t rows = 5, cols = 3;
  const auto a = random_values(rows * cols, 13);
  DeviceMatrix A = DeviceMatrix::from_host(rows, cols, a.data()), back(rows + 2, cols);
  FloatMatrix F(rows + 1, cols);
  narrow(A.view(), F.view().block(1, 0, rows, cols));
  widen(F.view().block(1, 0, rows, cols), back.view().block(2, 0, rows, cols));
  const auto h = back.to_host();
  for (index_t j = 0; j < cols; ++j)
    for (index_t i = 0; i < rows; ++i) EXPECT_EQ(h[2 + i + j * (rows + 2)], double(float(a[i + j * rows])));
  EXPECT_THROW(narrow(A.view(), F.view()), InputError);
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
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Ae);
  const Eigen::MatrixXd LU = abs_lu(lu), Ai = lu.inverse();
  for (Op op : {Op::none, Op::transpose}) {
    const Eigen::MatrixXd M = op == Op::none ? Eigen::MatrixXd(Ae) : Eigen::MatrixXd(Ae.transpose());
    const Eigen::MatrixXd Be = M * Xe;
    const LuFactors f = lu_factor(DeviceMatrix::from_host(n, n, a.data()), "test matrix");
    DeviceMatrix B = DeviceMatrix::from_host(n, nrhs, Be.data());
    lu_solve(f, op, B.view());
    const auto got = B.to_host();
    // B = fl(M X) = M X + dB, |dB| <= gamma_n |M| |X|; getrs solves (M + dM) Y = B with
    // |dM| <= gamma_3n |L||U| (transposed for op = T): to first order, entry by entry,
    // |Y - X| <= |M^-1| (gamma_n |M| + gamma_3n |L||U|) |X|, a componentwise n eps kappa bound
    // (kappa_inf ~ 1e3 here, so up to ~7e-11 where the former fixed 1e-12 assumed ~10 eps kappa).
    const Eigen::MatrixXd LUop = op == Op::none ? LU : Eigen::MatrixXd(LU.transpose());
    const Eigen::MatrixXd Mi = op == Op::none ? Ai : Eigen::MatrixXd(Ai.transpose());
    const Eigen::MatrixXd bound =
        Mi.cwiseAbs() * ((gamma_n(double(n)) * M.cwiseAbs() + gamma_n(3.0 * double(n)) * LUop) * Xe.cwiseAbs());
    double worst = 0;
    for (index_t i = 0; i < n * nrhs; ++i) worst = std::max(worst, std::abs(got[i] - x[i]) / bound.data()[i]);
    EXPECT_LE(worst, 1.0) << int(op);
  }
}

TEST(Dense, ConditionEstimateBracketsTheTrueOne) {
  // The estimate of ||A^{-1}||_1 is a lower bound attained by some unit vector, and in practice
  // within a factor 3 (Higham 1988): so rcond_est >= rcond_true >= rcond_est / 3 is asserted on
  // a random matrix, an ill-conditioned graded one (columns scaled over 10 decades) and a
  // Hilbert matrix; the identity gives 1.
  //
  // Both sides are rounded: "truth" uses X = fl(A^{-1}) (Eigen's LU), the estimate LAPACK's solves
  // (same partial pivoting, so Eigen's |L||U| stands for both). A computed solve y of A y = x has
  // |y - A^{-1} x| <= gamma_3n |X| |L||U| |y| (Higham Thm 9.4), so for ||x||_1 = 1 both ||X||_1 and
  // the estimate are within gamma_3n mu of ||A^{-1}||_1 (relative), mu = || |X||L||U||X| ||_1 /
  // ||X||_1 (<~ kappa_1; column scaling hardly moves it: graded kappa_1 ~ 2e12, mu ~ 2e4). With
  // the 1-norm sums and scalings (n + 4 roundings each): est >= truth (1 - tol),
  // tol = 2 gamma_3n mu + 2 gamma_{n+4}. Hilbert 8: mu ~ 3.5e9, tol ~ 2e-5 (its computed inverse
  // alone is off by ~1e-8, the former fixed tolerance); random, graded: tol ~ 1e-9.
  const index_t n = 60;
  auto check = [&](const Eigen::MatrixXd& A, const char* name) {
    const double m = double(A.rows());
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    const Eigen::MatrixXd X = lu.inverse();
    const double norm1 = A.cwiseAbs().colwise().sum().maxCoeff();
    const double inv1 = X.cwiseAbs().colwise().sum().maxCoeff();
    const double mu = (X.cwiseAbs() * abs_lu(lu) * X.cwiseAbs()).colwise().sum().maxCoeff() / inv1;
    const double tol = 2 * gamma_n(3 * m) * mu + 2 * gamma_n(m + 4);
    EXPECT_LT(tol, 1e-3) << name;  // stays sharp: an estimate 10% low (or in another norm) fails
    const double truth = 1.0 / (norm1 * inv1);
    const double est = lu_rcond(lu_factor(DeviceMatrix::from_host(A.rows(), A.cols(), A.data()), name), norm1);
    EXPECT_GE(est, truth * (1 - tol)) << name << ": tolerance " << tol;
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
  // Two substitutions with the same factors in different orders: each solves
  // (L + dL)(U + dU) y = P b with |dL| <= gamma_n |L|, |dU| <= gamma_n |U|, so each is within
  // 2 gamma_n |A^-1| |L||U| |y| of the exact solution (first order), the two within twice that.
  const Eigen::VectorXd bound = 4 * gamma_n(double(n)) * (lu.inverse().cwiseAbs() * (abs_lu(lu) * want.cwiseAbs()));
  for (index_t i = 0; i < n; ++i) EXPECT_NEAR(got[i], want[i], bound[i]) << i;
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

#if !defined(RBFIB_BACKEND_CUDA)
#include <omp.h>

namespace rbfib::linalg {
// A tall operator times a few columns is split by rows among the team (one one-thread GEMM per
// thread): the products agree with the BLAS's own threading to rounding, in strided batches and
// on blocks whose rows start off a multiple of 8, and with teams that split the rows unevenly.
TEST(Dense, TallProductsSplitByRowsEqualTheBlasThreads) {
  const index_t m = 1003, k = 97, n = 7, count = 3;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> a(static_cast<std::size_t>(count * m * k)), b(static_cast<std::size_t>(k * n));
  for (double& x : a) x = u(rng);
  for (double& x : b) x = u(rng);
  const linalg::DeviceMatrix A = linalg::DeviceMatrix::from_host(count * m, k, a.data()), B = linalg::DeviceMatrix::from_host(k, n, b.data());
  auto product = [&](bool split, int threads) {
    linalg::DeviceMatrix C(count * m, n);
    const int team = omp_get_max_threads();
    omp_set_num_threads(threads);
    linalg::set_rows_per_thread(split);
    // rows 3 .. 3 + m - 4 of each of the count blocks of A (stride m), into the blocks of C
    linalg::gemm_strided_batched(linalg::Op::none, linalg::Op::none, 1.0, A.view().block(3, 0, m - 4, k), m, B.view(), 0, 0.0,
                                 C.view().block(0, 0, m - 4, n), m, count);
    linalg::set_rows_per_thread(true);
    omp_set_num_threads(team);
    return C.to_host();
  };
  const std::vector<double> ref = product(false, 1);
  for (int threads : {2, 3}) {
    const std::vector<double> got = product(true, threads);
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) diff = std::max(diff, std::abs(got[i] - ref[i])), scale = std::max(scale, std::abs(ref[i]));
    EXPECT_LE(diff, 1e-14 * scale) << threads << " threads";
    EXPECT_GT(scale, 1.0);
  }
  EXPECT_TRUE(linalg::rows_per_thread());
}
}  // namespace rbfib::linalg
#endif
