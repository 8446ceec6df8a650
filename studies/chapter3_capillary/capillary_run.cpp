#include "capillary_run.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/surface/geometry.hpp"

#include <thrust/extrema.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace rbfib::capillary {

namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

/// f += b over n values (the background force added to the spread force).
void add_field(double* f, const double* b, index_t n) {
  for_each_index(n, [=] RBFIB_HD(index_t i) { f[i] += b[i]; });
}

/// X += dt (U + u_c) at n points (X[d n + i]): the update of eq. (87) with eq. (95)'s constant
/// velocity. (A device lambda may not sit inside the private Run::Impl.)
void advance_points(double* X, const double* U, index_t n, double dt, const double uc[3]) {
  const double ucx = uc[0], ucy = uc[1], ucz = uc[2];
  for_each_index(3 * n, [=] RBFIB_HD(index_t i) {
    const double ucd = i < n ? ucx : (i < 2 * n ? ucy : ucz);
    X[i] += dt * (U[i] + ucd);
  });
}

/// Volume, area and volume centroid of a closed triangulated surface X (n x 3 column-major).
void polyhedron(const std::vector<surface::Triangle>& tris, const std::vector<double>& X, double c[3], double& volume,
                double& area) {
  const std::size_t n = X.size() / 3;
  double mo[3] = {0, 0, 0};
  volume = 0;
  area = 0;
  for (const auto& t : tris) {
    double a[3], b[3], d[3], bxd[3], e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = X[k * n + t[0]];
      b[k] = X[k * n + t[1]];
      d[k] = X[k * n + t[2]];
      e1[k] = b[k] - a[k];
      e2[k] = d[k] - a[k];
    }
    surface::cross3(b, d, bxd);
    const double v = surface::dot3(a, bxd) / 6;  // the tetrahedron (0, a, b, d)
    volume += v;
    for (int k = 0; k < 3; ++k) mo[k] += v * (a[k] + b[k] + d[k]) / 4;
    surface::cross3(e1, e2, nn);
    area += 0.5 * std::sqrt(surface::dot3(nn, nn));
  }
  for (int k = 0; k < 3; ++k) c[k] = mo[k] / volume;
}

/// Area-weighted vertex normals of the triangulated surface X (n x 3), unit length.
std::vector<double> vertex_normals(const std::vector<surface::Triangle>& tris, const std::vector<double>& X) {
  const std::size_t n = X.size() / 3;
  std::vector<double> N(3 * n, 0.0);
  for (const auto& t : tris) {
    double e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = X[k * n + t[1]] - X[k * n + t[0]];
      e2[k] = X[k * n + t[2]] - X[k * n + t[0]];
    }
    surface::cross3(e1, e2, nn);
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) N[k * n + t[v]] += nn[k];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::sqrt(N[i] * N[i] + N[n + i] * N[n + i] + N[2 * n + i] * N[2 * n + i]);
    for (int k = 0; k < 3; ++k) N[k * n + i] = s > 0 ? N[k * n + i] / s : 0.0;
  }
  return N;
}

// Binary checkpoint helpers (host doubles and integers).
void put(std::ofstream& f, double x) { f.write(reinterpret_cast<const char*>(&x), sizeof x); }
void put(std::ofstream& f, const std::vector<double>& v) {
  put(f, double(v.size()));
  if (!v.empty()) f.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(double)));
}
bool get(std::ifstream& f, double& x) { return bool(f.read(reinterpret_cast<char*>(&x), sizeof x)); }
bool get(std::ifstream& f, std::vector<double>& v) {
  double s;
  if (!get(f, s) || s < 0 || s > 1e9) return false;
  v.resize(std::size_t(s));
  return v.empty() || bool(f.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * sizeof(double))));
}

}  // namespace

const char* to_string(Region r) { return r == Region::core ? "core" : "segment"; }

