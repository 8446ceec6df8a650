// Unit tests of interpolation and spreading (seed Algs. 4.2-4.6): every algorithm against a direct
// evaluation of the definitions f(x) = sum_k F_k delta_h(x - X_k) and U(X) = sum_x u(x)
// delta_h(x - X) h^3 (periodic images along periodic axes, only the box's unknowns along walls),
// every spreading variant against serial Alg. 4.2, adjointness <S F, u> h^3 = <F, I u>,
// conservation of the total force, and the errors on bad input.
//
// Tolerances come from the summation-order bound for sums of nonnegative weights times data:
// two orders of a sum of N terms differ by at most 2 (N - 1) eps sum |terms|; we bound N by the
// number of points whose support contains the unknown (counted by the direct evaluation) plus
// a few eps for the different association of the weight product.
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/ib/kernels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace rbfib::ib {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
using HostPoints = std::vector<double>;  // x..., y..., z...

std::function<double(double)> phi_of(const std::string& kernel) {
  std::function<double(double)> f;
  with_kernel(kernel_named(kernel), [&](auto k) { f = [](double r) { return decltype(k)::phi(r); }; });
  return f;
}

// Direct evaluation from the definitions: value, sum of |terms|, sum of |F| / h^3 over the
// contributing points, and the number of contributing points, per unknown of each component.
struct Direct {
  std::array<std::vector<double>, 3> f, abs, absF;
  std::array<std::vector<int>, 3> count;
};

double image_distance(const Axis& ax, double x, double X) {
  double r = x - X;
  if (ax.periodic()) r -= ax.length * std::round(r / ax.length);
  return r;
}

// 1D weights phi((x_i - X)/h) of one point along one axis of a box, as (i, w) pairs, for all i
// with |x_i - X| <= (s/2 + 1e-9) h: points on the edge of the support are kept (with their
// possibly zero weight) because rounding may put them on either side of it.
std::vector<std::pair<int, double>> weights_1d(const std::function<double(double)>& phi, const Box& b, int a, double X) {
  std::vector<std::pair<int, double>> w;
  for (int i = 0; i < b.n(a); ++i) {
    const double r = image_distance(b.axes[a], b.x(a, i), X) / b.axes[a].h();
    if (std::abs(r) <= 2.0 + 1e-9) w.push_back({i, phi(r)});
  }
  return w;
}

template <class Visit>
void for_support(const std::function<double(double)>& phi, const Box& b, const HostPoints& X, size_t n, size_t k, Visit visit) {
  const auto wx = weights_1d(phi, b, 0, X[k]), wy = weights_1d(phi, b, 1, X[n + k]), wz = weights_1d(phi, b, 2, X[2 * n + k]);
  for (auto [iz, vz] : wz)
    for (auto [iy, vy] : wy)
      for (auto [ix, vx] : wx) visit(ix + index_t(b.n(0)) * (iy + index_t(b.n(1)) * iz), vx * vy * vz);
}

Direct direct_spread(const std::array<Box, 3>& boxes, const std::string& kernel, const HostPoints& X, const HostPoints& F) {
  const auto phi = phi_of(kernel);
  const size_t n = X.size() / 3;
  Direct d;
  for (int c = 0; c < 3; ++c) {
    const Box& b = boxes[c];
    d.f[c].assign(b.size(), 0.0);
    d.abs[c].assign(b.size(), 0.0);
    d.absF[c].assign(b.size(), 0.0);
    d.count[c].assign(b.size(), 0);
    const double vol = b.axes[0].h() * b.axes[1].h() * b.axes[2].h();
    for (size_t k = 0; k < n; ++k)
      for_support(phi, b, X, n, k, [&](index_t m, double w) {
        d.f[c][m] += w * F[c * n + k] / vol;
        d.abs[c][m] += std::abs(w * F[c * n + k] / vol);
        d.absF[c][m] += std::abs(F[c * n + k] / vol);
        d.count[c][m] += 1;
      });
  }
  return d;
}

HostPoints direct_interpolate(const std::array<Box, 3>& boxes, const std::string& kernel, const HostPoints& X,
                              const std::array<std::vector<double>, 3>& u) {
  const auto phi = phi_of(kernel);
  const size_t n = X.size() / 3;
  HostPoints U(3 * n, 0.0);
  for (int c = 0; c < 3; ++c)
    for (size_t k = 0; k < n; ++k) {
      double v = 0.0;
      for_support(phi, boxes[c], X, n, k, [&](index_t m, double w) { v += w * u[c][m]; });
      U[c * n + k] = v;
    }
  return U;
}

// Non-cubic cells of different widths, to catch axis mix-ups.
constexpr std::array<int, 3> kCells = {12, 8, 20};
constexpr std::array<double, 3> kLength = {1.2, 1.0, 1.6};

std::array<Box, 3> boxes_for(bool walls) {
  return mac_boxes(kCells, kLength, {true, !walls, !walls});
}

enum class Layout { random, clustered, seams, walls };

HostPoints make_points(Layout layout, size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  HostPoints X(3 * n);
  for (size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) {
      const double L = kLength[a], h = L / kCells[a];
      double x = 0.0;
      switch (layout) {
        case Layout::random: x = L * U01(rng); break;
        case Layout::clustered: x = 0.37 * L + 0.3 * h * U01(rng); break;
        case Layout::seams: {
          // On the periodic seam, just inside and outside it, on cell faces and centres.
          const double choices[] = {0.0, L, -1e-14, L - 1e-14, L + 1e-14, 3 * h, 3.5 * h, -0.4 * h, L + 0.7 * h};
          x = choices[(k * 7 + a * 3) % 9];
          if (k % 5 == 4) x = h * std::floor(kCells[a] * U01(rng));
          break;
        }
        case Layout::walls: {
          // Within two cells of either end, and exactly on the ends (walls along y and z).
          const double r = 2.0 * h * U01(rng);
          const int pick = int(k % 6);
          x = pick == 0 ? 0.0 : pick == 1 ? L : pick % 2 ? r : L - r;
          break;
        }
      }
      X[a * n + k] = x;
    }
  return X;
}

HostPoints random_values(size_t m, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  HostPoints v(m);
  for (double& x : v) x = U(rng);
  return v;
}

struct Case {
  std::string kernel;
  Layout layout;
  bool walls;
  size_t n;
};

std::string name_of(const Case& c) {
  const char* layouts[] = {"random", "clustered", "seams", "walls"};
  return c.kernel + "/" + layouts[int(c.layout)] + (c.walls ? "/walls" : "/periodic");
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const std::string& name : kernel_names()) {
    cases.push_back({name, Layout::random, false, 600});
    cases.push_back({name, Layout::clustered, false, 300});
    cases.push_back({name, Layout::seams, false, 200});
    cases.push_back({name, Layout::random, true, 600});
    cases.push_back({name, Layout::walls, true, 300});
  }
  return cases;
}

