// Unit tests of the FFT plans and the Fourier (direct) solvers: the transforms invert each other
// and match a closed form; the direct solves equal the multigrid-preconditioned CG solves of the
// same discrete systems (channel: periodic x, z with walls in y; triply periodic) to what the PCG
// tolerance allows, with the residual at rounding; boxes they cannot handle are named.
#include "../common/random_field.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/fourier_solver.hpp"
#include "rbfib/fluid/helmholtz.hpp"
#include "rbfib/fluid/poisson.hpp"
#include "rbfib/grid/mac.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/linalg/fft.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace rbfib {
namespace {

using MB = MacBoundary;
using rbfib::testing::random_vector;

double relative_residual(const FourierSolver& S, const dvec& x, const dvec& b) {
  dvec r;
  S.apply(x, r);
  blas::axpy(-1.0, b, r);
  return blas::norm2(r) / blas::norm2(b);
}

constexpr double unit_roundoff = std::numeric_limits<double>::epsilon() / 2;

// ||A v - b||_2, A applied by S, plus what rounding can hide in it: each entry sums at most 16
// terms (7-point stencil, identity part, b), so it is within gamma_16 (|A||v| + |b|) of the
// exact residual; || |A| ||_2 <= abs_row_sum for symmetric A.
template <class Solver>
double residual_bound(const Solver& S, const dvec& v, const dvec& b, double abs_row_sum) {
  dvec r;
  S.apply(v, r);
  blas::axpy(-1.0, b, r);
  const double g16 = 16 * unit_roundoff / (1 - 16 * unit_roundoff);
  return blas::norm2(r) + g16 * (abs_row_sum * blas::norm2(v) + blas::norm2(b));
}

// x (direct) and q (PCG to rtol) solve A v = b for one symmetric A with smallest eigenvalue
// >= lambda_min on the space of x - q (mean-free vectors for the singular Poisson operator):
// A (x - q) = r_x - r_q, so ||x - q||_2 <= (||r_x|| + ||r_q||) / lambda_min. Each residual is
// taken with its own solver's operator, so a mismatch of operators still fails. (The former
// max|x - q| <= 1e-10 max|q| was tighter than rtol = 1e-13 guarantees: kappa sqrt(n) rtol ~ 7e-10.)
template <class Direct, class Iterative>
void expect_same_solution(const Direct& F, const dvec& x, const Iterative& S, const dvec& q, const dvec& b,
                          double lambda_min, double abs_row_sum, bool mean_free, const std::string& what) {
  dvec e = x;
  blas::axpy(-1.0, q, e);
  if (mean_free) remove_mean(e);  // the means themselves are checked by the caller
  const double bound = (residual_bound(F, x, b, abs_row_sum) + residual_bound(S, q, b, abs_row_sum)) / lambda_min;
  EXPECT_LT(bound, 1e-10 * blas::norm2(q)) << what;  // the comparison stays sharp
  EXPECT_LE(blas::norm2(e), bound) << what;
}

TEST(Fourier, TransformsInvertAndMatchTheDefinition) {
  for (std::array<bool, 3> t : {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, false, true}}) {
    const std::array<int, 3> n{6, 5, 4};
    linalg::FourierTransform F(n, t);
    const index_t size = 6 * 5 * 4;
    host_vector<linalg::complex> h(size);
    for (index_t p = 0; p < size; ++p) h[p] = linalg::complex(std::sin(0.3 * p), std::cos(0.7 * p));
    linalg::cvec v = h;
    F.forward(v);
    // Mode (1, 0, 2) (or (1, j, 2) per row j when y is batched) by the definition.
    const host_vector<linalg::complex> V = v;
    for (int j = 0; j < (t[1] ? 1 : 5); ++j) {
      linalg::complex want(0, 0);
      for (int z = 0; z < 4; ++z)
        for (int y = 0; y < (t[1] ? 5 : 1); ++y)
          for (int x = 0; x < 6; ++x) {
            const int yy = t[1] ? y : j;
            const double ph = -2 * pi * (1.0 * x / 6 + 2.0 * z / 4);
            want += h[x + 6 * (yy + 5 * z)] * linalg::complex(std::cos(ph), std::sin(ph));
          }
      const linalg::complex got = V[1 + 6 * (j + 5 * 2)];
      EXPECT_NEAR(got.real(), want.real(), 1e-12);
      EXPECT_NEAR(got.imag(), want.imag(), 1e-12);
    }
    F.backward(v);
    const host_vector<linalg::complex> back = v;
    for (index_t p = 0; p < size; ++p) {
      EXPECT_NEAR(back[p].real() / F.scale(), h[p].real(), 1e-13);
      EXPECT_NEAR(back[p].imag() / F.scale(), h[p].imag(), 1e-13);
    }
  }
}