struct Run::Impl {
  Model m;
  const chapter3::EvaluationSet* eval;
  MacGrid grid;
  PeriodicStokesSolver stokes;
  ib::Interaction ib;
  VectorField f, u;
  dvec p, background;
  // capillary: reference Z, positions X (host), device copies, forces and velocities
  int around = 0, along = 0;
  std::vector<double> Zcap, Xcap, Fcap_h, Ucap_h;
  dvec Xcap_d, Fcap_d, Ucap_d;
  ib::SortedPoints at_cap, at_eval, at_interp;
  // SHVD
  std::unique_ptr<cells::Batch> batch;
  cells::CellForces out;
  dvec U;
  // LDSM
  std::vector<double> Zc, X, F, W0, Uh;
  dvec Xd, Fd;
  std::vector<mechanics::EnergyDensity> energies;
  // run
  int k = 0;
  bool finished = false;
  std::string failure;
  std::vector<Sample> series;
  std::vector<View> views;
  Phases phases;
  int timed = 0;
  std::vector<surface::Triangle> no_tris;

  static MacGrid make_grid(const Model& m) {
    require(m.eta >= 8, "grid size eta", m.eta, "must be >= 8");
    require(m.L > 0, "half box L (cm)", m.L, "must be > 0");
    MacGrid g = make_mac_grid(3, {m.eta, m.eta, m.eta}, {2 * m.L, 2 * m.L, 2 * m.L},
                              {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
    g.origin = {-m.L, -m.L, -m.L};
    return g;
  }

  Impl(const Model& model, const chapter3::EvaluationSet* e)
      : m(model),
        eval(e),
        grid(make_grid(model)),
        stokes(grid, model.mu, 0.0),
        ib({stokes.operators().component_box(0), stokes.operators().component_box(1),
            stokes.operators().component_box(2)},
           model.kernel) {
    require(m.mu > 0, "viscosity mu (P)", m.mu, "must be > 0");
    require(m.dt > 0, "time step dt (s)", m.dt, "must be > 0");
    require(m.steps >= 0, "steps", m.steps, "must be >= 0");
    require(m.R_cap > 0 && m.R_cap < m.L, "capillary radius (cm)", m.R_cap, "must lie in (0, L)");
    require(m.k_teth >= 0, "k_teth (dyn/cm)", m.k_teth, "must be >= 0");
    require(m.k_bend >= 0, "k_bend (erg)", m.k_bend, "must be >= 0");
    require(m.record_every > 0, "record_every", m.record_every, "must be > 0");
    require(m.view_every > 0, "view_every", m.view_every, "must be > 0");
    make_background();
    make_capillary();
    if (m.with_cell) make_cell();
  }

  /// The background force on the x-faces: f_in inside the region, f_out elsewhere, zero sum.
  void make_background() {
    const Box& b = stokes.operators().component_box(0);
    std::vector<double> bg(static_cast<std::size_t>(b.size()));
    std::vector<char> in(bg.size());
    index_t n_in = 0;
    for (int kz = 0; kz < b.n(2); ++kz)
      for (int jy = 0; jy < b.n(1); ++jy)
        for (int ix = 0; ix < b.n(0); ++ix) {
          const double x = b.x(0, ix), y = b.x(1, jy), z = b.x(2, kz);
          bool inside = y * y + z * z < m.R_cap * m.R_cap;
          if (m.region == Region::segment) inside = inside && x >= m.x0_cap && x <= m.x1_cap;
          const index_t p = ix + index_t(b.n(0)) * (jy + index_t(b.n(1)) * kz);
          in[p] = inside;
          n_in += inside;
        }
    const double f_out = -m.f_in * double(n_in) / double(index_t(bg.size()) - n_in);
    for (std::size_t p = 0; p < bg.size(); ++p) bg[p] = in[p] ? m.f_in : f_out;
    background = dvec(bg.begin(), bg.end());
  }

  /// Nodes on the cylinder at the centres of equal patches: `around` x `along` of them.
  void make_capillary() {
    const double s = m.cap_spacing > 0 ? m.cap_spacing : m.h() / 2;
    around = std::max(8, int(std::lround(2 * pi * m.R_cap / s)));
    along = std::max(2, int(std::lround((m.x1_cap - m.x0_cap) / s)));
    const index_t n = index_t(around) * along;
    Zcap.assign(static_cast<std::size_t>(3 * n), 0.0);
    for (int j = 0; j < along; ++j)
      for (int i = 0; i < around; ++i) {
        const index_t q = index_t(j) * around + i;
        const double phi = 2 * pi * (i + 0.5 * (j % 2)) / around;  // staggered rings
        Zcap[q] = m.x0_cap + (m.x1_cap - m.x0_cap) * (j + 0.5) / along;
        Zcap[n + q] = m.R_cap * std::cos(phi);
        Zcap[2 * n + q] = m.R_cap * std::sin(phi);
      }
    Xcap = Zcap;
    Fcap_h.resize(Zcap.size());
    Ucap_h.resize(Zcap.size());
    Xcap_d.resize(Zcap.size());
    Fcap_d.resize(Zcap.size());
    Ucap_d.resize(Zcap.size());
  }

  void make_cell() {
    require(eval != nullptr, "evaluation set", "none", "a run with a cell needs its evaluation sites");
    const cells::ReferenceShape shape = cells::chapter3_red_cell_shape(m.R_cell);
    energies = {mechanics::EnergyDensity::neo_hookean_paper(m.Gs, m.A)};
    if (m.method == chapter3::Method::shvd) {
      cells::CellTypeSpec ts;
      ts.name = "red cell (eq. 92), SHVD m = " + to_text((m.M + 1) * (m.M + 1));
      ts.shape = shape;
      ts.data_sites = chapter3::interpolation_sites(m.M);
      ts.sample_sites = eval->sites;
      ts.interpolant = cells::Interpolant::spherical_harmonics;
      ts.sh_degree = m.M;
      ts.sphere_weights = eval->w;
      ts.model.elastic = energies;
      ts.model.kappa = 2 * m.k_bend;  // E = k_bend int (2H)^2 dA = 2 kappa int H^2 dA
      cells::Placement pl;
      pl.center = m.start;
      batch = std::make_unique<cells::Batch>(std::make_shared<const cells::CellType>(ts),
                                             std::vector<cells::Placement>{pl});
    } else {
      require(m.k_bend == 0, "LDSM k_bend (erg)", m.k_bend,
              "must be 0: LDSM has no bending model (paper Sec. 2.6.3 and 5.1.2)");
      const index_t n = eval->size();
      Zc.assign(static_cast<std::size_t>(3 * n), 0.0);
      for (index_t i = 0; i < n; ++i) {
        double x[3];
        shape.position(eval->sites.lambda[i], eval->sites.theta[i], x);
        for (int d = 0; d < 3; ++d) Zc[d * n + i] = x[d];
      }
      X = Zc;
      for (index_t i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) X[d * n + i] += m.start[d];
      W0 = mechanics::ldsm_area_weights(eval->tris, Zc);
      Uh.resize(X.size());
      Xd.resize(X.size());
      Fd.resize(X.size());
    }
  }

  bool record_due() const { return k % m.record_every == 0 || k == m.steps; }
  bool view_due() const { return k % m.view_every == 0 || k == m.steps; }

  /// The surface state at X^k after the force call (positions, |density|, normals, H).
  View view() const {
    View v;
    v.t = k * m.dt;
    if (m.method == chapter3::Method::shvd) {
      v.X = out.positions.to_host();
      const std::vector<double> D = out.density.to_host();
      const std::size_t n = v.X.size() / 3;
      v.f.resize(n);
      for (std::size_t i = 0; i < n; ++i) v.f[i] = std::sqrt(D[i] * D[i] + D[n + i] * D[n + i] + D[2 * n + i] * D[2 * n + i]);
      const std::vector<surface::Jet> jets =
          surface::jets_from_operators(batch->type().to_sample(), batch->positions_host());
      v.H.resize(n);
      v.normal.resize(3 * n);
      for (std::size_t i = 0; i < n; ++i) {
        const surface::PointGeometry g = surface::point_geometry(jets[i]);
        v.H[i] = g.H;
        for (int d = 0; d < 3; ++d) v.normal[d * n + i] = g.n[d];
      }
    } else {
      v.X = X;
      const std::size_t n = X.size() / 3;
      v.f.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        v.f[i] = std::sqrt(F[i] * F[i] + F[n + i] * F[n + i] + F[2 * n + i] * F[2 * n + i]) / W0[i];
      v.H.assign(n, NAN);
      v.normal = vertex_normals(eval->tris, X);
    }
    return v;
  }

  /// One step from X^k (or, at k = steps, the last record only).
  void step_once() {
    auto t0 = clock_type::now();
    const index_t ncap = index_t(Xcap.size() / 3);
    // 1.-2. forces
    double c[3] = {0, 0, 0}, area = NAN, volume = NAN;
    if (m.with_cell) {
      if (m.method == chapter3::Method::shvd) {
        cells::compute_forces(*batch, out);
        for (int d = 0; d < 3; ++d) c[d] = out.cells.centroid[0][d];
        area = out.cells.area[0];
        volume = out.cells.volume[0];
      } else {
        F = mechanics::ldsm_forces("red cell (LDSM)", eval->tris, Zc, X, energies).F;  // eq. (66)
        polyhedron(eval->tris, X, c, volume, area);
      }
    }
    double cap_disp = 0;
    for (index_t q = 0; q < ncap; ++q) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) {
        const double dx = Xcap[d * ncap + q] - Zcap[d * ncap + q];
        Fcap_h[d * ncap + q] = -m.k_teth * dx;  // eq. (93)
        d2 += dx * dx;
      }
      cap_disp = std::max(cap_disp, std::sqrt(d2));
    }
    const bool rec = record_due();
    if (m.with_cell && view_due()) views.push_back(view());
    double max_density = NAN;
    if (rec && m.with_cell && !views.empty() && views.back().t == k * m.dt)
      max_density = *std::max_element(views.back().f.begin(), views.back().f.end());
    Sample s{k * m.dt, {c[0], c[1], c[2]}, area, volume, {NAN, NAN, NAN}, NAN, cap_disp, max_density};
    if (k == m.steps) {
      if (rec) series.push_back(s);
      return;
    }
    const double t_forces = since(t0);
    // 3. spread: the cell from its n evaluation sites, the capillary nodes, the background force
    t0 = clock_type::now();
    bool spread_any = false;
    if (m.with_cell) {
      if (m.method == chapter3::Method::shvd) {
        ib.sort(ptr(out.positions.storage()), eval->size(), at_eval);
        ib.spread(at_eval, ptr(out.force.storage()), f);
      } else {
        thrust::copy(X.begin(), X.end(), Xd.begin());
        thrust::copy(F.begin(), F.end(), Fd.begin());
        ib.sort(ptr(Xd), eval->size(), at_eval);
        ib.spread(at_eval, ptr(Fd), f);
      }
      spread_any = true;
    }
    thrust::copy(Xcap.begin(), Xcap.end(), Xcap_d.begin());
    thrust::copy(Fcap_h.begin(), Fcap_h.end(), Fcap_d.begin());
    ib.sort(ptr(Xcap_d), ncap, at_cap);
    ib.spread(at_cap, ptr(Fcap_d), f, spread_any);
    add_field(ptr(f[0]), ptr(background), index_t(background.size()));
    phases.spread += since(t0);
    // 4. Stokes
    t0 = clock_type::now();
    stokes.solve(f, u, p);
    phases.solve += since(t0);
    // 5. interpolation
    t0 = clock_type::now();
    ib.interpolate(at_cap, u, ptr(Ucap_d));
    double* Xm = nullptr;
    index_t n_cell = 0;
    if (m.with_cell) {
      if (m.method == chapter3::Method::shvd) {
        n_cell = batch->type().n_data();
        Xm = ptr(batch->state().storage());
        ib.sort(Xm, n_cell, at_interp);
        U.resize(static_cast<std::size_t>(3 * n_cell));
        ib.interpolate(at_interp, u, ptr(U));
      } else {
        n_cell = eval->size();
        U.resize(static_cast<std::size_t>(3 * n_cell));
        ib.interpolate(at_eval, u, ptr(U));
      }
      if (!blas::all_finite(U)) throw NumericalError(Cause::non_finite, "non-finite velocity at the cell's sites");
    }
    if (!blas::all_finite(Ucap_d)) throw NumericalError(Cause::non_finite, "non-finite velocity at the capillary nodes");
    phases.interpolate += since(t0);
    // 6. eqs. (94)-(95) and the cell's update
    t0 = clock_type::now();
    thrust::copy(Ucap_d.begin(), Ucap_d.end(), Ucap_h.begin());
    double uc[3];
    for (int d = 0; d < 3; ++d) {
      double sum = 0;
      for (index_t q = 0; q < ncap; ++q) {
        const std::size_t i = d * ncap + q;
        const double xhat = Xcap[i] + m.dt * Ucap_h[i];  // eq. (94)
        Ucap_h[i] = xhat;
        sum += Zcap[i] - xhat;
      }
      uc[d] = sum / (double(ncap) * m.dt);  // eq. (95) with equal node areas
      for (index_t q = 0; q < ncap; ++q) Xcap[d * ncap + q] = Ucap_h[d * ncap + q] + m.dt * uc[d];
    }
    if (m.with_cell) {
      if (m.method == chapter3::Method::shvd) {
        advance_points(Xm, ptr(U), n_cell, m.dt, uc);
      } else {
        thrust::copy(U.begin(), U.end(), Uh.begin());
        const std::size_t n = X.size() / 3;
        for (std::size_t i = 0; i < X.size(); ++i) X[i] += m.dt * (Uh[i] + uc[i / n]);
      }
    }
    phases.update += since(t0);
    phases.forces += t_forces;
    if (rec) {
      for (int d = 0; d < 3; ++d) s.uc[d] = uc[d];
      s.u_max = *thrust::max_element(u[0].begin(), u[0].end()) + uc[0];
      series.push_back(s);
    }
    last_uc = {uc[0], uc[1], uc[2]};
    ++k;
    ++timed;
  }
  std::array<double, 3> last_uc{0, 0, 0};

