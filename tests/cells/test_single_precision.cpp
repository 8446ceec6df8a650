// The force call with single-precision products (CellTypeSpec::single_precision_products): the
// forces of a stretched, moving red cell (every energy: Skalak, bending, dissipation) agree with
// the double call to the force's response to float rounding of its shifted positions, wherever the
// cell sits in the box; the reference shape at rest carries rounding only.
#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/presets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace rbfib;
using namespace rbfib::cells;

namespace {
constexpr double um = 1e-4;

std::shared_ptr<const CellType> small_red_cell(bool single) {
  CellTypeSpec s = red_cell_spec(144, 400);
  s.single_precision_products = single;
  return std::make_shared<const CellType>(std::move(s));
}

Placement stretched(double x) {
  Placement p;
  p.center = {x, 3 * um, 2 * um};
  p.axis = {1, 1, 0};
  p.angle = 0.7;
  p.stretch = {1, 1 / 1.1, 1.1};
  return p;
}

/// Forces (n_s x 3) of one cell with positions X (data sites, n_d x 3) and velocities U = 1000/s y e_x.
std::vector<double> forces(const std::shared_ptr<const CellType>& type, const std::vector<double>& X) {
  Batch b(type, {stretched(0)});
  const index_t nd = type->n_data();
  std::vector<double> state(X);
  state.resize(static_cast<std::size_t>(6 * nd), 0.0);
  for (index_t i = 0; i < nd; ++i) state[3 * nd + i] = 1000 * X[nd + i];
  thrust::copy(state.begin(), state.end(), b.state().storage().begin());
  CellForces f;
  compute_forces(b, f);
  return f.force.to_host();
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}
}  // namespace

TEST(SinglePrecisionForces, AgreeWithDoubleToTheResponseToFloatRoundingAnywhereInTheBox) {
  const auto t64 = small_red_cell(false), t32 = small_red_cell(true);
  const index_t nd = t64->n_data();
  double near = 0;
  for (double x : {0.0, 40 * um}) {
    const std::vector<double> X = Batch(t64, {stretched(x)}).positions_host();
    const std::vector<double> f64 = forces(t64, X), f32 = forces(t32, X);
    // The products in float equal exact products of operands perturbed by at most gamma_{k+4}(u_f)
    // relative (operator entries, shifted positions, the k-term sums): the double call's response
    // to a perturbation of the shifted positions (X - X(site 0)) by u_f relative, in random signs,
    // times k + 4, bounds the difference to first order.
    std::vector<double> Xp = X;
    unsigned state = 12345;
    const double uf = std::numeric_limits<float>::epsilon() / 2;
    for (index_t d = 0; d < 3; ++d)
      for (index_t i = 0; i < nd; ++i) {
        state = state * 1664525u + 1013904223u;
        Xp[d * nd + i] += ((state >> 16) % 2 ? uf : -uf) * (X[d * nd + i] - X[d * nd]);
      }
    const double response = max_abs_diff(forces(t64, Xp), f64);
    const double diff = max_abs_diff(f32, f64);
    double scale = 0;
    for (double v : f64) scale = std::max(scale, std::abs(v));
    EXPECT_LT(diff, double(nd + 4) * response) << "x = " << x / um << " um";
    EXPECT_LT(diff, 1e-2 * scale);
    if (x == 0) near = diff;
    else EXPECT_LT(diff, 4 * near) << "far from the origin, the rounding grows with the cell's place";
    std::printf("x = %g um: single vs double %.3e of the largest force, response to u_f %.3e\n", x / um, diff / scale,
                response / scale);
  }
}

TEST(SinglePrecisionForces, ARigidlyMovedReferenceCarriesOnlyFloatRounding) {
  // A Skalak sphere (elastic forces only: its reference is force free) moved rigidly: the
  // reference jets come from the same float products, so its force is the response to float
  // rounding, bounded as above by k + 4 times the double call's response to u_f; small against a
  // 10% stretch.
  auto sphere = [](bool single) {
    CellTypeSpec s = skalak_sphere_spec(3.91 * um, 144, 400);
    s.single_precision_products = single;
    return std::make_shared<const CellType>(std::move(s));
  };
  const auto t64 = sphere(false), t32 = sphere(true);
  Placement rest = stretched(30 * um);
  rest.stretch = {1, 1, 1};
  const index_t nd = t64->n_data();
  auto density = [](const std::shared_ptr<const CellType>& t, const std::vector<double>& X) {
    Batch b(t, {Placement{}});
    thrust::copy(X.begin(), X.end(), b.state().storage().begin());
    CellForces f;
    compute_forces(b, f);
    return f.density.to_host();
  };
  const std::vector<double> X = Batch(t64, {rest}).positions_host();
  std::vector<double> Xp = X;
  unsigned state = 777;
  const double uf = std::numeric_limits<float>::epsilon() / 2;
  for (index_t d = 0; d < 3; ++d)
    for (index_t i = 0; i < nd; ++i) {
      state = state * 1664525u + 1013904223u;
      Xp[d * nd + i] += ((state >> 16) % 2 ? uf : -uf) * (X[d * nd + i] - X[d * nd]);
    }
  const std::vector<double> r32 = density(t32, X), r64 = density(t64, X);
  const double response = max_abs_diff(density(t64, Xp), r64);
  double fr = 0, fs = 0;
  for (double v : r32) fr = std::max(fr, std::abs(v));
  for (double v : density(t64, Batch(t64, {stretched(30 * um)}).positions_host())) fs = std::max(fs, std::abs(v));
  std::printf("at rest %.3e of the stretched sphere's largest force density (response to u_f %.3e)\n", fr / fs, response / fs);
  EXPECT_LT(fr, double(nd + 4) * response);
  EXPECT_LT(fr, 1e-3 * fs);
  EXPECT_NE(t32->describe().find("single precision"), std::string::npos);
}