// The real transform's spectrum is the first n_x / 2 + 1 modes along x of the complex transform of
// the same data, for odd and even n_x, with y transformed or batched, and backward takes it back.
TEST(Fourier, RealTransformIsTheHalfSpectrum) {
  for (int nx : {6, 7})
    for (std::array<bool, 3> t : {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, false, true}}) {
      const std::array<int, 3> n{nx, 5, 4};
      linalg::FourierTransform C(n, t);
      linalg::RealFourierTransform R(n, t);
      ASSERT_EQ(R.half(), nx / 2 + 1);
      const index_t size = index_t(nx) * 5 * 4;
      host_vector<double> h(size);
      host_vector<linalg::complex> hc(size);
      for (index_t p = 0; p < size; ++p) h[p] = std::sin(0.3 * p) + 0.1 * std::cos(1.7 * p), hc[p] = linalg::complex(h[p], 0.0);
      linalg::cvec full = hc, half;
      C.forward(full);
      const dvec real = h;
      R.forward(real, half);
      const host_vector<linalg::complex> F = full, H = half;
      ASSERT_EQ(index_t(H.size()), R.spectrum_size());
      for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 5; ++j)
          for (int i = 0; i < R.half(); ++i) {
            const linalg::complex a = F[i + nx * (j + 5 * k)], b = H[i + R.half() * (j + 5 * k)];
            EXPECT_NEAR(b.real(), a.real(), 1e-12) << nx << " " << i << " " << j << " " << k;
            EXPECT_NEAR(b.imag(), a.imag(), 1e-12) << nx << " " << i << " " << j << " " << k;
          }
      const host_vector<double> unchanged = real;
      for (index_t p = 0; p < size; ++p) EXPECT_EQ(unchanged[p], h[p]);  // the input is kept
      dvec back;
      R.backward(half, back);
      const host_vector<double> B = back;
      for (index_t p = 0; p < size; ++p) EXPECT_NEAR(B[p] / R.scale(), h[p], 1e-13);
    }
  EXPECT_THROW(linalg::RealFourierTransform({1, 4, 4}, {true, false, true}), InputError);
  EXPECT_THROW(linalg::RealFourierTransform({4, 4, 4}, {false, true, true}), InputError);
}

TEST(Fourier, ChannelPoissonEqualsMultigridPcg) {
  // The pressure box of a channel (cell centres; Neumann walls in y, no correction as eq. 2.9),
  // 3D and 2D: both solve -L q = b with b mean-free and return mean-free q; PCG runs to 1e-13.
  for (int dims : {2, 3}) {
    const MacGrid g = make_mac_grid(dims, {16, 12, 8}, {1.6, 1.2, 0.8}, {MB::periodic, MB::dirichlet, MB::periodic});
    const Box box = g.scalar();
    FourierSolver F(box, Correction::none, 0.0, -1.0, "poisson");
    ASSERT_TRUE(F.singular());
    PoissonOptions o;
    o.solver = SolverOptions{"poisson", 1e-13, 500};
    PoissonSolver P(box, o);
    dvec b = random_vector(box.size(), 3), q(box.size(), 0.0), x;
    P.solve(b, q);  // b made mean-free
    F.solve(b, x);
    EXPECT_LT(relative_residual(F, x, b), 1e-12) << dims << "D";
    for (const dvec* v : {&x, &q})  // mean-free: a sum of n terms rounds to n u sum |v| at most
      EXPECT_NEAR(thrust::reduce(v->begin(), v->end(), 0.0), 0.0, 1e-12 * blas::norm_inf(*v) * double(v->size())) << dims << "D";
    // -L: lambda_min the smallest nonzero eigenvalue (closed form); || |L| || <= Gershgorin's bound.
    expect_same_solution(F, x, P, q, b, smallest_nonzero_eigenvalue(box), gershgorin_bounds(P.laplacian(), 0.0, -1.0).lambda_max,
                         true, std::to_string(dims) + "D");
  }
}