// |a - b| <= bound for every unknown, bound = (2 count + 8) eps abs (summation-order bound above)
// plus argument_eps * absF: the direct evaluation forms the kernel argument (x_i - X)/h, the
// algorithms form cell - ((X - origin)/h - g); both are within 4 N eps of the exact value in
// units of h on an axis of N cells, and |phi'| <= 1, so each product of three 1D weights differs
// by at most 12 N eps.
void expect_equal_to_rounding(const std::vector<double>& got, const std::vector<double>& want,
                              const std::vector<double>& abs, const std::vector<int>& count, const std::string& what,
                              const std::vector<double>* absF = nullptr, double argument_eps = 0.0) {
  ASSERT_EQ(got.size(), want.size()) << what;
  int bad = 0;
  for (size_t m = 0; m < got.size(); ++m) {
    const double bound = (2.0 * count[m] + 8.0) * eps * abs[m] + (absF ? argument_eps * (*absF)[m] : 0.0);
    if (!(std::abs(got[m] - want[m]) <= bound) && bad++ < 5)
      ADD_FAILURE() << what << ": unknown " << m << " got " << got[m] << " want " << want[m] << " bound " << bound;
  }
  EXPECT_EQ(bad, 0) << what;
}

std::vector<double> to_host(const dvec& v) {
  host_vector<double> h = v;
  return std::vector<double>(h.begin(), h.end());
}

