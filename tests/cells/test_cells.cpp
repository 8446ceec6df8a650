// Unit tests of the cells module: the batched device force call against the per-cell host path
// (mechanics/shell.hpp) for every energy, batches of identical cells, rigid motions, force
// balance, diagnostics against closed forms, body forces, and named errors for bad cells.
#include "../common/errors.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/shell.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/point_sets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

using namespace rbfib;
using namespace rbfib::cells;

namespace {
constexpr double um = 1e-4;

/// Three placements: rotated, stretched (as Sec. 4.2.2.1) and translated.
std::vector<Placement> three_placements() {
  Placement a, b, c;
  a.center = {1 * um, 2 * um, 3 * um};
  b.center = {-5 * um, 0.5 * um, 2 * um};
  b.axis = {1, 1, 0};
  b.angle = 0.7;
  b.stretch = {1, 1 / 1.1, 1.1};
  c.center = {0, -4 * um, 8 * um};
  c.axis = {0.2, -1, 0.4};
  c.angle = 2.1;
  c.stretch = {1.05, 0.97, 1 / (1.05 * 0.97)};
  return {a, b, c};
}

/// Column block of cell c (n x 3) out of an n x 3N (or n x 6N, offset) matrix on the host.
std::vector<double> cell_columns(const std::vector<double>& M, index_t n, index_t N, index_t c, index_t col0 = 0) {
  std::vector<double> out(static_cast<std::size_t>(3 * n));
  for (index_t d = 0; d < 3; ++d)
    for (index_t i = 0; i < n; ++i) out[d * n + i] = M[(col0 + d * N + c) * n + i];
  return out;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// The rounding noise of a per-cell force evaluation f(X): max |f(X) - f(X')| with X' = X
/// perturbed by 4 ulps (relative) in random directions. Two evaluations of the same force that
/// differ only in the order of floating-point sums (the batched products run over more columns
/// than the per-cell ones, and BLAS blocks them differently) differ by about this much; the
/// amplification is the operators' (second derivatives of an r^7 spline, curvature derivatives
/// for bending), not the force code's.
double rounding_noise(const std::function<std::vector<double>(const std::vector<double>&)>& f, const std::vector<double>& X) {
  std::vector<double> Xp = X;
  unsigned state = 12345;
  for (double& x : Xp) {
    state = state * 1664525u + 1013904223u;
    x *= 1 + ((state >> 16) % 2 ? 4 : -4) * 2.220446049250313e-16;
  }
  const std::vector<double> a = f(X), b = f(Xp);
  double m = 0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

/// A small red cell type (same energies as the preset; fewer sites), built once.
const std::shared_ptr<const CellType>& small_red_cell() {
  static const auto t = red_cell(144, 400);
  return t;
}

/// A smooth velocity field at the data sites of every cell (1/s times position, plus a
/// quadratic part): U = A X + B (X * X), different for each cell.
void set_velocities(Batch& b) {
  const index_t nd = b.type().n_data(), N = b.size();
  const std::vector<double> X = b.positions_host();
  std::vector<double> U(X.size());
  const double A[3][3] = {{100, 300, -200}, {50, -100, 200}, {300, 100, 0}};
  for (index_t c = 0; c < N; ++c)
    for (index_t i = 0; i < nd; ++i)
      for (index_t d = 0; d < 3; ++d) {
        double u = 0;
        for (index_t e = 0; e < 3; ++e) {
          const double x = X[(e * N + c) * nd + i];
          u += (1 + 0.5 * double(c)) * A[d][e] * x + 1e5 * x * x;
        }
        U[(d * N + c) * nd + i] = u;
      }
  thrust::copy(U.begin(), U.end(), b.state().storage().begin() + 3 * N * nd);
}
}  // namespace

TEST(CellsBatch, EqualsThePerCellPathForEveryEnergy) {
  // The batched products and site launch compute the same sums as the per-cell host functions,
  // in a possibly different order: agreement to 1e-13 of the largest force density.
  const auto type = small_red_cell();
  Batch b(type, three_placements());
  set_velocities(b);
  CellForces out;
  compute_forces(b, out);
  const index_t nd = type->n_data(), ns = type->n_sample(), N = b.size();
  const std::vector<double> state = b.state().to_host(), density = out.density.to_host(), pos = out.positions.to_host();
  const std::vector<surface::Jet> Z = type->reference_jets_host();
  const std::vector<double> w = type->dA0_host();
  const ForceModel& m = type->model();
  for (index_t c = 0; c < N; ++c) {
    const std::vector<double> X = cell_columns(state, nd, N, c), U = cell_columns(state, nd, N, c, 3 * N);
    const auto XJ = surface::jets_from_operators(type->to_sample(), X);
    const auto UJ = surface::jets_from_operators(type->to_sample(), U);
    auto per_cell = [&](const std::vector<double>& Xc) {
      const auto J = surface::jets_from_operators(type->to_sample(), Xc);
      std::vector<double> F = mechanics::elastic_force_density("c", J, Z, m.elastic[0]);
      const auto Fb = mechanics::bending_force_density("c", *type->at_data(), type->to_sample(), Xc, Z,
                                                       mechanics::BendingModel{m.kappa, m.H0, {}});
      const auto Fv = mechanics::dissipative_force_density("c", J, UJ, Z, m.nu);
      for (std::size_t k = 0; k < F.size(); ++k) F[k] += Fb[k] + Fv[k];
      return F;
    };
    const std::vector<double> F = per_cell(X);
    const std::vector<double> got = cell_columns(density, ns, N, c);
    const double scale = max_abs(density);  // over all cells: cell 0 is at rest
    ASSERT_GT(scale, 0);
    const double tol = 10 * rounding_noise(per_cell, X) + 1e-13 * scale;
    EXPECT_LT(tol, 1e-9 * scale);  // the comparison stays sharp
    for (std::size_t k = 0; k < F.size(); ++k) ASSERT_NEAR(got[k], F[k], tol) << "cell " << c << " entry " << k;
    // Positions at the sample sites are the jets' values: two sums of n_d terms in different
    // orders differ by at most 2 n_d eps ||L_0||_inf max |X| (||L_0||_inf: the value operator's
    // largest absolute row sum, its Lebesgue constant).
    const std::vector<double> P = cell_columns(pos, ns, N, c);
    const std::vector<double> L0 = type->to_sample().value.to_host();
    double lebesgue = 0;
    for (index_t i = 0; i < ns; ++i) {
      double row = 0;
      for (index_t j = 0; j < nd; ++j) row += std::abs(L0[i + j * ns]);
      lebesgue = std::max(lebesgue, row);
    }
    const double ptol = 2.0 * double(nd) * 2.220446049250313e-16 * lebesgue * max_abs(X);
    EXPECT_LT(ptol, 1e-12 * max_abs(X));  // the comparison stays sharp
    for (index_t i = 0; i < ns; ++i)
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(P[d * ns + i], XJ[i].x[d], ptol);
    // Energies and dissipation.
    const double E = mechanics::elastic_energy("c", XJ, Z, m.elastic[0], w) +
                     mechanics::bending_energy("c", XJ, Z, mechanics::BendingModel{m.kappa, m.H0, {}}, w);
    EXPECT_NEAR(out.cells.energy[c], E, 1e-12 * std::abs(E)) << c;
    const double P0 = mechanics::dissipation("c", XJ, UJ, Z, m.nu, w);
    EXPECT_NEAR(out.cells.dissipation[c], P0, 1e-12 * std::abs(P0)) << c;
  }
}

namespace {
/// The batched elastic and bending force densities of three placed cells equal the per-cell host
/// path to 10 x its rounding noise; the noise itself must stay below `sharp` of the largest force
/// (so the comparison cannot become vacuous).
void expect_elastic_and_bending_equal_per_cell(const std::shared_ptr<const CellType>& type, double sharp) {
  Batch b(type, three_placements());
  CellForces out;
  compute_forces(b, out);
  const index_t nd = type->n_data(), ns = type->n_sample(), N = b.size();
  const std::vector<double> state = b.state().to_host(), density = out.density.to_host();
  const std::vector<surface::Jet> Z = type->reference_jets_host();
  const ForceModel& m = type->model();
  std::vector<double> H0(type->H0_data().size());  // empty unless H' is the reference curvature
  thrust::copy(type->H0_data().begin(), type->H0_data().end(), H0.begin());
  const mechanics::BendingModel bending{m.kappa, m.H0, H0};
  for (index_t c = 0; c < N; ++c) {
    const std::vector<double> X = cell_columns(state, nd, N, c);
    auto per_cell = [&](const std::vector<double>& Xc) {
      std::vector<double> F = mechanics::elastic_force_density("c", surface::jets_from_operators(type->to_sample(), Xc),
                                                               Z, m.elastic[0]);
      const auto Fb = mechanics::bending_force_density("c", *type->at_data(), type->to_sample(), Xc, Z, bending);
      for (std::size_t k = 0; k < F.size(); ++k) F[k] += Fb[k];
      return F;
    };
    const std::vector<double> F = per_cell(X);
    const std::vector<double> got = cell_columns(density, ns, N, c);
    const double scale = max_abs(density);  // over all cells: cell 0 is at rest
    const double tol = 10 * rounding_noise(per_cell, X) + 1e-13 * scale;
    EXPECT_LT(tol, sharp * scale);
    for (std::size_t k = 0; k < F.size(); ++k) ASSERT_NEAR(got[k], F[k], tol) << "cell " << c << " entry " << k;
  }
}
}  // namespace

TEST(CellsBatch, PlateletMaterialCurvatureEqualsThePerCellPath) {
  expect_elastic_and_bending_equal_per_cell(platelet(144, 144), 1e-8);
}

TEST(CellsBatch, FactoredHarmonicTypeEqualsThePerCellPath) {
  expect_elastic_and_bending_equal_per_cell(chapter3_red_cell(6, 300), 1e-9);
}

TEST(CellsBatch, IdenticalCellsGiveNTimesOneCell) {
  const auto type = small_red_cell();
  Placement p = three_placements()[1];
  CellForces one, many;
  compute_forces(Batch(type, {p}), one);
  compute_forces(Batch(type, std::vector<Placement>(5, p)), many);
  EXPECT_NEAR(many.energy, 5 * one.energy, 1e-13 * 5 * one.energy);
  const index_t ns = type->n_sample();
  const std::vector<double> f1 = one.force.to_host(), f5 = many.force.to_host();
  const double scale = max_abs(f1);
  // The products of one cell (3 columns) and of five (15) may take different kernels and sum in
  // other orders: the difference is rounding, measured by the one-cell call's own response to
  // a perturbation of its positions by a few ulps (as in the test above).
  auto forces_at = [&](const std::vector<double>& X) {
    Batch b(type, {p});
    thrust::copy(X.begin(), X.end(), b.state().storage().begin());
    CellForces f;
    compute_forces(b, f);
    return f.force.to_host();
  };
  const std::vector<double> X1 = Batch(type, {p}).positions_host();
  const double tol = 10 * rounding_noise(forces_at, X1) + 1e-13 * scale;
  EXPECT_LT(tol, 1e-9 * scale);  // the comparison stays sharp
  for (index_t c = 0; c < 5; ++c) {
    const std::vector<double> fc = cell_columns(f5, ns, 5, c);
    for (std::size_t k = 0; k < fc.size(); ++k) ASSERT_NEAR(fc[k], f1[k], tol) << c;
  }
}

TEST(CellsBatch, RigidMotionsCarryNoElasticForce) {
  // The reference jets come from the same operators, so a rotated and translated reference has
  // the reference metric up to rounding: I1, I2 ~ eps times the derivative operators' growth.
  // Against the force of a 10% stretch, the rigid-motion force is below 1e-9 (measured ~1e-12).
  const auto type = skalak_sphere(3.91 * um, 144, 400);
  std::vector<Placement> rigid = three_placements();
  for (auto& p : rigid) p.stretch = {1, 1, 1};
  CellForces r, s;
  compute_forces(Batch(type, rigid), r);
  compute_forces(Batch(type, three_placements()), s);
  const double stretched = max_abs(s.density.to_host());
  ASSERT_GT(stretched, 0);
  EXPECT_LT(max_abs(r.density.to_host()), 1e-9 * stretched);
  EXPECT_LT(r.energy, 1e-16 * s.energy);
}

TEST(CellsBatch, TranslationInvariantForcesBalancePerCell) {
  // sum_i F^_i = 0 in the continuum for the elastic and dissipative forces of the interpolated
  // surface; the discrete remainder is the sample rule's quadrature error, which falls as the
  // sample sites are refined (data sites fixed). Bending is left out: it evaluates H at the data
  // sites and reinterpolates it, so its remainder is the data sites' interpolation error of H.
  double r[2];
  int k = 0;
  for (index_t ns : {400, 1600}) {
    CellTypeSpec spec = red_cell_spec(144, ns);
    spec.model.kappa = 0;
    const auto type = std::make_shared<const CellType>(spec);
    Batch b(type, three_placements());
    set_velocities(b);
    CellForces out;
    compute_forces(b, out);
    const std::vector<double> F = out.force.to_host();
    double worst = 0;
    for (index_t c = 0; c < b.size(); ++c) {
      const std::vector<double> Fc = cell_columns(F, ns, b.size(), c);
      double sum[3] = {0, 0, 0}, tot = 0;
      for (index_t d = 0; d < 3; ++d)
        for (index_t i = 0; i < ns; ++i) {
          sum[d] += Fc[d * ns + i];
          tot += std::abs(Fc[d * ns + i]);
        }
      worst = std::max(worst, std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / tot);
    }
    r[k++] = worst;
  }
  EXPECT_LT(r[0], 1e-3);
  EXPECT_LT(r[1], 0.5 * r[0]);
}

TEST(CellsBatch, DiagnosticsOfASphereMatchClosedForms) {
  // Area 4 pi R^2, volume 4/3 pi R^3 (to the accuracy of the RBF quadrature, 1e-5 at 1600
  // sites), centroid at the placement's center.
  const double R = 2 * um;
  const auto type = skalak_sphere(R, 144, 1600);
  Placement p;
  p.center = {3 * um, -1 * um, 7 * um};
  CellForces out;
  compute_forces(Batch(type, {p, p}), out);
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR(out.cells.area[c], 4 * pi * R * R, 1e-5 * 4 * pi * R * R);
    EXPECT_NEAR(out.cells.volume[c], 4 * pi * R * R * R / 3, 1e-5 * 4 * pi * R * R * R / 3);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(out.cells.centroid[c][d], p.center[d], 1e-5 * R);
  }
  EXPECT_NEAR(type->reference_area(), 4 * pi * R * R, 1e-5 * 4 * pi * R * R);
}

TEST(CellsBatch, MeasureGivesTheForceCallsGeometryWithoutItsForces) {
  // Three placed (stretched, moved) red cells: positions, areas, volumes and centroids as the force
  // call's, to rounding (another product width may sum in another order); a collapsed cell is named.
  const auto type = small_red_cell();
  Batch b(type, three_placements());
  CellForces f;
  compute_forces(b, f);
  CellGeometry g;
  measure(b, g);
  const std::vector<double> pf = f.positions.to_host(), pg = g.positions.to_host();
  ASSERT_EQ(pf.size(), pg.size());
  // Rounding of a sum of n_d products (the value operator's rows sum to 1): n_d u max |X|.
  const double scale = std::abs(*std::max_element(pf.begin(), pf.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }));
  const double rounding = double(type->n_data()) * std::numeric_limits<double>::epsilon() * scale;
  for (std::size_t k = 0; k < pf.size(); ++k) ASSERT_NEAR(pg[k], pf[k], rounding) << k;
  for (index_t c = 0; c < b.size(); ++c) {
    EXPECT_NEAR(g.cells.area[c], f.cells.area[c], 1e-13 * f.cells.area[c]);
    EXPECT_NEAR(g.cells.volume[c], f.cells.volume[c], 1e-13 * f.cells.volume[c]);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(g.cells.centroid[c][d], f.cells.centroid[c][d], 1e-13 * um);
  }
  EXPECT_TRUE(g.cells.energy.empty());
  const index_t nd = type->n_data(), N = b.size();
  for (index_t d = 0; d < 3; ++d)
    thrust::fill(b.state().storage().begin() + (d * N + 2) * nd, b.state().storage().begin() + (d * N + 3) * nd, 0.0);
  try {
    measure(b, g);
    ADD_FAILURE() << "no error for a collapsed cell";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.cause(), Cause::degenerate_site);
    EXPECT_NE(std::string(e.what()).find("cell 2"), std::string::npos) << e.what();
  }
}

