// Unit tests of the IB kernels (seed Fig. 5.1) and of the compile-time shifts (Alg. 4.1):
// the defining moment conditions of each kernel, checked at many offsets r against their exact
// values, and the lexicographic order of the shifts.
#include "rbfib/ib/kernels.hpp"
#include "rbfib/ib/shifts.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace rbfib::ib {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
// Each phi(r) is a few operations and at most one sqrt or cos: relative error below 4 eps; a sum
// of at most 5 nonzero terms of size <= 1 adds 5 eps. 32 eps bounds both with margin; moments
// carry a factor |r - j| <= 2 (first) or 4 (second).
constexpr double tol = 32 * eps;

struct Moments {
  double sum = 0, even = 0, odd = 0, first = 0, second = 0, squares = 0;
};

template <class K>
Moments moments(double r) {
  Moments m;
  for (int j = -6; j <= 6; ++j) {
    const double p = K::phi(r - j);
    m.sum += p;
    (j % 2 == 0 ? m.even : m.odd) += p;
    m.first += (r - j) * p;
    m.second += (r - j) * (r - j) * p;
    m.squares += p * p;
  }
  return m;
}

// Offsets in [0, 1): a fine uniform sweep plus the breakpoints of the piecewise kernels.
template <class F>
void for_offsets(F f) {
  for (int i = 0; i < 1000; ++i) f(i / 1000.0 + 1e-4 * std::sin(i));
  for (double r : {0.0, 0.5, 0.25, 1.0 - eps, eps}) f(r);
}

TEST(IbKernels, NamesAndSupports) {
  EXPECT_EQ(kernel_names().size(), 4u);
  EXPECT_EQ(kernel_support(Kernel::roma3), 3);
  EXPECT_EQ(kernel_support(Kernel::bspline3), 4);
  EXPECT_EQ(kernel_support(Kernel::cosine4), 4);
  EXPECT_EQ(kernel_support(Kernel::peskin4), 4);
  try {
    kernel_named("gaussian");
    FAIL() << "an unknown kernel name must throw";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "kernel");
    EXPECT_NE(std::string(e.what()).find("gaussian"), std::string::npos);
  }
}

template <class K>
void expect_support_and_sign() {
  const double half = K::support / 2.0;
  for (double r = -half - 1.0; r <= half + 1.0; r += 0.01) {
    const double p = K::phi(r);
    EXPECT_GE(p, 0.0) << K::name << " r=" << r;
    EXPECT_EQ(p, K::phi(-r)) << K::name << " must be even, r=" << r;
    if (std::abs(r) >= half) {
      EXPECT_EQ(p, 0.0) << K::name << " outside the support, r=" << r;
    }
  }
  // Continuity at the support edge and the breakpoints (a jump would show as a large difference).
  for (double b : {0.5, 1.0, 1.5, 2.0}) EXPECT_NEAR(K::phi(b - 1e-12), K::phi(b + 1e-12), 1e-5) << K::name << " at " << b;
}

TEST(IbKernels, SupportSymmetryPositivity) {
  expect_support_and_sign<Roma3>();
  expect_support_and_sign<BSpline3>();
  expect_support_and_sign<Cosine4>();
  expect_support_and_sign<Peskin4>();
}

TEST(IbKernels, ValuesAtZero) {
  EXPECT_NEAR(Roma3::phi(0.0), 2.0 / 3.0, 2 * eps);
  EXPECT_NEAR(BSpline3::phi(0.0), 2.0 / 3.0, 2 * eps);
  EXPECT_NEAR(BSpline3::phi(1.0), 1.0 / 6.0, 2 * eps);
  EXPECT_NEAR(Cosine4::phi(0.0), 0.5, 2 * eps);
  EXPECT_NEAR(Cosine4::phi(1.0), 0.25, 2 * eps);
  EXPECT_NEAR(Peskin4::phi(0.0), 0.5, 2 * eps);
  EXPECT_NEAR(Peskin4::phi(1.0), 0.25, 2 * eps);
}

TEST(IbKernels, Roma3Moments) {
  for_offsets([](double r) {
    const Moments m = moments<Roma3>(r);
    EXPECT_NEAR(m.sum, 1.0, tol) << r;
    EXPECT_NEAR(m.first, 0.0, 2 * tol) << r;
    EXPECT_NEAR(m.squares, 0.5, tol) << r;
  });
}