TEST(IbInteraction, SpreadingVariantsEqualSerialAndDefinition) {
  for (const Case& c : all_cases()) {
    const auto boxes = boxes_for(c.walls);
    Interaction ib(boxes, kernel_named(c.kernel));
    const HostPoints X = make_points(c.layout, c.n, 7);
    const HostPoints F = random_values(3 * c.n, 11);
    const Direct direct = direct_spread(boxes, c.kernel, X, F);
    const dvec dX(X.begin(), X.end()), dF(F.begin(), F.end());
    std::array<dvec, 3> serial, serial_abs;
    ib.spread(dX, dF, serial, Spreading::serial);
    HostPoints absF(F);
    for (double& v : absF) v = std::abs(v);
    ib.spread(dX, dvec(absF.begin(), absF.end()), serial_abs, Spreading::serial);  // S|F| = sum |terms|
    for (int k = 0; k < 3; ++k)
      expect_equal_to_rounding(to_host(serial[k]), direct.f[k], direct.abs[k], direct.count[k],
                               name_of(c) + " serial vs definition, component " + std::to_string(k), &direct.absF[k],
                               12.0 * 20 * eps);  // N <= 20 cells
    for (Spreading alg : all_spreadings()) {
      std::array<dvec, 3> f;
      for (int repeat = 0; repeat < 2; ++repeat) {  // twice: the preallocated buffer must be left zero
        ib.spread(dX, dF, f, alg);
        for (int k = 0; k < 3; ++k)
          // The binned variant evaluates the weights of an axis in closed form (kernel weights()),
          // within 16 eps of phi in absolute terms (test AxisWeightsMatchPhi): 48 eps per product.
          expect_equal_to_rounding(to_host(f[k]), to_host(serial[k]), to_host(serial_abs[k]), direct.count[k],
                                   name_of(c) + " " + to_string(alg) + " vs serial, component " + std::to_string(k),
                                   &direct.absF[k], 48 * eps);
      }
    }
  }
}

TEST(IbInteraction, InterpolationVariantsEqualDefinition) {
  for (const Case& c : all_cases()) {
    const auto boxes = boxes_for(c.walls);
    Interaction ib(boxes, kernel_named(c.kernel));
    const HostPoints X = make_points(c.layout, c.n, 5);
    std::array<std::vector<double>, 3> u;
    std::array<dvec, 3> du;
    for (int k = 0; k < 3; ++k) {
      u[k] = random_values(boxes[k].size(), 20 + k);
      du[k] = dvec(u[k].begin(), u[k].end());
    }
    const HostPoints want = direct_interpolate(boxes, c.kernel, X, u);
    const dvec dX(X.begin(), X.end());
    // Each value is a sum of at most s^3 <= 64 terms |w u| <= 1 with sum w <= 1: the bound
    // (2 * 64 + 8) eps covers any summation order; the kernel arguments differ by up to 12 N eps
    // per weight (see expect_equal_to_rounding), N <= 20, and the weights sum to at most 1.
    const double tol = (2.0 * 64 + 8) * eps + 12.0 * 20 * eps + 48 * eps;  // + closed-form weights
    for (Interpolation alg : all_interpolations()) {
      dvec U;
      ib.interpolate(dX, du, U, alg);
      const auto got = to_host(U);
      double worst = 0.0;
      for (size_t i = 0; i < got.size(); ++i) worst = std::max(worst, std::abs(got[i] - want[i]));
      EXPECT_LE(worst, tol) << name_of(c) << " " << to_string(alg);
    }
  }
}