  /// The flow of the current state without a cell (a run read back from its checkpoint has not
  /// solved in this process): tether forces, spreading, the background force, the Stokes solve.
  void solve_empty_flow() {
    const index_t ncap = index_t(Xcap.size() / 3);
    for (std::size_t i = 0; i < Xcap.size(); ++i) Fcap_h[i] = -m.k_teth * (Xcap[i] - Zcap[i]);
    thrust::copy(Xcap.begin(), Xcap.end(), Xcap_d.begin());
    thrust::copy(Fcap_h.begin(), Fcap_h.end(), Fcap_d.begin());
    ib.sort(ptr(Xcap_d), ncap, at_cap);
    ib.spread(at_cap, ptr(Fcap_d), f);
    add_field(ptr(f[0]), ptr(background), index_t(background.size()));
    stokes.solve(f, u, p);
  }
};

Run::Run(const Model& model, const chapter3::EvaluationSet* eval) : impl_(std::make_unique<Impl>(model, eval)) {}
Run::~Run() = default;

bool Run::advance(double stop_after_seconds) {
  Impl& s = *impl_;
  const auto t0 = clock_type::now();
  while (!s.finished) {
    try {
      const int k = s.k;
      s.step_once();
      if (k == s.m.steps) s.finished = true;
    } catch (const NumericalError& e) {
      s.failure = "step " + to_text(s.k) + " (t = " + to_text(s.k * s.m.dt) + " s): " + e.what();
      s.finished = true;
    }
    if (since(t0) > stop_after_seconds) break;
  }
  return s.finished;
}

