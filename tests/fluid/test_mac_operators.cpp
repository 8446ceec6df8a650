// Unit tests of the MAC-grid operators: divergence = -gradient^T, D G = the Neumann Laplacian of
// eq. 2.9, exactness of divergence, gradient and the Div.-S2 advection (eq. 2.5) on polynomials next
// to every boundary type, and the projection leaving a discretely divergence-free field.
#include "../common/random_field.hpp"
#include "rbfib/fluid/mac_operators.hpp"
#include "rbfib/fluid/laplacian.hpp"
#include "rbfib/fluid/poisson.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace rbfib {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
using MB = MacBoundary;

MacGrid grid3(std::array<MB, 3> bc, std::array<int, 3> cells = {6, 5, 7}) {
  return make_mac_grid(3, cells, {1.2, 0.9, 1.1}, bc);
}

using rbfib::testing::random_vector;

const std::array<MB, 3> kBoundaryCases[] = {
    {MB::periodic, MB::periodic, MB::periodic}, {MB::periodic, MB::dirichlet, MB::periodic},
    {MB::dirichlet, MB::dirichlet, MB::dirichlet}, {MB::neumann, MB::dirichlet, MB::periodic},
    {MB::neumann, MB::neumann, MB::neumann},
};

TEST(MacOperators, DivergenceIsMinusGradientTranspose) {
  for (const auto& bc : kBoundaryCases)
    for (int dims : {2, 3}) {
      MacGrid g = grid3(bc);
      g.dims = dims;
      MacOperators ops(g);
      VectorField u, gq;
      for (int a = 0; a < dims; ++a) u[a] = random_vector(ops.component_box(a).size(), 10 + a);
      dvec q = random_vector(ops.scalar_box().size(), 3), du;
      ops.divergence(u, nullptr, du);
      ops.gradient(q, gq);
      double lhs = blas::dot(q, du), rhs = 0.0, scale = 0.0;
      for (int a = 0; a < dims; ++a) {
        rhs += blas::dot(gq[a], u[a]);
        scale += blas::norm2(gq[a]) * blas::norm2(u[a]);
      }
      // <q, D u> = -<G q, u>: a sum of O(n) products of O(1/h) terms; 64 eps of the scale.
      EXPECT_NEAR(lhs, -rhs, 64 * eps * scale) << to_string(bc[0]) << "/" << to_string(bc[1]) << "/" << to_string(bc[2])
                                               << " dims " << dims;
    }
}

TEST(MacOperators, DivergenceOfGradientIsTheNeumannLaplacian) {
  for (const auto& bc : kBoundaryCases) {
    MacOperators ops(grid3(bc));
    StaggeredLaplacian L(ops.scalar_box(), Correction::none);
    dvec q = random_vector(ops.scalar_box().size(), 7), dg, lq;
    VectorField gq;
    ops.gradient(q, gq);
    ops.divergence(gq, nullptr, dg);
    L.apply(q, lq);
    blas::axpy(-1.0, lq, dg);
    // entries O(|q| / h^2) with h >= 0.15: 16 eps of that.
    EXPECT_LT(blas::norm_inf(dg), 16 * eps * 4.0 / (0.15 * 0.15)) << to_string(bc[0]) << "/" << to_string(bc[1]);
  }
}

// A linear divergence-free field: d u/dx + dv/dy + dw/dz = 0.5 + 0.3 - 0.8 = 0.
struct Linear {
  double J[3][3] = {{0.5, 2.0, -1.0}, {3.0, 0.3, 0.7}, {-1.0, 0.4, -0.8}};
  double c[3] = {1.0, -0.5, 0.2};
  double operator()(int a, double x, double y, double z) const { return c[a] + J[a][0] * x + J[a][1] * y + J[a][2] * z; }
};

// Same, constant along x (for periodic x): dv/dy + dw/dz = 0.3 - 0.3 = 0.
struct LinearYZ {
  double J[3][3] = {{0.0, 2.0, -1.0}, {0.0, 0.3, 0.7}, {0.0, 0.4, -0.3}};
  double c[3] = {1.0, -0.5, 0.2};
  double operator()(int a, double x, double y, double z) const { return c[a] + J[a][0] * x + J[a][1] * y + J[a][2] * z; }
};