TEST(IbInteraction, SpreadingIsAdjointOfInterpolation) {
  for (const Case& c : all_cases()) {
    const auto boxes = boxes_for(c.walls);
    Interaction ib(boxes, kernel_named(c.kernel));
    const HostPoints X = make_points(c.layout, c.n, 3);
    const HostPoints F = random_values(3 * c.n, 4);
    std::array<dvec, 3> du;
    std::array<std::vector<double>, 3> u;
    for (int k = 0; k < 3; ++k) {
      u[k] = random_values(boxes[k].size(), 30 + k);
      du[k] = dvec(u[k].begin(), u[k].end());
    }
    const dvec dX(X.begin(), X.end()), dF(F.begin(), F.end());
    for (Spreading alg : all_spreadings()) {
      std::array<dvec, 3> f;
      ib.spread(dX, dF, f, alg);
      dvec U;
      ib.interpolate(dX, du, U, Interpolation::binned);
      const auto Uh = to_host(U);
      double lhs = 0.0, rhs = 0.0, scale = 0.0;
      for (int k = 0; k < 3; ++k) {
        const auto fh = to_host(f[k]);
        for (size_t m = 0; m < fh.size(); ++m) lhs += fh[m] * u[k][m] * ib.cell_volume();
      }
      for (size_t i = 0; i < F.size(); ++i) {
        rhs += F[i] * Uh[i];
        scale += std::abs(F[i]);  // |u| <= 1 and the weights sum to <= 1
      }
      // Both sides sum the same n s^3 products in different orders; with all partial sums of
      // |terms| <= scale, (s^3 + n + grid + 8) eps scale bounds the difference.
      const double bound = (64.0 + c.n + boxes[0].size() + 8.0) * eps * scale;
      EXPECT_NEAR(lhs, rhs, bound) << name_of(c) << " " << to_string(alg);
    }
  }
}

TEST(IbInteraction, TotalForceIsConserved) {
  for (const Case& c : all_cases()) {
    if (c.layout == Layout::walls) continue;  // supports cut by the wall lose force by design
    const auto boxes = boxes_for(c.walls);
    Interaction ib(boxes, kernel_named(c.kernel));
    HostPoints X = make_points(c.layout, c.n, 9);
    if (c.walls)  // keep supports away from the walls along y and z: x in [3h, L - 3h]
      for (int a = 1; a < 3; ++a) {
        const double h = kLength[a] / kCells[a];
        for (size_t k = 0; k < c.n; ++k) X[a * c.n + k] = 3 * h + (kLength[a] - 6 * h) * (X[a * c.n + k] / kLength[a]);
      }
    const HostPoints F = random_values(3 * c.n, 10);
    const dvec dX(X.begin(), X.end()), dF(F.begin(), F.end());
    for (Spreading alg : all_spreadings()) {
      std::array<dvec, 3> f;
      ib.spread(dX, dF, f, alg);
      for (int k = 0; k < 3; ++k) {
        double total = 0.0, want = 0.0, scale = 0.0;
        for (double v : to_host(f[k])) total += v * ib.cell_volume();
        for (size_t i = 0; i < c.n; ++i) {
          want += F[k * c.n + i];
          scale += std::abs(F[k * c.n + i]);
        }
        const double bound = (64.0 + c.n + boxes[k].size() + 8.0) * eps * scale;
        EXPECT_NEAR(total, want, bound) << name_of(c) << " " << to_string(alg) << " component " << k;
      }
    }
  }
}

