// Single-precision surface products (operators.hpp, in_single_precision): every apply_* variant is
// within float rounding of the double products, bounded by the standard rounding bound of a k-term
// sum of the shifted operand, so that a field far from the origin (a cell far from the box's
// corner) is rounded no worse than one near it; constants are kept exactly; an interpolant
// without the constant is refused.
#include "rbfib/core/error.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/point_sets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace rbfib;
using namespace rbfib::surface;

namespace {
constexpr double uf = std::numeric_limits<float>::epsilon() / 2;

/// Fields F (nd x cols): a smooth pattern of amplitude about 1 plus an offset per column.
std::vector<double> fields(index_t nd, index_t cols, double offset) {
  std::vector<double> F(static_cast<std::size_t>(nd * cols));
  for (index_t c = 0; c < cols; ++c)
    for (index_t i = 0; i < nd; ++i) F[i + c * nd] = offset * double(c + 1) + std::cos(0.3 * double(i) + double(c)) + 0.2 * double(i % 7);
  return F;
}

/// The float result is the exact product of the operator and the shifted operand each rounded
/// once to float, summed in float: within gamma_{k+4}(u_f) sum_l |L_il| |C'_lj| of the double
/// product (the double one's own rounding is below it by 2^-29), where C' is the shifted operand
/// the single path keeps in work.coefficients (solved by the LU factors for a factored set).
struct FloatBound {
  std::vector<double> Mv, Md, C;
  index_t k, ns;
  double g;
  FloatBound(const SurfaceOperators& o, const std::vector<double>& Cshift)
      : Mv(o.value.to_host()), Md(o.derivatives.to_host()), C(Cshift), k(o.value.cols()), ns(o.n_sample()),
        g(double(k + 4) * uf / (1 - double(k + 4) * uf)) {}
  double at(const std::vector<double>& M, index_t ld, index_t row, index_t c) const {
    double s = 0;
    for (index_t j = 0; j < k; ++j) s += std::abs(M[row + j * ld]) * std::abs(C[j + c * k]);
    return g * s;
  }
  double value(index_t site, index_t c) const { return at(Mv, ns, site, c); }
  double derivative(index_t row, index_t c) const { return at(Md, 5 * ns, row, c); }
};

std::vector<std::shared_ptr<const SurfaceOperators>> operator_sets() {
  const SphereSites data = bauer_spiral(64), sample = bauer_spiral(150);
  const MaxDetResult md = max_determinant_points(5);
  return {rbf_operators(data, sample, PhsBasis{7, 3}), sh_operators(md.sites, sample, 5)};
}
}  // namespace

TEST(SinglePrecision, ProductsAreWithinFloatRoundingOfTheShiftedOperand) {
  for (const auto& ops64 : operator_sets()) {
    const auto ops = in_single_precision(*ops64);
    ASSERT_TRUE(ops->single_precision());
    const index_t nd = ops->n_data(), ns = ops->n_sample(), cols = 4;
    for (double offset : {0.0, 1e4}) {
      const std::vector<double> F = fields(nd, cols, offset);
      const linalg::DeviceMatrix Fd = linalg::DeviceMatrix::from_host(nd, cols, F.data());
      OperatorWorkspace w64, w32;
      linalg::DeviceMatrix V(ns, cols), D(5 * ns, cols), v(ns, cols), d(5 * ns, cols);
      apply_operators(*ops64, Fd.view(), V.view(), D.view(), w64);
      apply_operators(*ops, Fd.view(), v.view(), d.view(), w32);
      const FloatBound tol(*ops, w32.coefficients.to_host());
      const auto Vh = V.to_host(), Dh = D.to_host(), vh = v.to_host(), dh = d.to_host();
      double worst = 0;  // the largest error against its bound
      for (index_t c = 0; c < cols; ++c)
        for (index_t i = 0; i < ns; ++i) {
          // the shift s = F(0, c) is added back in double: its rounding, |s| 2^-53, is added
          const double tv = tol.value(i, c) + std::abs(F[c * nd]) * 2 * std::numeric_limits<double>::epsilon();
          EXPECT_NEAR(vh[i + c * ns], Vh[i + c * ns], tv);
          worst = std::max(worst, std::abs(vh[i + c * ns] - Vh[i + c * ns]) / tv);
          for (int q = 0; q < 5; ++q) EXPECT_NEAR(dh[q * ns + i + c * 5 * ns], Dh[q * ns + i + c * 5 * ns], tol.derivative(q * ns + i, c));
        }
      EXPECT_GT(worst, 1e-3) << "the comparison is not sharp: float rounding did not show";
      if (offset > 0) {  // the unshifted operand's bound would be about offset times larger
        const FloatBound raw(*ops, ops->factored() ? w64.coefficients.to_host() : F);
        EXPECT_GT(raw.value(0, 0), 1e3 * tol.value(0, 0));
      }
    }
  }
}