TEST(IbKernels, BSpline3Moments) {
  for_offsets([](double r) {
    const Moments m = moments<BSpline3>(r);
    EXPECT_NEAR(m.sum, 1.0, tol) << r;
    EXPECT_NEAR(m.first, 0.0, 2 * tol) << r;
    EXPECT_NEAR(m.second, 1.0 / 3.0, 4 * tol) << r;
  });
  // B3 has no even-odd condition: at r = 0 the even points carry 2/3 + 0 + 0, the odd 1/6 + 1/6.
  const Moments m0 = moments<BSpline3>(0.0);
  EXPECT_NEAR(m0.even, 2.0 / 3.0, tol);
}

TEST(IbKernels, Cosine4Moments) {
  double max_first = 0.0;
  for_offsets([&](double r) {
    const Moments m = moments<Cosine4>(r);
    EXPECT_NEAR(m.sum, 1.0, tol) << r;
    EXPECT_NEAR(m.even, 0.5, tol) << r;
    EXPECT_NEAR(m.odd, 0.5, tol) << r;
    EXPECT_NEAR(m.squares, 3.0 / 8.0, tol) << r;
    max_first = std::max(max_first, std::abs(m.first));
  });
  // The cosine kernel does not satisfy the first-moment condition (documented in its header).
  EXPECT_GT(max_first, 1e-3);
}

TEST(IbKernels, Peskin4Moments) {
  for_offsets([](double r) {
    const Moments m = moments<Peskin4>(r);
    EXPECT_NEAR(m.sum, 1.0, tol) << r;
    EXPECT_NEAR(m.even, 0.5, tol) << r;
    EXPECT_NEAR(m.odd, 0.5, tol) << r;
    EXPECT_NEAR(m.first, 0.0, 2 * tol) << r;
    EXPECT_NEAR(m.squares, 3.0 / 8.0, tol) << r;
  });
}

TEST(IbShifts, Algorithm41Order) {
  using S4 = Shifts<4, 3>;
  static_assert(S4::count == 64);
  static_assert(S4::value[0][0] == -2 && S4::value[0][1] == -2 && S4::value[0][2] == -2);
  static_assert(S4::value[1][0] == -1 && S4::value[1][1] == -2);
  static_assert(S4::value[4][0] == -2 && S4::value[4][1] == -1);
  static_assert(S4::value[63][0] == 1 && S4::value[63][1] == 1 && S4::value[63][2] == 1);
  using S3 = Shifts<3, 3>;
  static_assert(S3::count == 27);
  static_assert(S3::value[0][0] == -1 && S3::value[26][2] == 1);
  // Every shift appears once, in lexicographic order with the first component fastest.
  for (int j = 0; j < S4::count; ++j) {
    EXPECT_EQ(S4::value[j][0], j % 4 - 2);
    EXPECT_EQ(S4::value[j][1], (j / 4) % 4 - 2);
    EXPECT_EQ(S4::value[j][2], j / 16 - 2);
  }
}

}  // namespace
}  // namespace rbfib::ib

namespace rbfib::ib {
namespace {

// The closed-form axis weights equal s evaluations of phi at the shifted offsets: both are a few
// operations and one sqrt/cos away from the exact value, 16 eps apart at most.
template <class K>
void expect_axis_weights_match_phi() {
  const int S = K::support;
  for (int i = 0; i <= 1000; ++i) {
    const double delta = (S % 2 == 0) ? (i == 0 ? 1e-17 : i / 1000.0) : (i == 0 ? -0.5 + 1e-12 : -0.5 + i / 1000.0);
    double w[8];
    axis_weights<K>(delta, w);
    double sum = 0.0;
    for (int t = 0; t < S; ++t) {
      EXPECT_NEAR(w[t], K::phi(t - S / 2 + delta), 16 * eps) << K::name << " delta=" << delta << " t=" << t;
      sum += w[t];
    }
    EXPECT_NEAR(sum, 1.0, 8 * eps) << K::name << " delta=" << delta;
  }
}

TEST(IbKernels, AxisWeightsMatchPhi) {
  expect_axis_weights_match_phi<Roma3>();
  expect_axis_weights_match_phi<BSpline3>();
  expect_axis_weights_match_phi<Cosine4>();
  expect_axis_weights_match_phi<Peskin4>();
}

}  // namespace
}  // namespace rbfib::ib