int Run::step() const { return impl_->k; }
bool Run::done() const { return impl_->finished; }
const std::string& Run::failure() const { return impl_->failure; }
const std::vector<Sample>& Run::series() const { return impl_->series; }
const std::vector<View>& Run::views() const { return impl_->views; }
const Phases& Run::phases() const { return impl_->phases; }
int Run::steps_timed() const { return impl_->timed; }
const Model& Run::model() const { return impl_->m; }
const std::vector<double>& Run::capillary_reference() const { return impl_->Zcap; }
int Run::capillary_around() const { return impl_->around; }
int Run::capillary_along() const { return impl_->along; }
const std::vector<surface::Triangle>& Run::triangles() const {
  return impl_->eval ? impl_->eval->tris : impl_->no_tris;
}

std::vector<std::array<double, 2>> Run::profile_x(double x_probe) const {
  Impl& s = *impl_;
  if (s.u[0].empty()) {
    require(!s.m.with_cell, "profile_x", "a run with a cell", "needs the flow of its last step");
    s.solve_empty_flow();
  }
  const double h = s.m.h();
  const int nz = int(std::lround(2 * s.m.L / (h / 2)));
  std::vector<double> P(static_cast<std::size_t>(3 * nz));
  for (int j = 0; j < nz; ++j) {
    P[j] = x_probe;
    P[nz + j] = 0;
    P[2 * nz + j] = -s.m.L + (j + 0.5) * h / 2;
  }
  dvec Pd(P.begin(), P.end()), Ud;
  s.ib.interpolate(Pd, s.u, Ud);
  std::vector<double> Uh(Ud.size());
  thrust::copy(Ud.begin(), Ud.end(), Uh.begin());
  std::vector<std::array<double, 2>> out;
  for (int j = 0; j < nz; ++j) out.push_back({P[2 * nz + j], Uh[j] + s.last_uc[0]});
  return out;
}