TEST(IbInteraction, PeriodicImagesGiveTheSameResult) {
  const auto boxes = boxes_for(false);
  Interaction ib(boxes, Kernel::bspline3);
  const size_t n = 100;
  HostPoints X = make_points(Layout::random, n, 1), Y = X;
  for (size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) Y[a * n + k] += (k % 3 == 0 ? -2.0 : 1.0) * kLength[a];
  const HostPoints F = random_values(3 * n, 2);
  std::array<dvec, 3> f, g;
  ib.spread(dvec(X.begin(), X.end()), dvec(F.begin(), F.end()), f, Spreading::binned);
  ib.spread(dvec(Y.begin(), Y.end()), dvec(F.begin(), F.end()), g, Spreading::binned);
  for (int k = 0; k < 3; ++k) {
    const auto a = to_host(f[k]), b = to_host(g[k]);
    // x + k L (|k| <= 2) is exact to 2 ulp of 3 L; a weight moves by at most |phi'| <= 1 times that
    // over h, 60 eps (3 L / h <= 60); at most 64 points of |F| / h^3 <= 1 / (0.1 0.125 0.08) = 1000
    // reach an unknown: 64 * 60 eps * 1000 = 8.5e-10.
    for (size_t m = 0; m < a.size(); ++m) EXPECT_NEAR(a[m], b[m], 1e-9) << m;
  }
}

template <class F>
void expect_input_error(F f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "expected InputError for " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

TEST(IbInteraction, BadInputIsReported) {
  const auto walls = boxes_for(true);
  Interaction ib(walls, Kernel::peskin4);
  const size_t n = 10;
  HostPoints X = make_points(Layout::random, n, 1);
  const HostPoints F(3 * n, 1.0);
  std::array<dvec, 3> f;
  std::array<dvec, 3> u = {dvec(walls[0].size(), 0.0), dvec(walls[1].size(), 0.0), dvec(walls[2].size(), 0.0)};
  dvec U;
  for (Spreading alg : all_spreadings()) {
    HostPoints Y = X;
    Y[2 * n + 3] = kLength[2] + 1e-9;  // outside the wall along z
    expect_input_error([&] { ib.spread(dvec(Y.begin(), Y.end()), dvec(F.begin(), F.end()), f, alg); }, "X[3].z");
    Y = X;
    Y[n + 4] = -1e-12;  // below the wall along y
    expect_input_error([&] { ib.spread(dvec(Y.begin(), Y.end()), dvec(F.begin(), F.end()), f, alg); }, "X[4].y");
    Y = X;
    Y[5] = std::nan("");
    expect_input_error([&] { ib.spread(dvec(Y.begin(), Y.end()), dvec(F.begin(), F.end()), f, alg); }, "X[5].x");
  }
  for (Interpolation alg : all_interpolations()) {
    HostPoints Y = X;
    Y[n + 7] = std::numeric_limits<double>::infinity();
    expect_input_error([&] { ib.interpolate(dvec(Y.begin(), Y.end()), u, U, alg); }, "X[7].y");
  }
  expect_input_error([&] { ib.spread(dvec(X.begin(), X.end()), dvec(F.begin(), F.end() - 3), f); }, "F.size");
  expect_input_error([&] { ib.interpolate(dvec(X.begin(), X.end()), {dvec(5), u[1], u[2]}, U); }, "u[0].size");
  // A kernel wider than the grid.
  expect_input_error([] { Interaction(mac_boxes({3, 8, 8}, {1.0, 1.0, 1.0}, {true, true, true}), Kernel::bspline3); }, "grid.x.cells");
  expect_input_error([] { Interaction(mac_boxes({8, 8, 2}, {1.0, 1.0, 1.0}, {true, true, true}), Kernel::roma3); }, "grid.z.cells");
  expect_input_error([] { kernel_named("delta"); }, "kernel");
}

TEST(IbGrid, KeysAreInjectiveAndInvertible) {
  for (bool walls : {false, true}) {
    const auto boxes = boxes_for(walls);
    for (int c = 0; c < 3; ++c) {
      const ComponentGrid g = make_component_grid(boxes[c], 4);
      std::vector<int> seen(size_t(g.axis[0].key_extent) * g.axis[1].key_extent * g.axis[2].key_extent, 0);
      auto range = [](const GridAxis& a) { return a.periodic ? std::pair{0, a.cells - 1} : std::pair{-1, a.cells}; };
      const auto [x0, x1] = range(g.axis[0]);
      const auto [y0, y1] = range(g.axis[1]);
      const auto [z0, z1] = range(g.axis[2]);
      for (int k = z0; k <= z1; ++k)
        for (int j = y0; j <= y1; ++j)
          for (int i = x0; i <= x1; ++i) {
            const key_t key = g.key(i, j, k);
            ASSERT_LT(key, seen.size());
            EXPECT_EQ(seen[key]++, 0) << "key collision";
            int cell[3];
            g.cell_of_key(key, cell);
            EXPECT_EQ(cell[0], i);
            EXPECT_EQ(cell[1], j);
            EXPECT_EQ(cell[2], k);
          }
    }
  }
}

TEST(IbGrid, CellsAndIndexing) {
  const auto boxes = mac_boxes({10, 10, 10}, {1.0, 1.0, 1.0}, {true, false, true});
  const ComponentGrid gx = make_component_grid(boxes[0], 4);  // g = 1 along x
  const ComponentGrid gy = make_component_grid(boxes[1], 3);  // g = 1 along the wall axis y
  double delta = 0.0;
  // Even support: cell = floor(u) + 1 with u = x/h - g; delta in (0, 1].
  EXPECT_EQ(cell_of<4>(gx.axis[0], 0.23, delta), 2);  // u = 1.3
  EXPECT_NEAR(delta, 0.7, 1e-14);
  EXPECT_EQ(cell_of<4>(gx.axis[1], 0.23, delta), 2);  // u = 1.8
  EXPECT_NEAR(delta, 0.2, 1e-14);
  // Odd support: cell = floor(u + 1/2); delta in (-1/2, 1/2].
  EXPECT_EQ(cell_of<3>(gy.axis[1], 0.23, delta), 1);  // u = 1.3
  EXPECT_NEAR(delta, -0.3, 1e-14);
  // Periodic wrap of the grid index and of the position.
  EXPECT_EQ(gx.axis[0].index(-1), 9);
  EXPECT_EQ(gx.axis[0].index(10), 0);
  EXPECT_EQ(cell_of<4>(gx.axis[0], 1.23, delta), 2);
  // Walls: the y-faces have 9 unknowns (the wall faces y = 0 and y = 1 are not unknowns).
  EXPECT_EQ(gy.axis[1].n, 9);
  EXPECT_EQ(gy.axis[1].index(-1), -1);
  EXPECT_EQ(gy.axis[1].index(9), -1);
  EXPECT_EQ(gy.axis[1].index(8), 8);
  EXPECT_EQ(gx.axis[1].n, 10);
  EXPECT_EQ(gx.axis[1].index(10), -1);
}

}  // namespace
}  // namespace rbfib::ib

