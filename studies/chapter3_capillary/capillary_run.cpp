#include "capillary_run.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/cells/shapes.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/fluid/fluid_step.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/surface/geometry.hpp"

#include <thrust/copy.h>
#include <thrust/extrema.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace rbfib::capillary {

namespace {

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

}  // namespace

const char* to_string(Region r) { return r == Region::core ? "core" : "segment"; }

struct Run::Impl {
  Model m;
  const chapter3::EvaluationSet* eval;
  int around = 0, along = 0;
  std::vector<double> Zcap;            // the capillary's reference nodes (cm), 3 n_cap
  std::vector<double> Zc, W0;          // LDSM: reference vertices and their area weights
  std::vector<mechanics::EnergyDensity> energies;
  std::optional<run::Run> loop;
  std::vector<surface::Triangle> no_tris;
  // what the accessors give, rebuilt from the run's series after each advance
  std::vector<Sample> samples;
  std::vector<View> kept_views;
  Phases phase_sums;

  static MacGrid make_grid(const Model& m) {
    require(m.eta >= 8, "grid size eta", m.eta, "must be >= 8");
    require(m.L > 0, "half box L (cm)", m.L, "must be > 0");
    MacGrid g = make_mac_grid(3, {m.eta, m.eta, m.eta}, {2 * m.L, 2 * m.L, 2 * m.L},
                              {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
    g.origin = {-m.L, -m.L, -m.L};
    return g;
  }

  Impl(const Model& model, const chapter3::EvaluationSet* e, const std::string& checkpoint, double sitting)
      : m(model), eval(e) {
    require(m.mu > 0, "viscosity mu (P)", m.mu, "must be > 0");
    require(m.dt > 0, "time step dt (s)", m.dt, "must be > 0");
    require(m.steps >= 0, "steps", m.steps, "must be >= 0");
    require(m.R_cap > 0 && m.R_cap < m.L, "capillary radius (cm)", m.R_cap, "must lie in (0, L)");
    require(m.k_teth >= 0, "k_teth (dyn/cm)", m.k_teth, "must be >= 0");
    require(m.k_bend >= 0, "k_bend (erg)", m.k_bend, "must be >= 0");
    require(m.record_every > 0, "record_every", m.record_every, "must be > 0");
    require(m.view_every > 0, "view_every", m.view_every, "must be > 0");
    // The coupled step of Sec. 3.3 with eqs. (94)-(95): steady Stokes, forward Euler, the
    // background force after the spread forces, the capillary's nodes holding the frame.
    auto fluid = std::make_unique<PeriodicStokesStep>(make_grid(m), FluidParameters{1.0, m.mu}, m.dt, true);
    sim::IbOptions o;
    o.coupling = sim::Coupling::forward_euler;
    o.kernel = m.kernel;
    o.stopping_condition = false;
    o.body_force_density = background(fluid->operators());
    sim::ImmersedBoundary ib(std::move(fluid), o);
    if (m.with_cell) add_cell(ib);
    add_capillary(ib);
    run::Options ro;
    ro.t_end = m.steps * m.dt;
    ro.checkpoint = checkpoint;
    ro.sitting = sitting;
    ro.sample_every = run::Cadence{};  // the hooks record at their own steps
    run::Hooks hooks;
    hooks.after_step = [this](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& s) {
      after_step(ib, r, s);
    };
    loop.emplace(describe(), std::move(ib), ro, std::move(hooks));
    collect();
  }

  /// The setup as text: what a checkpoint must match.
  std::string describe() const {
    std::string d = "chapter3_capillary run\n";
    for (double x : {m.L, double(m.eta), m.mu, m.f_in, double(int(m.region)), m.R_cap, m.x0_cap, m.x1_cap, m.k_teth,
                     m.cap_spacing, double(m.with_cell), double(int(m.method)), double(m.M), m.R_cell, m.Gs, m.A, m.k_bend,
                     m.start[0], m.start[1], m.start[2], m.dt, double(m.steps), double(m.record_every), double(m.view_every),
                     double(int(m.kernel))})
      d += to_text(x) + "\n";
    if (eval) d += eval->family + " " + to_text(eval->size()) + "\n";
    return d;
  }

  /// The background force on the x-faces: f_in inside the region, f_out elsewhere, zero sum.
  VectorField background(const MacOperators& ops) const {
    const Box& b = ops.component_box(0);
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
    return {dvec(bg.begin(), bg.end()), dvec(ops.component_box(1).size(), 0.0), dvec(ops.component_box(2).size(), 0.0)};
  }

  /// Nodes on the cylinder at the centres of equal patches, `around` x `along` of them, tethered
  /// by eq. (93) and holding the frame (eqs. 94-95).
  void add_capillary(sim::ImmersedBoundary& ib) {
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
    sim::TetheredPoints cap{"capillary", dvec(Zcap.begin(), Zcap.end()), dvec(Zcap.begin(), Zcap.end()), m.k_teth, 0.0};
    cap.frame = true;
    ib.add(std::move(cap));
  }

  void add_cell(sim::ImmersedBoundary& ib) {
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
      ib.add(cells::Batch(std::make_shared<const cells::CellType>(ts), std::vector<cells::Placement>{pl}));
      return;
    }
    require(m.k_bend == 0, "LDSM k_bend (erg)", m.k_bend, "must be 0: LDSM has no bending model (paper Sec. 2.6.3 and 5.1.2)");
    const index_t n = eval->size();
    Zc.assign(static_cast<std::size_t>(3 * n), 0.0);
    for (index_t i = 0; i < n; ++i) {
      double x[3];
      shape.position(eval->sites.lambda[i], eval->sites.theta[i], x);
      for (int d = 0; d < 3; ++d) Zc[d * n + i] = x[d];
    }
    std::vector<double> X = Zc;
    for (index_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) X[d * n + i] += m.start[d];
    W0 = mechanics::ldsm_area_weights(eval->tris, Zc);
    ib.add(sim::LdsmShell{"red cell (LDSM)", eval->tris, Zc, X, energies});
  }

  bool record_due(long k) const { return k % m.record_every == 0 || k == m.steps; }
  bool view_due(long k) const { return k % m.view_every == 0 || k == m.steps; }

  /// After step k - 1 (or at the start, r null): the step's frame velocity and peak flow go into
  /// the row recorded at X^{k-1}; then X^k is measured when due (a force call of its own, the same
  /// as the step's: the forces of Sec. 3.3 act at X^k).
  void after_step(const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, run::SeriesSet& s) {
    const long k = ib.step_count();
    if (r) {
      std::vector<std::vector<double>>& rows = s["samples"].rows;
      if (!rows.empty() && std::abs(rows.back()[0] - (k - 1) * m.dt) <= 1e-9 * m.dt) {
        std::vector<double>& row = rows.back();
        const dvec& u0 = ib.fluid_state().u[0];
        for (int d = 0; d < 3; ++d) row[6 + d] = r->frame_velocity[d];
        row[9] = *thrust::max_element(u0.begin(), u0.end()) + r->frame_velocity[0];
      }
      s["frame"].rows = {{r->frame_velocity[0], r->frame_velocity[1], r->frame_velocity[2]}};
      auto& ph = s["phases"].rows;
      if (ph.empty()) ph = {std::vector<double>(5, 0.0)};
      const double add[5] = {r->seconds_forces, r->seconds_spreading, r->seconds_fluid, r->seconds_interpolation,
                             r->seconds_update};
      for (int i = 0; i < 5; ++i) ph[0][i] += add[i];
    }
    if (!record_due(k) && !view_due(k)) return;
    double c[3] = {0, 0, 0}, area = NAN, volume = NAN, max_density = NAN;
    View v;
    v.t = k * m.dt;
    if (m.with_cell) {
      if (m.method == chapter3::Method::shvd) {
        const cells::Batch& batch = ib.batch(0);
        cells::CellForces out;
        cells::compute_forces(batch, out);
        for (int d = 0; d < 3; ++d) c[d] = out.cells.centroid[0][d];
        area = out.cells.area[0];
        volume = out.cells.volume[0];
        if (view_due(k)) shvd_view(batch, out, v);
      } else {
        const std::vector<double>& X = ib.shell(0).shell().X;
        const surface::PolyhedronMeasures pm = surface::polyhedron_measures(eval->tris, X);
        volume = pm.volume;
        area = pm.area;
        for (int d = 0; d < 3; ++d) c[d] = pm.centroid[d];
        if (view_due(k)) ldsm_view(X, mechanics::ldsm_forces("red cell (LDSM)", eval->tris, Zc, X, energies).F, v);
      }
      if (view_due(k)) {
        max_density = *std::max_element(v.f.begin(), v.f.end());
        std::vector<double> row{v.t, double(v.f.size())};
        for (const std::vector<double>* part : {&v.X, &v.f, &v.H, &v.normal}) row.insert(row.end(), part->begin(), part->end());
        s["views"].rows.push_back(std::move(row));
      }
    }
    if (!record_due(k)) return;
    const std::vector<double> X(ib.points(0).X.begin(), ib.points(0).X.end());
    const std::size_t ncap = X.size() / 3;
    double cap_disp = 0;
    for (std::size_t q = 0; q < ncap; ++q) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += (X[d * ncap + q] - Zcap[d * ncap + q]) * (X[d * ncap + q] - Zcap[d * ncap + q]);
      cap_disp = std::max(cap_disp, std::sqrt(d2));
    }
    s["samples"].columns = {"t (s)", "cx (cm)", "cy (cm)", "cz (cm)", "area (cm^2)", "volume (cm^3)", "ucx (cm/s)",
                            "ucy (cm/s)", "ucz (cm/s)", "u_max (cm/s)", "cap_disp (cm)", "max_density (dyn/cm^2)"};
    s["samples"].rows.push_back({v.t, c[0], c[1], c[2], area, volume, NAN, NAN, NAN, NAN, cap_disp, max_density});
  }

