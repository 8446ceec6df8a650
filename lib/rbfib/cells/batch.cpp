#include "rbfib/cells/batch.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/core/rotation.hpp"
#include "rbfib/mechanics/force_kernels.hpp"

#include <thrust/copy.h>
#include <thrust/find.h>

#include <chrono>
#include <cmath>

namespace rbfib::cells {

namespace {
using surface::Jet;
using surface::JetView;

/// The elastic energies of a model, by value (captured by the site kernel).
struct EnergyList {
  mechanics::EnergyDensity e[ForceModel::max_elastic_energies];
  int n = 0;
};

/// Status codes of a site (0: good); 1-3 are mechanics::ForceStatus.
enum SiteStatus : int { site_non_finite = 4, site_degenerate_data = 5 };

const char* status_text(int s) {
  switch (s) {
    case mechanics::force_degenerate_metric: return "degenerate surface metric (det G <= 0 or det G0 <= 0)";
    case mechanics::force_bad_energy: return "energy density undefined (det C <= 0)";
    case site_non_finite: return "non-finite force density";
    case site_degenerate_data: return "degenerate surface metric at a data site (bending)";
  }
  return "unknown failure";
}

Cause status_cause(int s) {
  switch (s) {
    case mechanics::force_degenerate_metric: return Cause::degenerate_site;
    case site_degenerate_data: return Cause::degenerate_site;
    case mechanics::force_bad_energy: return Cause::inverted_cell;
    case site_non_finite: return Cause::non_finite;
  }
  return Cause::solver;
}

RBFIB_HD inline bool finite(double v) { return (v - v) == 0.0; }

/// The per-cell sums of q per-site quantities, the n_s x qN matrix w.site_sums (column k N + c:
/// quantity k of cell c), as one product with a vector of ones; on the host, entry k N + c.
std::vector<double> per_cell_sums(Batch::Workspace& w, index_t ns, int q, index_t N) {
  w.cell_sums.resize(static_cast<std::size_t>(q * N));
  if (static_cast<index_t>(w.ones.size()) != ns) w.ones.assign(static_cast<std::size_t>(ns), 1.0);
  linalg::gemm(linalg::Op::transpose, linalg::Op::none, 1.0, linalg::ConstMatrixView{ptr(w.site_sums), ns, q * N, ns},
               linalg::ConstMatrixView{ptr(w.ones), ns, 1, ns}, 0.0, linalg::MatrixView{ptr(w.cell_sums), q * N, 1, q * N});
  std::vector<double> s(w.cell_sums.size());
  thrust::copy(w.cell_sums.begin(), w.cell_sums.end(), s.begin());
  return s;
}

/// Area, volume and centroid of each cell from the per-cell sums s (quantity `area` is the area,
/// area + 1 the volume, area + 2 .. area + 4 the volume moments); throws NumericalError for a cell
/// turned inside out.
void set_geometry(CellDiagnostics& cd, const std::vector<double>& s, int area, index_t N, const std::string& name) {
  cd.area.assign(s.begin() + area * N, s.begin() + (area + 1) * N);
  cd.volume.assign(s.begin() + (area + 1) * N, s.begin() + (area + 2) * N);
  cd.centroid.assign(static_cast<std::size_t>(N), {0, 0, 0});
  for (index_t c = 0; c < N; ++c) {
    if (!(cd.volume[c] > 0))
      throw NumericalError(Cause::inverted_cell, "cell type '" + name + "', cell " + to_text(c) + ": enclosed volume " +
                                                     to_text(cd.volume[c]) + " cm^3 <= 0 (the surface is turned inside out)");
    for (int d = 0; d < 3; ++d) cd.centroid[c][d] = s[(area + 2 + d) * N + c] / cd.volume[c];
  }
}

/// Number of per-site contributions reduced per cell.
constexpr int sums_per_site = 7;  // energy, dissipation, area, volume, 3 volume moments

/// Throws the named error for the first site with a nonzero status, if any.
void raise_first_bad(const device_vector<int>& status, index_t per_cell, const std::string& type, const char* where) {
  const auto it = thrust::find_if(status.begin(), status.end(), [] RBFIB_HD (int s) { return s != 0; });
  if (it == status.end()) return;
  const index_t k = it - status.begin();
  const int s = *it;
  throw NumericalError(status_cause(s), "cell type '" + type + "', cell " + to_text(k / per_cell) + ": " + status_text(s) + " at " +
                       where + " site " + to_text(k % per_cell));
}

double seconds_since(std::chrono::steady_clock::time_point& t0) {
  synchronize();
  const auto t1 = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(t1 - t0).count();
  t0 = t1;
  return s;
}
}  // namespace

Batch::Batch(std::shared_ptr<const CellType> type, const std::vector<Placement>& placements)
    : type_(std::move(type)), cells_(static_cast<index_t>(placements.size())) {
  require(bool(type_), "batch cell type", "null", "must be given");
  require(cells_ > 0, "batch of '" + type_->name() + "': number of cells", cells_, "must be > 0");
  state_ = linalg::DeviceMatrix(type_->n_data(), 6 * cells_);
  body_.assign(static_cast<std::size_t>(3 * cells_), 0.0);
  body_device_.assign(body_.size(), 0.0);
  for (index_t c = 0; c < cells_; ++c) place(c, placements[c]);
}

Batch Batch::from_state(std::shared_ptr<const CellType> type, index_t cells, const std::vector<double>& state,
                        const std::vector<double>& body) {
  require(bool(type), "batch cell type", "null", "must be given");
  require(cells >= 0, "batch of '" + type->name() + "': number of cells", cells, "must be >= 0");
  require(index_t(state.size()) == 6 * cells * type->n_data(), "batch of '" + type->name() + "': state size", state.size(),
          "must be 6 n_d N = " + to_text(6 * cells * type->n_data()));
  require(index_t(body.size()) == 3 * cells, "batch of '" + type->name() + "': body forces", body.size(),
          "must be 3 N = " + to_text(3 * cells));
  Batch b;
  b.type_ = std::move(type);
  b.cells_ = cells;
  b.state_ = linalg::DeviceMatrix::from_host(b.type_->n_data(), 6 * cells, state.data());
  b.body_ = body;
  b.body_device_ = dvec(body.begin(), body.end());
  return b;
}

std::vector<double> placed(const std::vector<double>& reference, index_t n, const Placement& p, const std::string& who) {
  const double an = std::sqrt(p.axis[0] * p.axis[0] + p.axis[1] * p.axis[1] + p.axis[2] * p.axis[2]);
  require(an > 0 && std::isfinite(an), who + ": rotation axis length", an, "must be finite and > 0");
  require(std::isfinite(p.angle), who + ": rotation angle (rad)", p.angle, "must be finite");
  for (int d = 0; d < 3; ++d) {
    require(p.stretch[d] > 0 && std::isfinite(p.stretch[d]), who + ": stretch[" + to_text(d) + "]", p.stretch[d],
            "must be finite and > 0");
    require(std::isfinite(p.center[d]), who + ": center[" + to_text(d) + "] (cm)", p.center[d], "must be finite");
  }
  const Mat3 R = rotation_matrix(p.axis, p.angle);
  std::vector<double> X(static_cast<std::size_t>(3 * n));
  for (index_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      double v = p.center[a];
      for (int b = 0; b < 3; ++b) v += R[a][b] * p.stretch[b] * reference[b * n + i];
      X[a * n + i] = v;
    }
  return X;
}

void Batch::place(index_t c, const Placement& p) {
  const std::string cell = "batch of '" + type_->name() + "', cell " + to_text(c);
  require(c >= 0 && c < cells_, cell + ": index", c, "must lie in [0, " + to_text(cells_) + ")");
  const index_t nd = type_->n_data();
  const std::vector<double> cols = placed(type_->reference_data_host(), nd, p, cell);
  for (int a = 0; a < 3; ++a)
    thrust::copy(cols.begin() + a * nd, cols.begin() + (a + 1) * nd,
                 state_.storage().begin() + (a * cells_ + c) * nd);
}

void Batch::set_body_force(index_t c, const std::array<double, 3>& F) {
  require(c >= 0 && c < cells_, "batch of '" + type_->name() + "': body-force cell", c,
          "must lie in [0, " + to_text(cells_) + ")");
  for (int d = 0; d < 3; ++d) {
    require(std::isfinite(F[d]), "batch of '" + type_->name() + "', cell " + to_text(c) + ": body force (dyn)", F[d],
            "must be finite");
    body_[d * cells_ + c] = F[d];
  }
  body_device_.assign(body_.begin(), body_.end());
}

std::vector<double> Batch::positions_host() const {
  const index_t n = type_->n_data() * 3 * cells_;
  std::vector<double> h(static_cast<std::size_t>(n));
  thrust::copy(state_.storage().begin(), state_.storage().begin() + n, h.begin());
  return h;
}

void compute_forces(const Batch& batch, CellForces& out, ForceTimings* timings) {
  compute_forces(batch, batch.state().view(), out, timings);
}

void compute_forces(const Batch& batch, linalg::ConstMatrixView state, CellForces& out, ForceTimings* timings) {
  const CellType& type = batch.type();
  const ForceModel& model = type.model();
  const std::string& name = type.name();
  const index_t N = batch.size(), ns = type.n_sample(), nd = type.n_data(), total = N * ns;
  const bool dissipation = model.dissipation(), bending = model.bending();
  const index_t cols = (dissipation ? 6 : 3) * N;
  require(state.rows == nd && state.cols >= cols, "force call of cell type '" + name + "': state", to_text(state.rows) + " x " + to_text(state.cols),
          "must be n_d x 6N = " + to_text(nd) + " x " + to_text(6 * N));
  Batch::Workspace& w = batch.workspace();
  auto t0 = std::chrono::steady_clock::now();
  if (timings) {
    *timings = ForceTimings{};
    synchronize();
    t0 = std::chrono::steady_clock::now();
  }

  // 1. With bending, H - H' at the data sites first, from the jets of X there (rows n_s .. of the
  //    type's operators): it then rides as N more columns, [X U (H - H')], through the one pass
  //    over the sample sites' operators that gives the jets of X (and U); its derivatives there
  //    enter the Laplace-Beltrami term. One stream of those operators per call, not two: the
  //    products with few columns (a cell or two) are bound by reading the operators.
  const index_t both = bending ? cols + N : cols;  // the columns of the sample sites' pass
  if (bending) {
    // H needs the derivatives of X alone (the geometry reads no value): no value product.
    w.data_derivatives.resize(surface::derivative_count * nd, 3 * N);
    surface::apply_operators_rows(type.operators(), state.block(0, 0, nd, 3 * N), ns, nd, linalg::MatrixView{},
                                  w.data_derivatives.view(), w.ops);
    if (timings) timings->bending_products = seconds_since(t0);
    const JetView xd{nullptr, nd, ptr(w.data_derivatives.storage()), surface::derivative_count * nd, nd, N};
    w.fields.resize(nd, both);
    linalg::copy(state.block(0, 0, nd, cols), w.fields.view().block(0, 0, nd, cols));
    w.data_status.resize(static_cast<std::size_t>(N * nd));
    double* dH = ptr(w.fields.storage()) + cols * nd;
    int* dstat = ptr(w.data_status);
    const double* H0d = model.H0_reference ? ptr(type.H0_data()) : nullptr;
    for_each_index(N * nd, [=] RBFIB_HD (index_t k) {
      const index_t c = k / nd, i = k % nd;
      const surface::PointGeometry g = surface::point_geometry(xd.jet(c, i));
      const bool ok = g.det_g > 0 && finite(g.H);
      dstat[k] = ok ? 0 : site_degenerate_data;
      // A constant H' drops out of the Laplacian, so only a material field is subtracted.
      dH[i + c * nd] = ok ? g.H - (H0d ? H0d[i] : 0.0) : 0.0;
    });
    raise_first_bad(w.data_status, nd, name, "data");
    if (timings) timings->bending_kernel = seconds_since(t0);
  }

  // 2. Jets at the sample sites: value and derivatives of X (and U), and of H - H' with bending,
  //    by one product for the values and one (a batch of five) for the derivatives. Only the
  //    positions' values are read (where the forces act, the volume sums): the velocities' and
  //    H - H''s values are not computed.
  const index_t ldd = surface::derivative_count * ns;
  w.values.resize(ns, 3 * N);
  w.derivatives.resize(ldd, both);
  surface::apply_operators_rows(type.operators(), bending ? linalg::ConstMatrixView(w.fields.view()) : state.block(0, 0, nd, cols), 0, ns,
                                w.values.view(), w.derivatives.view(), w.ops);
  out.positions.resize(ns, 3 * N);
  linalg::copy(w.values.view().block(0, 0, ns, 3 * N), out.positions.view());
  const double* V = ptr(w.values.storage());
  const double* D = ptr(w.derivatives.storage());
  const JetView xj{V, ns, D, ldd, ns, N};
  const JetView uj = dissipation ? JetView{nullptr, ns, D + 3 * N * ldd, ldd, ns, N} : JetView{};
  const JetView dhj = bending ? JetView{nullptr, ns, D + cols * ldd, ldd, ns, N} : JetView{};
  if (timings) timings->jets = seconds_since(t0);

  // 3. The site launch: every force density, F^, and per-site sums.
  out.density.resize(ns, 3 * N);
  out.force.resize(ns, 3 * N);
  w.status.resize(static_cast<std::size_t>(total));
  w.site_sums.resize(static_cast<std::size_t>(sums_per_site * total));
  EnergyList energies;
  for (const auto& e : model.elastic) energies.e[energies.n++] = e;
  const JetView zj = type.reference_jets();
  const JetView h0j = type.H0_jets();
  const bool material_H0 = model.H0_reference && bending;
  const double kappa = model.kappa, H0 = model.H0, nu = model.nu, A0 = type.reference_area();
  const double* dA0 = ptr(type.dA0());
  const double* body = ptr(batch.body_force_device());
  double* Fd = ptr(out.density.storage());
  double* Fh = ptr(out.force.storage());
  double* sums = ptr(w.site_sums);
  int* stat = ptr(w.status);
  for_each_index(total, [=] RBFIB_HD (index_t k) {
    const index_t c = k / ns, i = k % ns;
    const Jet X = xj.jet(c, i), Z = zj.jet(0, i);
    double F[3] = {0, 0, 0}, W = 0, P = 0;
    int status = 0;
    for (int q = 0; q < energies.n; ++q) {
      const mechanics::ForceAtSite r = mechanics::elastic_force_density(X, Z, energies.e[q]);
      if (r.status) status = r.status;
      W += r.W;
      for (int d = 0; d < 3; ++d) F[d] += r.F[d];
    }
    const surface::PointGeometry g = surface::point_geometry(X), g0 = surface::point_geometry(Z);
    if (!(g.det_g > 0) || !(g0.det_g > 0)) status = mechanics::force_degenerate_metric;
    const double J = status ? 0.0 : sqrt(g.det_g / g0.det_g);  // dA / dA0
    if (bending && !status) {
      const surface::ScalarJet h0 = material_H0 ? h0j.scalar(0, i) : surface::ScalarJet{H0, 0, 0, 0, 0, 0};
      double fb[3];
      mechanics::bending_force_density(g, g0.det_g, surface::laplace_beltrami(X, dhj.scalar(c, i)), kappa, h0.u, fb);
      if (material_H0) {  // tangential term of a material field H' (see mechanics/shell.hpp)
        double grad[3];
        surface::surface_gradient(X, h0, grad);
        for (int d = 0; d < 3; ++d) fb[d] += -4 * kappa * J * (g.H - h0.u) * grad[d];
      }
      for (int d = 0; d < 3; ++d) F[d] += fb[d];
      W += 2 * kappa * (g.H - h0.u) * (g.H - h0.u) * J;
    }
    if (nu > 0 && !status) {
      const mechanics::ForceAtSite r = mechanics::dissipative_force_density(X, uj.jet(c, i), Z, nu);
      if (r.status) status = r.status;
      P = r.W;
      for (int d = 0; d < 3; ++d) F[d] += r.F[d];
    }
    for (int d = 0; d < 3; ++d)
      if (!finite(F[d]) && !status) status = site_non_finite;
    stat[k] = status;
    const double a0 = dA0[i], dA = J * a0;
    for (int d = 0; d < 3; ++d) {
      Fd[d * total + k] = F[d];
      Fh[d * total + k] = F[d] * a0 + body[d * N + c] * a0 / A0;
    }
    // Enclosed volume and its first moments by the divergence theorem: V = (1/3) int X . n dA,
    // int_V x_d dV = (1/2) int x_d^2 n_d dA.
    sums[0 * total + k] = W * a0;
    sums[1 * total + k] = P * a0;
    sums[2 * total + k] = dA;
    sums[3 * total + k] = (X.x[0] * g.n[0] + X.x[1] * g.n[1] + X.x[2] * g.n[2]) * dA / 3;
    for (int d = 0; d < 3; ++d) sums[(4 + d) * total + k] = 0.5 * X.x[d] * X.x[d] * g.n[d] * dA;
  });
  if (timings) timings->kernels = seconds_since(t0);

  // 4. The first bad site, then sums per cell.
  raise_first_bad(w.status, ns, name, "sample");
  const std::vector<double> s = per_cell_sums(w, ns, sums_per_site, N);
  CellDiagnostics& cd = out.cells;
  cd.energy.assign(s.begin(), s.begin() + N);
  cd.dissipation.assign(s.begin() + N, s.begin() + 2 * N);
  set_geometry(cd, s, 2, N, name);
  out.energy = 0;
  for (index_t c = 0; c < N; ++c) out.energy += cd.energy[c];
  if (timings) timings->reductions = seconds_since(t0);
}

void measure(const Batch& batch, CellGeometry& out) {
  const CellType& type = batch.type();
  const std::string& name = type.name();
  const index_t N = batch.size(), ns = type.n_sample(), nd = type.n_data(), total = N * ns;
  Batch::Workspace& w = batch.workspace();
  // Jets of the positions at the sample sites: value and derivatives.
  const index_t ldd = surface::derivative_count * ns;
  w.values.resize(ns, 3 * N);
  w.derivatives.resize(ldd, 3 * N);
  surface::apply_operators_rows(type.operators(), batch.state().view().block(0, 0, nd, 3 * N), 0, ns, w.values.view(), w.derivatives.view(),
                                w.ops);
  out.positions.resize(ns, 3 * N);
  linalg::copy(w.values.view(), out.positions.view());
  const JetView xj{ptr(w.values.storage()), ns, ptr(w.derivatives.storage()), ldd, ns, N};
  const JetView zj = type.reference_jets();
  const double* dA0 = ptr(type.dA0());
  constexpr int q = 5;  // area, volume, 3 volume moments
  w.status.resize(static_cast<std::size_t>(total));
  w.site_sums.resize(static_cast<std::size_t>(q * total));
  double* sums = ptr(w.site_sums);
  int* stat = ptr(w.status);
  for_each_index(total, [=] RBFIB_HD (index_t k) {
    const index_t i = k % ns;
    const Jet X = xj.jet(k / ns, i), Z = zj.jet(0, i);
    const surface::PointGeometry g = surface::point_geometry(X), g0 = surface::point_geometry(Z);
    const bool ok = g.det_g > 0 && g0.det_g > 0;
    stat[k] = ok ? 0 : mechanics::force_degenerate_metric;
    const double dA = ok ? sqrt(g.det_g / g0.det_g) * dA0[i] : 0.0;
    // The force call's divergence-theorem sums: V = (1/3) int X . n dA, int_V x_d dV = (1/2) int x_d^2 n_d dA.
    sums[0 * total + k] = dA;
    sums[1 * total + k] = (X.x[0] * g.n[0] + X.x[1] * g.n[1] + X.x[2] * g.n[2]) * dA / 3;
    for (int d = 0; d < 3; ++d) sums[(2 + d) * total + k] = 0.5 * X.x[d] * X.x[d] * g.n[d] * dA;
  });
  raise_first_bad(w.status, ns, name, "sample");
  CellDiagnostics& cd = out.cells;
  cd.energy.clear();
  cd.dissipation.clear();
  set_geometry(cd, per_cell_sums(w, ns, q, N), 0, N, name);
}

}  // namespace rbfib::cells