TEST(SinglePrecision, ConstantsAreKeptExactly) {
  // A constant column has a zero shifted operand: values equal the constant, derivatives are 0.
  for (const auto& ops64 : operator_sets()) {
    const auto ops = in_single_precision(*ops64);
    const index_t nd = ops->n_data(), ns = ops->n_sample();
    const std::vector<double> F(static_cast<std::size_t>(nd), 0.123456789012345);
    const linalg::DeviceMatrix Fd = linalg::DeviceMatrix::from_host(nd, 1, F.data());
    OperatorWorkspace w;
    linalg::DeviceMatrix v(ns, 1), d(5 * ns, 1);
    apply_operators(*ops, Fd.view(), v.view(), d.view(), w);
    for (double x : v.to_host()) EXPECT_EQ(x, F[0]);
    for (double x : d.to_host()) EXPECT_EQ(x, 0.0);
  }
}

TEST(SinglePrecision, RowRangesGiveTheDoubleProductsToFloatRounding) {
  // apply_operators_rows in single precision: the same float bound against the double products.
  for (const auto& ops64 : operator_sets()) {
    const auto ops = in_single_precision(*ops64);
    const index_t nd = ops->n_data(), ns = ops->n_sample(), cols = 6, row0 = 37, rows = 51;
    const std::vector<double> F = fields(nd, cols, 50.0);
    const linalg::DeviceMatrix Fd = linalg::DeviceMatrix::from_host(nd, cols, F.data());
    OperatorWorkspace w64, w32;
    linalg::DeviceMatrix V(ns, cols), D(5 * ns, cols), vr(rows, cols), dr(5 * rows, cols);
    apply_operators(*ops64, Fd.view(), V.view(), D.view(), w64);
    apply_operators_rows(*ops, Fd.view(), row0, rows, vr.view(), dr.view(), w32);
    const FloatBound tol(*ops, w32.coefficients.to_host());
    const auto Vh = V.to_host(), Dh = D.to_host(), vh = vr.to_host(), dh = dr.to_host();
    const double eps = 2 * std::numeric_limits<double>::epsilon();
    for (index_t c = 0; c < cols; ++c)
      for (index_t i = 0; i < rows; ++i) {
        EXPECT_NEAR(vh[i + c * rows], Vh[row0 + i + c * ns], tol.value(row0 + i, c) + std::abs(F[c * nd]) * eps);
        for (int q = 0; q < 5; ++q)
          EXPECT_NEAR(dh[q * rows + i + c * 5 * rows], Dh[q * ns + row0 + i + c * 5 * ns], tol.derivative(q * ns + row0 + i, c));
      }
  }
}

TEST(SinglePrecision, AnInterpolantWithoutTheConstantIsRefused) {
  const auto ops = rbf_operators(bauer_spiral(64), bauer_spiral(150), PhsBasis{7, -1});
  EXPECT_THROW(in_single_precision(*ops), InputError);
}