namespace rbfib::ib {
namespace {

// The binned spreading splits z into slabs of at least s + 1 planes, an even number of them on a
// periodic axis; grids with few z cells hit the edge cases (one slab, two slabs, odd counts on a
// wall axis). Each must equal serial Alg. 4.2 to rounding; the bound is the summation-order bound
// of expect_equal_to_rounding with every point counted (n terms) and the closed-form weights.
TEST(IbInteraction, BinnedSlabsForFewPlanes) {
  for (const std::string& kernel : kernel_names())
    for (bool walls : {false, true})
      for (int cz : {4, 5, 8, 9, 10, 11}) {  // s + 1 = 4 or 5: one slab, two, odd counts
        const auto boxes = mac_boxes({8, 6, cz}, {0.8, 0.6, 0.1 * cz}, {true, true, !walls});
        Interaction ib(boxes, kernel_named(kernel));
        const size_t n = 200;
        std::mt19937_64 rng(cz);
        std::uniform_real_distribution<double> U01(0.0, 1.0);
        HostPoints X(3 * n);
        const double L[3] = {0.8, 0.6, 0.1 * cz};
        for (size_t k = 0; k < n; ++k)
          for (int a = 0; a < 3; ++a) X[a * n + k] = L[a] * U01(rng);
        const HostPoints F = random_values(3 * n, 5);
        HostPoints absF(F);
        for (double& v : absF) v = std::abs(v);
        const dvec dX(X.begin(), X.end()), dF(F.begin(), F.end()), dA(absF.begin(), absF.end());
        std::array<dvec, 3> serial, serial_abs, binned;
        ib.spread(dX, dF, serial, Spreading::serial);
        ib.spread(dX, dA, serial_abs, Spreading::serial);
        ib.spread(dX, dF, binned, Spreading::binned);
        const double vol = ib.cell_volume();
        double sumF = 0.0;
        for (double v : absF) sumF += v;
        for (int c = 0; c < 3; ++c) {
          const auto s = to_host(serial[c]), b = to_host(binned[c]), a = to_host(serial_abs[c]);
          for (size_t m = 0; m < s.size(); ++m)
            ASSERT_NEAR(b[m], s[m], (2.0 * n + 8.0) * eps * a[m] + 48 * eps * sumF / vol)
                << kernel << (walls ? " walls" : " periodic") << " cz=" << cz << " component " << c << " unknown " << m;
        }
      }
}

// Points sorted once serve every later call at the same positions: read in place from a block
// of a larger array (a batch's state: positions, then velocities), their interpolation and
// spreading equal the calls that sort on their own, bit for bit (the same sort, the same sums),
// for two different fields through one sort; an empty set gives zero.
TEST(IbInteraction, PointsSortedOnceServeEveryCallAtThemBitForBit) {
  const auto boxes = mac_boxes({8, 6, 10}, {0.8, 0.6, 1.0}, {true, false, true});
  Interaction ib(boxes, Kernel::bspline3);
  const size_t n = 300;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  const double L[3] = {0.8, 0.6, 1.0};
  HostPoints state(6 * n, 99.0);  // positions, then a block that must not be read as positions
  for (size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) state[a * n + k] = L[a] * U01(rng);
  const HostPoints X(state.begin(), state.begin() + 3 * n), F = random_values(3 * n, 11);
  const dvec dstate(state.begin(), state.end()), dX(X.begin(), X.end()), dF(F.begin(), F.end());
  SortedPoints sorted;
  ib.sort(ptr(dstate), index_t(n), sorted);
  ASSERT_EQ(sorted.size(), index_t(n));
  for (int field = 0; field < 2; ++field) {
    std::array<dvec, 3> u;
    for (int c = 0; c < 3; ++c) {
      const HostPoints v = random_values(size_t(ib.grid(c).size), 20 + 3 * field + c);
      u[c] = dvec(v.begin(), v.end());
    }
    dvec once(3 * n), alone;
    ib.interpolate(sorted, u, ptr(once));
    ib.interpolate(dX, u, alone, Interpolation::binned);
    const auto a = to_host(once), b = to_host(alone);
    for (size_t k = 0; k < 3 * n; ++k) ASSERT_EQ(a[k], b[k]) << "field " << field << " entry " << k;
  }
  std::array<dvec, 3> f_once, f_alone;
  ib.spread(sorted, ptr(dF), f_once);
  ib.spread(dX, dF, f_alone, Spreading::binned);
  double total = 0;
  for (int c = 0; c < 3; ++c) {
    const auto a = to_host(f_once[c]), b = to_host(f_alone[c]);
    ASSERT_EQ(a.size(), b.size());
    for (size_t m = 0; m < a.size(); ++m) ASSERT_EQ(a[m], b[m]) << "component " << c << " unknown " << m;
    for (double v : a) total += std::abs(v);
  }
  EXPECT_GT(total, 0.0);
  SortedPoints none;
  ib.sort(ptr(dstate), 0, none);
  ib.spread(none, ptr(dF), f_once);
  for (int c = 0; c < 3; ++c)
    for (double v : to_host(f_once[c])) ASSERT_EQ(v, 0.0);
  // A bad position is named as by the other calls.
  HostPoints bad(X);
  bad[n + 5] = 0.7;  // y = 0.7 lies beyond the wall at 0.6
  const dvec dbad(bad.begin(), bad.end());
  try {
    ib.sort(ptr(dbad), index_t(n), sorted);
    FAIL() << "a point beyond a wall was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("X[5].y"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rbfib::ib