  /// The SHVD surface at its n evaluation sites: positions, |density|, normals and H.
  void shvd_view(const cells::Batch& batch, const cells::CellForces& out, View& v) const {
    v.X = out.positions.to_host();
    const std::vector<double> D = out.density.to_host();
    const std::size_t n = v.X.size() / 3;
    v.f.resize(n);
    for (std::size_t i = 0; i < n; ++i) v.f[i] = std::sqrt(D[i] * D[i] + D[n + i] * D[n + i] + D[2 * n + i] * D[2 * n + i]);
    const std::vector<surface::Jet> jets = surface::jets_from_operators(batch.type().to_sample(), batch.positions_host());
    v.H.resize(n);
    v.normal.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const surface::PointGeometry g = surface::point_geometry(jets[i]);
      v.H[i] = g.H;
      for (int d = 0; d < 3; ++d) v.normal[d * n + i] = g.n[d];
    }
  }

  /// The LDSM surface at its vertices: positions, |force| over the area weight, vertex normals.
  void ldsm_view(const std::vector<double>& X, const std::vector<double>& F, View& v) const {
    v.X = X;
    const std::size_t n = X.size() / 3;
    v.f.resize(n);
    for (std::size_t i = 0; i < n; ++i) v.f[i] = std::sqrt(F[i] * F[i] + F[n + i] * F[n + i] + F[2 * n + i] * F[2 * n + i]) / W0[i];
    v.H.assign(n, NAN);
    v.normal = vertex_normals(eval->tris, X);
  }

  /// The accessors' copies of the run's series.
  void collect() {
    const run::SeriesSet& s = loop->series();
    samples.clear();
    kept_views.clear();
    phase_sums = Phases{};
    if (auto it = s.find("samples"); it != s.end())
      for (const std::vector<double>& r : it->second.rows)
        samples.push_back(Sample{r[0], {r[1], r[2], r[3]}, r[4], r[5], {r[6], r[7], r[8]}, r[9], r[10], r[11]});
    if (auto it = s.find("views"); it != s.end())
      for (const std::vector<double>& r : it->second.rows) {
        View v;
        v.t = r[0];
        const std::size_t n = std::size_t(r[1]);
        auto part = [&](std::size_t from, std::size_t count) {
          return std::vector<double>(r.begin() + std::ptrdiff_t(2 + from), r.begin() + std::ptrdiff_t(2 + from + count));
        };
        v.X = part(0, 3 * n);
        v.f = part(3 * n, n);
        v.H = part(4 * n, n);
        v.normal = part(5 * n, 3 * n);
        kept_views.push_back(std::move(v));
      }
    if (auto it = s.find("phases"); it != s.end() && !it->second.rows.empty()) {
      const std::vector<double>& p = it->second.rows[0];
      phase_sums = Phases{p[0], p[1], p[2], p[3], p[4]};
    }
  }
};