TEST(CellsBatch, BodyForceIsSpreadInProportionToTheReferenceArea) {
  const auto type = skalak_sphere(2 * um, 144, 400);
  Batch b(type, three_placements());
  const std::array<double, 3> F{1e-7, -2e-7, 0.5e-7};
  b.set_body_force(1, F);
  CellForces out;
  compute_forces(b, out);
  const index_t ns = type->n_sample();
  const std::vector<double> f = out.force.to_host(), dens = out.density.to_host();
  const std::vector<double> w = type->dA0_host();
  const std::vector<double> f1 = cell_columns(f, ns, 3, 1), d1 = cell_columns(dens, ns, 3, 1);
  for (int d = 0; d < 3; ++d) {
    double body = 0;
    for (index_t i = 0; i < ns; ++i) body += f1[d * ns + i] - d1[d * ns + i] * w[i];
    EXPECT_NEAR(body, F[d], 1e-13 * 2e-7);
  }
  EXPECT_THROW(b.set_body_force(3, F), InputError);
}

TEST(CellsBatch, DegenerateCellIsNamed) {
  // Cell 2 collapsed to a point: every metric is zero; the error names the type, cell 2 and a site.
  const auto type = small_red_cell();
  Batch b(type, three_placements());
  const index_t nd = type->n_data(), N = b.size();
  for (index_t d = 0; d < 3; ++d)
    thrust::fill(b.state().storage().begin() + (d * N + 2) * nd, b.state().storage().begin() + (d * N + 3) * nd, 0.0);
  CellForces out;
  const std::string msg = rbfib::testing::message_of<NumericalError>([&] { compute_forces(b, out); });
  ASSERT_FALSE(msg.empty()) << "expected NumericalError";
  EXPECT_NE(msg.find("red cell"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cell 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("degenerate"), std::string::npos) << msg;
}

TEST(CellsBatch, BadInputIsNamed) {
  const auto type = small_red_cell();
  Placement p;
  p.stretch = {1, 0, 1};
  EXPECT_THROW(Batch(type, {p}), InputError);
  p = Placement{};
  p.axis = {0, 0, 0};
  EXPECT_THROW(Batch(type, {p}), InputError);
  EXPECT_THROW(Batch(type, {}), InputError);
  CellTypeSpec s;
  s.name = "bad";
  s.shape = ellipsoid_shape(1, 1, 1);
  s.data_sites = surface::bauer_spiral(50);
  s.sample_sites = surface::bauer_spiral(60);
  s.model.nu = -1;
  EXPECT_THROW(CellType{s}, InputError);
}
