// Unit tests of the cortex's lattice (eqs. 99-100) and the membrane-cortex links (eqs. 101-102):
// forces are minus the derivative of their energy, the lattice's springs sum to zero and hold a
// tension 4 k on an equilateral lattice, the links balance to rounding, detached links carry no
// force, bad input raises errors naming the field.
#include "../common/errors.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/cortex.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace rbfib;
using namespace rbfib::mechanics;

namespace {

struct Sphere {
  std::vector<surface::Triangle> tris;
  std::vector<double> Z, X;  // reference and a perturbed state, n x 3
};

/// 200 spiral sites on a sphere of radius r, and a state moved off it irregularly.
Sphere sphere(double r) {
  const surface::SphereSites sites = surface::bauer_spiral(200);
  Sphere s;
  s.tris = surface::sphere_triangulation(sites);
  s.Z = surface::ellipsoid(r, r, r).points(sites);
  s.X = s.Z;
  for (std::size_t i = 0; i < s.X.size(); ++i) s.X[i] *= 0.9 + 0.05 * std::sin(3.0 * double(i));
  return s;
}

std::vector<double> fd_gradient(const std::function<double(const std::vector<double>&)>& E, std::vector<double> x, double h) {
  std::vector<double> g(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double x0 = x[i];
    x[i] = x0 + h;
    const double ep = E(x);
    x[i] = x0 - h;
    const double em = E(x);
    x[i] = x0;
    g[i] = (ep - em) / (2 * h);
  }
  return g;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST(Cortex, LatticeForceIsMinusTheGradientOfItsEnergy) {
  const Sphere s = sphere(2.0);
  const CortexLattice L = cortex_lattice(s.tris, s.Z, 0.7);
  const PointForces f = cortex_forces(L, s.X);
  const std::vector<double> g = fd_gradient([&](const std::vector<double>& x) { return cortex_forces(L, x).energy; }, s.X, 1e-6);
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_NEAR(f.F[i], -g[i], 1e-7 * max_abs(f.F)) << "entry " << i;
}

TEST(Cortex, LatticeForcesSumToZeroAndPullTheSphereIn) {
  // Internal forces: no net force; zero-rest-length springs in tension pull every site inward.
  const Sphere s = sphere(1.0);
  const CortexLattice L = cortex_lattice(s.tris, s.Z, 1.0);
  const PointForces f = cortex_forces(L, s.Z);
  const std::size_t n = s.Z.size() / 3;
  for (int d = 0; d < 3; ++d) {
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) sum += f.F[d * n + i];
    EXPECT_NEAR(sum, 0.0, 1e-13 * max_abs(f.F) * double(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    double radial = 0;
    for (int d = 0; d < 3; ++d) radial += f.F[d * n + i] * s.Z[d * n + i];
    EXPECT_LT(radial, 0.0) << "site " << i;
  }
}

TEST(Cortex, EquilateralLatticeHoldsTensionFourK) {
  // A flat triangular lattice of spacing a: an interior vertex's weight (eq. 67) is (sqrt 3 / 2)
  // a^2, each spring's kappa (eq. 100) is (4 / sqrt 3) k a, and the virial of the springs about an
  // interior vertex, (1 / 2) sum_j f_ij (x) r_ij / dA, is the isotropic tension 4 k at any
  // uniform stretch (zero rest length: the force grows as the length).
  const double a = 0.3, k = 2.0;
  const int rows = 7, cols = 7;
  std::vector<double> Z(3 * rows * cols, 0.0);
  const std::size_t n = std::size_t(rows * cols);
  auto id = [&](int r, int c) { return index_t(r * cols + c); };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      Z[std::size_t(id(r, c))] = a * (c + 0.5 * r);
      Z[n + std::size_t(id(r, c))] = a * std::sqrt(3.0) / 2 * r;
    }
  std::vector<surface::Triangle> tris;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c) {
      tris.push_back({id(r, c), id(r, c + 1), id(r + 1, c)});
      tris.push_back({id(r, c + 1), id(r + 1, c + 1), id(r + 1, c)});
    }
  const CortexLattice L = cortex_lattice(tris, Z, k);
  const index_t centre = id(3, 3);
  EXPECT_NEAR(L.dA[std::size_t(centre)], std::sqrt(3.0) / 2 * a * a, 1e-15);
  for (double stretch : {1.0, 1.7}) {
    std::vector<double> X = Z;
    for (double& x : X) x *= stretch;
    double sxx = 0, syy = 0, sxy = 0;
    for (std::size_t e = 0; e < L.edges.size(); ++e) {
      const index_t i = L.edges[e][0], j = L.edges[e][1];
      if (i != centre && j != centre) continue;
      EXPECT_NEAR(L.kappa[e], 4 / std::sqrt(3.0) * k * a, 1e-12);
      const double rx = X[std::size_t(i)] - X[std::size_t(j)], ry = X[n + std::size_t(i)] - X[n + std::size_t(j)];
      const double c = 0.5 * L.kappa[e] / L.length[e];  // half of |f| / |r|: each spring is shared by its two ends
      sxx += c * rx * rx, syy += c * ry * ry, sxy += c * rx * ry;
    }
    const double area = L.dA[std::size_t(centre)] * stretch * stretch;  // the vertex's share of the stretched plane
    EXPECT_NEAR(sxx / area, 4 * k, 1e-12) << "stretch " << stretch;
    EXPECT_NEAR(syy / area, 4 * k, 1e-12) << "stretch " << stretch;
    EXPECT_NEAR(sxy / area, 0.0, 1e-12) << "stretch " << stretch;
  }
}

TEST(Cortex, AdhesionBalancesEq102AndIsMinusTheGradientOfItsEnergy) {
  const Sphere c = sphere(1.0), m = sphere(1.01);
  const CortexLattice L = cortex_lattice(c.tris, c.Z, 1.0);
  const std::size_t n = c.Z.size() / 3;
  std::vector<char> attached(n, 1);
  const AdhesionForces a = adhesion_forces(m.X, c.Z, L.dA, 3.0, attached);
  for (std::size_t i = 0; i < 3 * n; ++i) EXPECT_EQ(a.on_membrane[i] + a.on_cortex[i], 0.0) << "entry " << i;  // eq. (102)
  const std::vector<double> g =
      fd_gradient([&](const std::vector<double>& x) { return adhesion_forces(x, c.Z, L.dA, 3.0, attached).energy; }, m.X, 1e-6);
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_NEAR(a.on_membrane[i], -g[i], 1e-7 * max_abs(a.on_membrane));
}

TEST(Cortex, ADetachedLinkCarriesNoForce) {
  const Sphere c = sphere(1.0), m = sphere(1.2);
  const CortexLattice L = cortex_lattice(c.tris, c.Z, 1.0);
  const std::size_t n = c.Z.size() / 3;
  std::vector<char> attached(n, 1);
  for (std::size_t i = 0; i < n; i += 3) attached[i] = 0;
  const AdhesionForces a = adhesion_forces(m.X, c.Z, L.dA, 3.0, attached);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      if (attached[i]) {
        EXPECT_NE(a.on_cortex[d * n + i], 0.0);
        continue;
      }
      EXPECT_EQ(a.on_cortex[d * n + i], 0.0) << "site " << i;
      EXPECT_EQ(a.on_membrane[d * n + i], 0.0) << "site " << i;
    }
}

TEST(Cortex, BadInputNamesTheField) {
  const Sphere s = sphere(1.0);
  using rbfib::testing::field_of;
  EXPECT_EQ(field_of([&] { cortex_lattice(s.tris, s.Z, -1.0); }), "cortex stiffness k (dyn/cm)");
  const CortexLattice L = cortex_lattice(s.tris, s.Z, 1.0);
  const std::vector<double> short_X(s.Z.begin(), s.Z.end() - 3);
  EXPECT_EQ(field_of([&] { cortex_forces(L, short_X); }), "cortex positions size");
  const std::vector<char> attached(s.Z.size() / 3, 1);
  EXPECT_EQ(field_of([&] { adhesion_forces(short_X, s.Z, L.dA, 1.0, attached); }), "membrane sites size");
  EXPECT_EQ(field_of([&] { adhesion_forces(s.Z, s.Z, L.dA, -1.0, attached); }), "adhesion stiffness k_adh (dyn/cm^3)");
}