TEST(Fourier, ChannelHelmholtzEqualsPcgOnEveryComponent) {
  // H = I~ - c L with the Appendix A correction, Dirichlet or Neumann walls in y, each MAC
  // component (faces and centres along y): the direct solve equals PCG (to 1e-13).
  for (MB wall : {MB::dirichlet, MB::neumann}) {
    const MacGrid g = make_mac_grid(3, {16, 12, 8}, {1.6, 1.2, 0.8}, {MB::periodic, wall, MB::periodic});
    for (int a = 0; a < 3; ++a) {
      const Box box = g.component(a);
      const double c = 0.05;
      FourierSolver F(box, Correction::appendix_a, 1.0, -c, "helmholtz");
      EXPECT_FALSE(F.singular());
      HelmholtzOptions o;
      o.solver = SolverOptions{"helmholtz", 1e-13, 1000};
      HelmholtzSolver H(box, c, o);
      const dvec b = random_vector(box.size(), 10 + a);
      dvec u(box.size(), 0.0), x;
      H.solve(b, u);
      F.solve(b, x);
      EXPECT_LT(relative_residual(F, x, b), 1e-12) << "component " << a;
      // H SPD: Gershgorin's interval encloses its spectrum, and its upper end bounds || |H| ||.
      expect_same_solution(F, x, H, u, b, H.bounds().lambda_min, H.bounds().lambda_max, false,
                           "component " + std::to_string(a));
    }
  }
}

TEST(Fourier, TriplyPeriodicSolvesAreExactToRounding) {
  const MacGrid g = make_mac_grid(3, {16, 10, 8}, {1.6, 1.0, 0.8}, {MB::periodic, MB::periodic, MB::periodic});
  for (int a = 0; a < 3; ++a) {
    FourierSolver F(g.component(a), Correction::appendix_a, 1.0, -0.05, "helmholtz");
    const dvec b = random_vector(g.component(a).size(), 20 + a);
    dvec x;
    F.solve(b, x);
    EXPECT_LT(relative_residual(F, x, b), 1e-12);
  }
  FourierSolver P(g.scalar(), Correction::none, 0.0, -1.0, "poisson");
  ASSERT_TRUE(P.singular());
  dvec b = random_vector(g.scalar().size(), 30), x;
  remove_mean(b);
  P.solve(b, x);
  EXPECT_LT(relative_residual(P, x, b), 1e-12);
  EXPECT_NEAR(thrust::reduce(x.begin(), x.end(), 0.0), 0.0, 1e-12 * blas::norm_inf(x) * double(x.size()));
}

TEST(Fourier, BoxesWithWallsAcrossXAreNamed) {
  const MacGrid g = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::dirichlet, MB::periodic, MB::periodic});
  EXPECT_FALSE(FourierSolver::applies(g.scalar()));
  EXPECT_THROW(FourierSolver(g.scalar(), Correction::none, 0.0, -1.0, "poisson"), InputError);
  const MacGrid c = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::periodic});
  EXPECT_THROW(FourierSolver(c.scalar(), Correction::none, 0.0, 1.0, "poisson"), InputError);  // beta > 0
}

}  // namespace
}  // namespace rbfib