Run::Run(const Model& model, const chapter3::EvaluationSet* eval, const std::string& checkpoint, double sitting)
    : impl_(std::make_unique<Impl>(model, eval, checkpoint, sitting)) {}
Run::~Run() = default;

bool Run::advance() {
  impl_->loop->evolve();
  impl_->collect();
  return done();
}

int Run::step() const { return int(impl_->loop->ib().step_count()); }
bool Run::done() const { return impl_->loop->progress().ended(); }
std::string Run::failure() const { return impl_->loop->progress().stop_message; }
bool Run::continued() const { return impl_->loop->continued(); }
const std::vector<Sample>& Run::series() const { return impl_->samples; }
const std::vector<View>& Run::views() const { return impl_->kept_views; }
const Phases& Run::phases() const { return impl_->phase_sums; }
int Run::steps_timed() const { return int(impl_->loop->progress().steps_timed); }
const Model& Run::model() const { return impl_->m; }
const std::vector<double>& Run::capillary_reference() const { return impl_->Zcap; }
int Run::capillary_around() const { return impl_->around; }
int Run::capillary_along() const { return impl_->along; }
const std::vector<surface::Triangle>& Run::triangles() const {
  return impl_->eval ? impl_->eval->tris : impl_->no_tris;
}

std::vector<std::array<double, 2>> Run::profile_x(double x_probe) const {
  const Impl& s = *impl_;
  const sim::ImmersedBoundary& ib = s.loop->ib();
  require(ib.step_count() > 0, "profile_x", "a run at step 0", "needs the flow of a step");
  const run::SeriesSet& series = s.loop->series();
  const auto frame = series.find("frame");
  const double ucx = frame == series.end() || frame->second.rows.empty() ? 0.0 : frame->second.rows[0][0];
  const double h = s.m.h();
  const int nz = int(std::lround(2 * s.m.L / (h / 2)));
  std::vector<double> P(static_cast<std::size_t>(3 * nz));
  for (int j = 0; j < nz; ++j) {
    P[j] = x_probe;
    P[nz + j] = 0;
    P[2 * nz + j] = -s.m.L + (j + 0.5) * h / 2;
  }
  dvec Pd(P.begin(), P.end()), Ud;
  ib::Interaction probe({ib.fluid().operators().component_box(0), ib.fluid().operators().component_box(1),
                         ib.fluid().operators().component_box(2)},
                        s.m.kernel);
  probe.interpolate(Pd, ib.fluid_state().u, Ud);
  std::vector<double> Uh(Ud.size());
  thrust::copy(Ud.begin(), Ud.end(), Uh.begin());
  std::vector<std::array<double, 2>> out;
  for (int j = 0; j < nz; ++j) out.push_back({P[2 * nz + j], Uh[j] + ucx});
  return out;
}

}  // namespace rbfib::capillary