template <class Field>
void check_advection_exact(const MacGrid& g, const Field& F) {
  MacOperators ops(g);
  VectorField u, n;
  for (int a = 0; a < 3; ++a)
    u[a] = sample(ops.component_box(a), [&](double x, double y, double z) { return F(a, x, y, z); });
  VelocityBoundaryData gamma = sample_velocity_boundary(g, [&](int a, int d, int side, double x, double y, double z) {
    const BoundaryCondition bc = g.velocity_condition(a, d, side);
    return bc.kind == BoundaryKind::neumann ? (side ? -1.0 : 1.0) * F.J[a][d] : F(a, x, y, z);
  });
  ops.advection(u, gamma, n);
  for (int a = 0; a < 3; ++a) {
    // (u . grad) u_a = sum_b J[a][b] u_b (div u = 0), a quadratic: exact for Div.-S2.
    dvec exact = sample(ops.component_box(a), [&](double x, double y, double z) {
      double s = 0;
      for (int b = 0; b < 3; ++b) s += F.J[a][b] * F(b, x, y, z);
      return s;
    });
    blas::axpy(-1.0, exact, n[a]);
    // products of O(5) values over h ~ 0.15: 256 eps * 25 / 0.15.
    EXPECT_LT(blas::norm_inf(n[a]), 256 * eps * 25 / 0.15)
        << "component " << a << " " << to_string(g.lower[0]) << "/" << to_string(g.lower[1]) << "/" << to_string(g.lower[2]);
  }
  // the divergence with the normal boundary data is exact (zero) as well
  dvec div;
  ops.divergence(u, &gamma, div);
  EXPECT_LT(blas::norm_inf(div), 64 * eps * 10 / 0.15);
}

TEST(MacOperators, AdvectionExactOnLinearFieldsNearWalls) {
  check_advection_exact(grid3({MB::dirichlet, MB::dirichlet, MB::dirichlet}), Linear{});
  check_advection_exact(grid3({MB::neumann, MB::dirichlet, MB::neumann}), Linear{});
  check_advection_exact(grid3({MB::dirichlet, MB::neumann, MB::neumann}), Linear{});
  check_advection_exact(grid3({MB::periodic, MB::dirichlet, MB::dirichlet}), LinearYZ{});
  check_advection_exact(grid3({MB::periodic, MB::neumann, MB::dirichlet}), LinearYZ{});
}

TEST(MacOperators, GradientExactOnQuadratics) {
  MacOperators ops(grid3({MB::dirichlet, MB::neumann, MB::dirichlet}));
  auto q = [](double x, double y, double z) { return 0.3 + x * x - 2 * y * z + 0.5 * z * z + x * y; };
  auto dq = [](int a, double x, double y, double z) {
    return a == 0 ? 2 * x + y : a == 1 ? -2 * z + x : -2 * y + z;
  };
  VectorField g;
  ops.gradient(sample(ops.scalar_box(), q), g);
  for (int a = 0; a < 3; ++a) {
    dvec e = sample(ops.component_box(a), [&](double x, double y, double z) { return dq(a, x, y, z); });
    blas::axpy(-1.0, e, g[a]);
    EXPECT_LT(blas::norm_inf(g[a]), 64 * eps * 4 / 0.15);
  }
}

TEST(MacOperators, ProjectionLeavesDiscretelyDivergenceFreeField) {
  for (const auto& bc : kBoundaryCases) {
    MacGrid g = grid3(bc, {8, 8, 8});
    MacOperators ops(g);
    VectorField u, gq;
    for (int a = 0; a < 3; ++a) u[a] = random_vector(ops.component_box(a).size(), 20 + a);
    VelocityBoundaryData gamma = sample_velocity_boundary(g, [](int a, int d, int side, double x, double y, double z) {
      return 0.3 * a - 0.2 * d + 0.1 * side + std::sin(x + 2 * y + 3 * z);
    });
    ops.make_compatible(gamma);
    EXPECT_NEAR(ops.boundary_outflow(gamma), 0.0, 1e-14);
    dvec div, q;
    ops.divergence(u, &gamma, div);
    const double before = blas::norm_inf(div);
    PoissonSolver poisson(ops.scalar_box(), PoissonOptions{});
    blas::scale(-1.0, div);  // -L q = -D u
    poisson.solve(div, q);
    ops.gradient(q, gq);
    for (int a = 0; a < 3; ++a) blas::axpy(-1.0, gq[a], u[a]);
    ops.divergence(u, &gamma, div);
    // PCG stops at ||r|| <= 1e-11 ||b||; b has 512 entries of size ~before.
    EXPECT_LT(blas::norm_inf(div), 1e-11 * std::sqrt(512.0) * before) << to_string(bc[1]);
  }
}

}  // namespace
}  // namespace rbfib