void Run::save(const std::string& path, const std::string& label) const {
  const Impl& s = *impl_;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    const std::string head = "rbfib chapter3_capillary checkpoint " + label + "\n";
    f.write(head.data(), std::streamsize(head.size()));
    put(f, double(s.k));
    put(f, double(s.finished));
    const std::string fail = s.failure + "\n";
    f.write(fail.data(), std::streamsize(fail.size()));
    put(f, s.Xcap);
    std::vector<double> cell;
    if (s.batch) {
      cell.resize(s.batch->state().storage().size());
      thrust::copy(s.batch->state().storage().begin(), s.batch->state().storage().end(), cell.begin());
    } else {
      cell = s.X;
    }
    put(f, cell);
    put(f, std::vector<double>{s.last_uc[0], s.last_uc[1], s.last_uc[2]});
    put(f, std::vector<double>{s.phases.forces, s.phases.spread, s.phases.solve, s.phases.interpolate,
                               s.phases.update, double(s.timed)});
    std::vector<double> ser;
    for (const Sample& x : s.series) {
      ser.insert(ser.end(), {x.t, x.c[0], x.c[1], x.c[2], x.area, x.volume, x.uc[0], x.uc[1], x.uc[2], x.u_max,
                             x.cap_disp, x.max_density});
    }
    put(f, ser);
    put(f, double(s.views.size()));
    for (const View& v : s.views) {
      put(f, v.t);
      put(f, v.X);
      put(f, v.f);
      put(f, v.H);
      put(f, v.normal);
    }
    if (!f) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

bool Run::load(const std::string& path, const std::string& label) {
  Impl& s = *impl_;
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::string head, fail;
  std::getline(f, head);
  if (head != "rbfib chapter3_capillary checkpoint " + label) return false;
  double k, fin;
  if (!get(f, k) || !get(f, fin) || !std::getline(f, fail)) return false;
  std::vector<double> xcap, cell, uc, ph, ser;
  if (!get(f, xcap) || !get(f, cell) || !get(f, uc) || !get(f, ph) || !get(f, ser) || xcap.size() != s.Xcap.size() ||
      uc.size() != 3 || ph.size() != 6)
    return false;
  if (s.batch) {
    if (cell.size() != s.batch->state().storage().size()) return false;
    thrust::copy(cell.begin(), cell.end(), s.batch->state().storage().begin());
  } else {
    if (cell.size() != s.X.size()) return false;
    s.X = cell;
  }
  s.Xcap = xcap;
  s.k = int(k);
  s.finished = fin != 0;
  s.failure = fail;
  s.last_uc = {uc[0], uc[1], uc[2]};
  s.phases = Phases{ph[0], ph[1], ph[2], ph[3], ph[4]};
  s.timed = int(ph[5]);
  s.series.clear();
  for (std::size_t i = 0; i + 12 <= ser.size(); i += 12) {
    const double* r = &ser[i];
    s.series.push_back(Sample{r[0], {r[1], r[2], r[3]}, r[4], r[5], {r[6], r[7], r[8]}, r[9], r[10], r[11]});
  }
  double nv;
  if (!get(f, nv)) return false;
  s.views.clear();
  for (int i = 0; i < int(nv); ++i) {
    View v;
    if (!get(f, v.t) || !get(f, v.X) || !get(f, v.f) || !get(f, v.H) || !get(f, v.normal)) return false;
    s.views.push_back(std::move(v));
  }
  return true;
}

}  // namespace rbfib::capillary
